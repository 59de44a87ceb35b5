// hitray._core.render: hr_render on a thread of its own while the calling
// thread waits with the GIL released. Every POLL_MS, and whenever a tile
// finishes, the waiting thread takes the GIL briefly to run Python's signal
// handlers (Ctrl-C raises KeyboardInterrupt there: only the main thread runs
// them, which is why the render cannot run on the caller's thread) and to
// report progress; an exception from either cancels the render through its
// progress callback, the render thread is joined, and the exception is
// raised. So two Python threads can render at once, and Ctrl-C stops a
// render cleanly: the flag hr_render_options.cancel is read before every ray,
// so even a render stuck in a slow Python shape stops within one ray per
// thread.
#include "image_handle.h"
#include "scene_handle.h"

#include <pybind11/stl.h>

#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>

namespace hitray_py {

namespace {

constexpr int POLL_MS = 50;

struct RenderRun {
    // In: what hr_render needs.
    const hr_scene *scene = nullptr;
    hr_camera camera{};
    hr_render_options options{};
    // Out: filled by the render thread.
    int32_t query_nesting = 0;  // the calling thread's (hr_query_nesting)
    hr_image *image = nullptr;
    hr_render_stats stats{};
    hr_status status = HR_OK;
    ErrorReport failure;
    // Between the threads.
    std::mutex lock;
    std::condition_variable changed;
    bool done = false;
    std::atomic<double> fraction{0.0};
    std::atomic<int32_t> cancel{0};  // what on_progress answers
    int32_t cancel_flag = 0;          // hr_render_options.cancel: read before every ray
};

int32_t on_progress(void *user, double fraction)
{
    auto *run = static_cast<RenderRun *>(user);
    run->fraction.store(fraction);
    run->changed.notify_one();
    return run->cancel.load();
}

void render_thread(RenderRun *run)
{
    run->stats.struct_size = sizeof run->stats;
    // This thread renders for the caller: a render from inside a shape's
    // hit nests as deep as that hit is.
    hr_query_set_nesting(run->query_nesting);
    hr_status st = hr_render(run->scene, &run->camera, &run->options, &run->image, &run->stats);
    if (st != HR_OK) run->failure = capture_error(st);  // this thread's error slot
    std::lock_guard<std::mutex> guard(run->lock);
    run->status = st;
    run->done = true;
    run->changed.notify_one();
}

// One look at Python from the waiting thread (GIL held): signals, then the
// progress callback if the fraction moved. False: an exception is pending.
bool poll_python(const py::object &progress, double fraction, double &reported)
{
    if (PyErr_CheckSignals() != 0) return false;
    if (!progress.is_none() && fraction != reported) {
        reported = fraction;
        // Nothing may escape from here: the render thread is still running
        // and must be joined, so every failure becomes a pending exception.
        try {
            progress(fraction);
        } catch (py::error_already_set &e) {
            e.restore();
            return false;
        } catch (const std::exception &e) {
            PyErr_SetString(PyExc_RuntimeError, e.what());
            return false;
        }
    }
    return true;
}

py::object render(const ScenePtr &s, const py::tuple &cam, int32_t width, int32_t height, int32_t spp,
                  int32_t threads, int32_t depth, int32_t block_size, bool all_effects,
                  double adaptive, double min_weight, bool exact, const std::array<int32_t, 4> &window,
                  int32_t texture_filter, const py::object &progress)
{
    auto run = std::make_unique<RenderRun>();
    run->scene = committed_scene(s);
    if (cam.size() != 4) throw py::value_error("camera: expected (eye, look, up, angle)");
    run->camera = camera_from(cam[0].cast<vec3>(), cam[1].cast<vec3>(), cam[2].cast<vec3>(),
                              cam[3].cast<double>(), width, height);
    hr_render_options_default(&run->options);
    run->options.width = width;
    run->options.height = height;
    run->options.samples_per_pixel = spp;
    run->options.threads = threads;
    run->options.max_depth = depth;
    run->options.block_size = block_size;
    run->options.effects = all_effects ? HR_EFFECTS_ALL : HR_EFFECTS_AUTO;
    run->options.adaptive_threshold = adaptive;
    run->options.min_weight = min_weight;
    run->options.exact = exact ? 1 : 0;
    run->options.window_x = window[0];
    run->options.window_y = window[1];
    run->options.window_width = window[2];
    run->options.window_height = window[3];
    run->options.texture_filter = texture_filter;
    run->options.progress = on_progress;
    run->options.progress_user = run.get();
    run->options.cancel = &run->cancel_flag;
    run->query_nesting = hr_query_nesting();

    double reported = -1.0;
    bool interrupted = false;
    PyObject *exc_type = nullptr, *exc_value = nullptr, *exc_tb = nullptr;
    std::thread worker;
    try {
        worker = std::thread(render_thread, run.get());
    } catch (const std::system_error &) {
        raise_error(HR_ERROR_OUT_OF_MEMORY, "render: cannot start a thread");
    }
    {
        py::gil_scoped_release release;
        std::unique_lock<std::mutex> guard(run->lock);
        while (!run->done) {
            run->changed.wait_for(guard, std::chrono::milliseconds(POLL_MS));
            if (run->done || interrupted) continue;
            double fraction = run->fraction.load();
            guard.unlock();
            {
                py::gil_scoped_acquire acquire;
                if (!poll_python(progress, fraction, reported)) {
                    interrupted = true;
                    run->cancel.store(1);
                    __atomic_store_n(&run->cancel_flag, 1, __ATOMIC_RELAXED);
                    PyErr_Fetch(&exc_type, &exc_value, &exc_tb);
                }
            }
            guard.lock();
        }
        guard.unlock();
        worker.join();
    }
    if (interrupted) {
        hr_image_destroy(run->image);
        PyErr_Restore(exc_type, exc_value, exc_tb);
        throw py::error_already_set();
    }
    if (run->status != HR_OK) raise_error(run->failure);
    // The last tick (1.0) may have come after the last poll.
    double fraction = run->fraction.load();
    if (!poll_python(progress, fraction, reported)) {
        hr_image_destroy(run->image);
        throw py::error_already_set();
    }
    auto image = std::make_shared<ImageHandle>(run->image);
    image->stats = run->stats;
    image->has_stats = true;
    return py::cast(image);
}

}  // namespace

void bind_render(py::module_ &m)
{
    m.def("render", &render, py::arg("scene"), py::arg("camera"), py::arg("width"), py::arg("height"),
          py::arg("spp"), py::arg("threads"), py::arg("depth"), py::arg("block_size"),
          py::arg("all_effects"), py::arg("adaptive"), py::arg("min_weight"), py::arg("exact"),
          py::arg("window"), py::arg("texture_filter"), py::arg("progress"));
}

}  // namespace hitray_py
