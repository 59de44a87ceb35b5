// hitray._core.trace: Hill's getFirstHit for N rays at once, over N x 3
// numpy arrays, with the GIL released and the rays split over threads, each
// thread handing its rays to the batch query (hr_scene_first_hits) a
// piece at a time. A miss gives t = inf, normal (0, 0, 0) and object -1;
// with `full`, the point (0, 0, 0), surface -1, entering False and error 0
// too. hitray._core.occluded: hr_scene_occluded the same way.
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
    // First hits: t, normal and object, and with `full` the rest (else
    // NULL); occlusion (t NULL): blocked alone.
    double *t = nullptr;
    double *normal = nullptr;
    int64_t *object = nullptr;
    double *point = nullptr;
    int32_t *surface = nullptr;
    bool *entering = nullptr;
    double *error = nullptr;
    bool *blocked = nullptr;
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

// The rays a batch call takes at a time (on the stack).
constexpr int64_t PIECE = 256;

// Ray `i` alone, to name it in the error when its piece's batch failed:
// the single query's own message, as before batches (the batch checks
// every ray first, so the first one the single query refuses is the one).
bool find_failure(TraceJob *job, const hr_ray *rays, int64_t begin, int64_t count)
{
    for (int64_t k = 0; k < count; k++) {
        hr_hit hit{};
        int32_t found = 0;
        hr_status st = hr_scene_first_hit(job->scene, &rays[k], job->tmin, job->tmax, &hit, &found);
        if (st != HR_OK) {
            if (!job->failure_taken.test_and_set()) {
                job->failure = capture_error(st);
                job->failed_ray.store(begin + k);
            }
            return true;
        }
    }
    return false;
}

void store_hit(TraceJob *job, int64_t i, const hr_hit &hit, bool found)
{
    double *n = job->normal + 3 * i;
    job->t[i] = found ? hit.t : INFINITY;
    n[0] = found ? hit.normal.x : 0.0, n[1] = found ? hit.normal.y : 0.0, n[2] = found ? hit.normal.z : 0.0;
    job->object[i] = found ? hit.object : -1;
    if (!job->point) return;
    double *p = job->point + 3 * i;
    p[0] = found ? hit.point.x : 0.0, p[1] = found ? hit.point.y : 0.0, p[2] = found ? hit.point.z : 0.0;
    job->surface[i] = found ? hit.surface : -1;
    job->entering[i] = found && hit.entering != 0;
    job->error[i] = found ? hit.error : 0.0;
}

void trace_range(TraceJob *job, int64_t begin, int64_t end)
{
    hr_ray rays[PIECE];
    hr_hit hits[PIECE];
    int32_t found[PIECE];
    for (int64_t at = begin; at < end; at += PIECE) {
        if (job->failed_ray.load(std::memory_order_relaxed) >= 0 ||
            job->interrupted.load(std::memory_order_relaxed))
            return;
        const int64_t count = std::min(PIECE, end - at);
        for (int64_t k = 0; k < count; k++) {
            const double *o = job->origins + 3 * (at + k), *d = job->directions + 3 * (at + k);
            rays[k] = hr_ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}};
        }
        hr_status st = job->t ? hr_scene_first_hits(job->scene, rays, count, job->tmin, job->tmax, hits, found)
                              : hr_scene_occluded(job->scene, rays, count, job->tmin, job->tmax, found);
        if (st != HR_OK) {
            // A bad ray (named by the single query), else a shape's failure.
            if (!find_failure(job, rays, at, count) && !job->failure_taken.test_and_set()) {
                job->failure = capture_error(st);
                job->failed_ray.store(at);
            }
            return;
        }
        for (int64_t k = 0; k < count; k++) {
            if (job->t) store_hit(job, at + k, hits[k], found[k] != 0);
            else job->blocked[at + k] = found[k] != 0;
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

// Run the job over its rays (on the calling thread for a few, else on
// `threads` workers); raises the first failure, naming its ray.
void run_job(TraceJob &job, int threads)
{
    const int64_t n = job.count;
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
}

// The checks of trace and occluded; sets up `job`.
void start_job(TraceJob &job, const char *what, const ScenePtr &s, const rays_array &origins,
               const rays_array &directions, double tmin, double tmax, int threads)
{
    job.scene = committed_scene(s);
    const std::string name(what);
    if (origins.ndim() != 2 || origins.shape(1) != 3)
        throw py::value_error(name + ": origins must be an N x 3 array");
    if (directions.ndim() != 2 || directions.shape(1) != 3)
        throw py::value_error(name + ": directions must be an N x 3 array");
    if (origins.shape(0) != directions.shape(0))
        throw py::value_error(name + ": origins and directions must have the same number of rows");
    if (threads < 0) throw py::value_error(name + ": threads must be positive (0: every core)");
    job.origins = origins.data();
    job.directions = directions.data();
    job.tmin = tmin;
    job.tmax = tmax;
    job.count = origins.shape(0);
}

py::tuple trace(const ScenePtr &s, const rays_array &origins, const rays_array &directions, double tmin,
                double tmax, int threads, bool full)
{
    TraceJob job;
    start_job(job, "trace", s, origins, directions, tmin, tmax, threads);
    const int64_t n = job.count;
    py::array_t<double> t(n);
    py::array_t<double> normal({n, static_cast<int64_t>(3)});
    py::array_t<int64_t> object(n);
    py::array_t<double> point(full ? std::vector<int64_t>{n, 3} : std::vector<int64_t>{0, 3});
    py::array_t<int32_t> surface(full ? n : 0);
    py::array_t<bool> entering(full ? n : 0);
    py::array_t<double> error(full ? n : 0);
    job.t = t.mutable_data();
    job.normal = normal.mutable_data();
    job.object = object.mutable_data();
    if (full) {
        job.point = point.mutable_data();
        job.surface = surface.mutable_data();
        job.entering = entering.mutable_data();
        job.error = error.mutable_data();
    }
    run_job(job, threads);
    if (!full) return py::make_tuple(t, normal, object);
    return py::make_tuple(t, point, normal, surface, entering, object, error);
}

py::array_t<bool> occluded(const ScenePtr &s, const rays_array &origins, const rays_array &directions,
                           double tmin, double tmax, int threads)
{
    TraceJob job;
    start_job(job, "occluded", s, origins, directions, tmin, tmax, threads);
    py::array_t<bool> blocked(job.count);
    job.t = nullptr;
    job.blocked = blocked.mutable_data();
    run_job(job, threads);
    return blocked;
}

}  // namespace

void bind_trace(py::module_ &m)
{
    m.def("trace", &trace, py::arg("scene"), py::arg("origins"), py::arg("directions"), py::arg("tmin"),
          py::arg("tmax"), py::arg("threads"), py::arg("full") = false);
    m.def("occluded", &occluded, py::arg("scene"), py::arg("origins"), py::arg("directions"), py::arg("tmin"),
          py::arg("tmax"), py::arg("threads"));
}

}  // namespace hitray_py
