// Statuses to exceptions: the library's message (and, for scene files, the
// file, line and column) become a hitray.Error subclass chosen by
// hitray.errors._from_status, so the mapping lives in one Python place.
#include "core.h"

namespace hitray_py {

ErrorReport capture_error(hr_status status)
{
    ErrorReport report;
    report.status = status;
    hr_error_info info{};
    info.struct_size = sizeof info;
    if (hr_context_last_error_info(context(), &info) == HR_OK && info.status == status &&
        info.message && *info.message) {
        report.message = info.message;
        report.file = info.file ? info.file : "";
        report.line = info.line;
        report.column = info.column;
    } else {
        report.message = hr_status_name(status);
    }
    return report;
}

void raise_error(const ErrorReport &report)
{
    py::object make = py::module_::import("hitray.errors").attr("_from_status");
    py::object file = report.file.empty() ? py::object(py::none()) : py::object(path_text(report.file));
    py::object exc = make(report.status, text(report.message), file, report.line, report.column);
    PyErr_SetObject(reinterpret_cast<PyObject *>(Py_TYPE(exc.ptr())), exc.ptr());
    throw py::error_already_set();
}

void raise_error(hr_status status, const std::string &message)
{
    ErrorReport report;
    report.status = status;
    report.message = message;
    raise_error(report);
}

}  // namespace hitray_py
