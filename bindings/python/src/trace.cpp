// hitray._core.trace: Hill's getFirstHit for N rays at once, over N x 3
// numpy arrays, with the GIL released and the rays split over threads.
// A miss gives t = inf, normal (0, 0, 0) and object -1.
//
// Beyond a few thousand rays the calling thread traces none itself: it
// waits, taking the GIL every POLL_MS to run Python's signal handlers (only
// the main thread runs them), so Ctrl-C stops a long trace within a fraction
// of a second and raises KeyboardInterrupt itself. The rays are handed out
// in blocks through an atomic counter, and every thread stops at the next
// block once a ray failed or the trace was interrupted.
#include "scene_handle.h"

#include <pybind11/numpy.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace hitray_py {

namespace {

using rays_array = py::array_t<double, py::array::c_style | py::array::forcecast>;

constexpr int POLL_MS = 50;
// Rays per block handed to a thread: small enough that a stop is seen soon.
constexpr int64_t BLOCK = 1024;
// Fewer rays than this are traced on the calling thread, as one block.
constexpr int64_t MIN_PARALLEL = 4096;

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
    int64_t count = 0;
    std::atomic<int64_t> next_block{0};
    std::atomic<bool> interrupted{false};
    // The waiting thread sleeps on this until every worker is done.
    std::mutex lock;
    std::condition_variable finished;
    int running = 0;
};

void trace_range(TraceJob *job, int64_t begin, int64_t end)
{
    for (int64_t i = begin; i < end; i++) {
        if (job->failed_ray.load(std::memory_order_relaxed) >= 0 ||
            job->interrupted.load(std::memory_order_relaxed))
            return;
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

// A worker: blocks of rays until none is left or the trace stops.
void trace_blocks(TraceJob *job)
{
    for (;;) {
        int64_t begin = job->next_block.fetch_add(BLOCK);
        if (begin >= job->count || job->failed_ray.load() >= 0 || job->interrupted.load()) break;
        trace_range(job, begin, std::min(job->count, begin + BLOCK));
    }
    std::lock_guard<std::mutex> guard(job->lock);
    job->running--;
    job->finished.notify_one();
}

// Run `workers` threads over the job while this thread, GIL released,
// wakes every POLL_MS to let Python run its signal handlers. Returns false
// with the Python exception pending if one was raised (Ctrl-C).
bool run_workers(TraceJob *job, int64_t workers)
{
    std::vector<std::thread> pool;
    bool ok = true;
    PyObject *type = nullptr, *value = nullptr, *tb = nullptr;
    {
        py::gil_scoped_release release;
        for (int64_t w = 0; w < workers; w++) {
            {
                std::lock_guard<std::mutex> guard(job->lock);
                job->running++;
            }
            try {
                pool.emplace_back(trace_blocks, job);
            } catch (const std::system_error &) {
                std::lock_guard<std::mutex> guard(job->lock);
                job->running--;
                break;
            }
        }
        if (pool.empty()) {  // no thread to be had: trace here, unpolled
            {
                std::lock_guard<std::mutex> guard(job->lock);
                job->running++;
            }
            trace_blocks(job);
        }
        std::unique_lock<std::mutex> guard(job->lock);
        while (job->running > 0) {
            job->finished.wait_for(guard, std::chrono::milliseconds(POLL_MS));
            if (job->running == 0 || !ok) continue;
            guard.unlock();
            {
                py::gil_scoped_acquire acquire;
                if (PyErr_CheckSignals() != 0) {
                    ok = false;
                    job->interrupted.store(true);
                    PyErr_Fetch(&type, &value, &tb);
                }
            }
            guard.lock();
        }
        guard.unlock();
        for (auto &th : pool) th.join();
    }
    if (!ok) PyErr_Restore(type, value, tb);
    return ok;
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
    job.count = n;
    if (n < MIN_PARALLEL) {
        // Below a few thousand rays a thread costs more than it saves.
        py::gil_scoped_release release;
        trace_range(&job, 0, n);
    } else {
        int64_t workers = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
        workers = std::max<int64_t>(1, std::min<int64_t>(workers, n / MIN_PARALLEL));
        if (!run_workers(&job, workers)) throw py::error_already_set();
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
