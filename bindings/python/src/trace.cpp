// hitray._core.trace: Hill's getFirstHit for N rays at once, over N x 3
// numpy arrays, with the GIL released and the rays split over threads.
// A miss gives t = inf, normal (0, 0, 0) and object -1.
#include "scene_handle.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>
#include <vector>

namespace hitray_py {

namespace {

using rays_array = py::array_t<double, py::array::c_style | py::array::forcecast>;

struct TraceJob {
    const hr_scene *scene;
    const double *origins;
    const double *directions;
    double tmin, tmax;
    double *t;
    double *normal;
    int64_t *object;
    // The first ray that failed (its index), so the error names it; the
    // error itself is read on the thread that met it.
    std::atomic<int64_t> failed_ray{-1};
    ErrorReport failure;
    std::atomic_flag failure_taken = ATOMIC_FLAG_INIT;
};

void trace_range(TraceJob *job, int64_t begin, int64_t end)
{
    for (int64_t i = begin; i < end; i++) {
        if (job->failed_ray.load(std::memory_order_relaxed) >= 0) return;
        const double *o = job->origins + 3 * i, *d = job->directions + 3 * i;
        hr_ray ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
        hr_hit hit{};
        int32_t found = 0;
        hr_status st = hr_scene_first_hit(job->scene, &ray, job->tmin, job->tmax, &hit, &found);
        if (st != HR_OK) {
            if (!job->failure_taken.test_and_set()) {
                job->failure = capture_error(st);
                job->failed_ray.store(i);
            }
            return;
        }
        double *n = job->normal + 3 * i;
        if (found) {
            job->t[i] = hit.t;
            n[0] = hit.normal.x, n[1] = hit.normal.y, n[2] = hit.normal.z;
            job->object[i] = hit.object;
        } else {
            job->t[i] = INFINITY;
            n[0] = n[1] = n[2] = 0.0;
            job->object[i] = -1;
        }
    }
}

py::tuple trace(const ScenePtr &s, const rays_array &origins, const rays_array &directions, double tmin,
                double tmax, int threads)
{
    const hr_scene *scene = committed_scene(s);
    if (origins.ndim() != 2 || origins.shape(1) != 3)
        throw py::value_error("trace: origins must be an N x 3 array");
    if (directions.ndim() != 2 || directions.shape(1) != 3)
        throw py::value_error("trace: directions must be an N x 3 array");
    if (origins.shape(0) != directions.shape(0))
        throw py::value_error("trace: origins and directions must have the same number of rows");
    if (threads < 0) throw py::value_error("trace: threads must be positive (0: every core)");
    const int64_t n = origins.shape(0);
    py::array_t<double> t(n);
    py::array_t<double> normal({n, static_cast<int64_t>(3)});
    py::array_t<int64_t> object(n);

    TraceJob job;
    job.scene = scene;
    job.origins = origins.data();
    job.directions = directions.data();
    job.tmin = tmin;
    job.tmax = tmax;
    job.t = t.mutable_data();
    job.normal = normal.mutable_data();
    job.object = object.mutable_data();
    {
        py::gil_scoped_release release;
        int64_t workers = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
        // Below a few thousand rays a thread costs more than it saves.
        workers = std::max<int64_t>(1, std::min<int64_t>(workers, n / 4096));
        std::vector<std::thread> pool;
        int64_t chunk = (n + workers - 1) / workers;
        try {
            for (int64_t w = 1; w < workers; w++)
                pool.emplace_back(trace_range, &job, std::min(n, w * chunk), std::min(n, (w + 1) * chunk));
        } catch (const std::system_error &) {
            // No thread to be had: the calling thread does the rest.
            int64_t done = static_cast<int64_t>(pool.size() + 1) * chunk;
            trace_range(&job, std::min(n, done), n);
        }
        trace_range(&job, 0, std::min(n, chunk));
        for (auto &th : pool) th.join();
    }
    int64_t bad = job.failed_ray.load();
    if (bad >= 0) {
        job.failure.message = "ray " + std::to_string(bad) + ": " + job.failure.message;
        raise_error(job.failure);
    }
    return py::make_tuple(t, normal, object);
}

}  // namespace

void bind_trace(py::module_ &m)
{
    m.def("trace", &trace, py::arg("scene"), py::arg("origins"), py::arg("directions"), py::arg("tmin"),
          py::arg("tmax"), py::arg("threads"));
}

}  // namespace hitray_py
