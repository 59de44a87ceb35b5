/* Cost and accuracy of the torus module's root solvers (shapes/torus), the
 * numbers quoted in the `solver` parameter's help.
 *
 *   build/bench/torus_solvers [rays per set] [timing repeats]
 *
 * For each set of rays (fixed seed) and each solver it prints
 * - ns per solve: wall time of torus_solve over the whole set, all hits and
 *   first hit only (the first-hit query of a renderer's primary ray), the
 *   best of `repeats` passes (the machine may be busy: take the smallest);
 * - |t error| against roots computed in __float128 by Sturm sequences
 *   (tests/shapes/quad_reference.c), over the rays where the solver and the
 *   reference agree on the count: the worst and the 99th percentile, both
 *   relative to |t| and in units of u * condition (u = 2^-53; the condition
 *   is the root's sensitivity to rounding of the inputs, quad_reference.h);
 * - missed and spurious roots: hits fewer or more than the reference's,
 *   split into rays clear of any tangency (margin > 1e-6: a solver should
 *   never differ there) and near-tangent ones (there rounding may rightly
 *   turn a touch into a miss or a tiny chord).
 * Ray sets: "near" (origins around the bounds, aimed into them), "far 1e4"
 * and "far 1e6" (from that far, aimed into the bounds), "grazing" (tangent
 * to the surface at a random point, moved off it by 10^-4 .. 10^-12 either
 * way), each for tube 0.2, and "thin near" for tube 1e-3. */
/* clock_gettime(CLOCK_MONOTONIC) is POSIX, not C11. */
#define _POSIX_C_SOURCE 200809L

#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "quad_reference.h"
#include "random_rays.h"
#include "torus_quartic.h"

#define UNIT_ROUNDOFF (DBL_EPSILON / 2)
#define CLEAR_MARGIN 1e-6

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static hr_ray make_ray(double ox, double oy, double oz, double dx, double dy, double dz)
{
    hr_ray r = {{ox, oy, oz}, {dx, dy, dz}};
    return r;
}

static hr_ray far_ray(ray_rng *rng, const hr_bounds *b, double distance)
{
    const double tx = rng_uniform(rng, b->lo.x, b->hi.x), ty = rng_uniform(rng, b->lo.y, b->hi.y);
    const double tz = rng_uniform(rng, b->lo.z, b->hi.z);
    const hr_vec3 away = rng_unit_vector(rng);
    const double length = exp2(rng_uniform(rng, -3, 3));
    return make_ray(tx + distance * away.x, ty + distance * away.y, tz + distance * away.z,
                    -away.x * length, -away.y * length, -away.z * length);
}

static hr_ray grazing_ray(ray_rng *rng, double tube)
{
    const double phi = rng_uniform(rng, 0, 6.283185307179586);
    const double theta = rng_uniform(rng, 0, 6.283185307179586);
    const hr_vec3 n = {cos(theta) * cos(phi), cos(theta) * sin(phi), sin(theta)};
    const hr_vec3 p = {(1 + tube * cos(theta)) * cos(phi), (1 + tube * cos(theta)) * sin(phi),
                       tube * sin(theta)};
    hr_vec3 v = rng_unit_vector(rng);
    const double vn = v.x * n.x + v.y * n.y + v.z * n.z;
    v.x -= vn * n.x, v.y -= vn * n.y, v.z -= vn * n.z;
    const double off = (rng_chance(rng, 0.5) ? 1 : -1) * pow(10, -rng_uniform(rng, 4, 12));
    return make_ray(p.x + off * n.x - 4 * v.x, p.y + off * n.y - 4 * v.y,
                    p.z + off * n.z - 4 * v.z, v.x, v.y, v.z);
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static double percentile(double *v, int n, double p)
{
    if (n == 0) return 0;
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    int k = (int)ceil(p * n) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return v[k];
}

typedef struct ray_set {
    const char *name;
    double tube;
    int kind; /* 0 near, 1 far 1e4, 2 far 1e6, 3 grazing */
} ray_set;

static void run_set(const ray_set *set, int count, int repeats)
{
    torus_geometry g;
    torus_geometry_make(set->tube, &g);
    const hr_bounds b = {{-1 - set->tube, -1 - set->tube, -set->tube},
                         {1 + set->tube, 1 + set->tube, set->tube}};
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0xbe4c4) + (uint64_t)set->kind);
    hr_ray *rays = malloc((size_t)count * sizeof *rays);
    ref_trace *refs = malloc((size_t)count * sizeof *refs);
    double *rel = malloc((size_t)count * 4 * sizeof *rel);
    double *cond = malloc((size_t)count * 4 * sizeof *cond);
    if (!rays || !refs || !rel || !cond) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    const ref_shape ref = ref_shape_of("torus", set->tube);
    for (int i = 0; i < count; i++) {
        rays[i] = set->kind == 0   ? random_ray_near(&rng, &b)
                  : set->kind == 1 ? far_ray(&rng, &b, 1e4)
                  : set->kind == 2 ? far_ray(&rng, &b, 1e6)
                                   : grazing_ray(&rng, set->tube);
        ref_trace_ray(ref, rays[i], &refs[i]);
    }
    for (int solver = 0; solver < TORUS_SOLVER_COUNT; solver++) {
        double best_all = INFINITY, best_first = INFINITY;
        volatile int sink = 0;
        for (int rep = 0; rep < repeats; rep++) {
            torus_roots roots;
            double start = now_ns();
            for (int i = 0; i < count; i++)
                sink += torus_solve(&g, solver, &rays[i], -INFINITY, INFINITY, 0, &roots);
            double ns = (now_ns() - start) / count;
            if (ns < best_all) best_all = ns;
            start = now_ns();
            for (int i = 0; i < count; i++)
                sink += torus_solve(&g, solver, &rays[i], 0.0, INFINITY, 1, &roots);
            ns = (now_ns() - start) / count;
            if (ns < best_first) best_first = ns;
        }
        (void)sink;
        int n_err = 0, missed_clear = 0, spurious_clear = 0, missed_near = 0, spurious_near = 0;
        for (int i = 0; i < count; i++) {
            torus_roots roots;
            const int n = torus_solve(&g, solver, &rays[i], -INFINITY, INFINITY, 0, &roots);
            const ref_trace *r = &refs[i];
            const int clear = r->margin > CLEAR_MARGIN;
            if (n < r->count) *(clear ? &missed_clear : &missed_near) += r->count - n;
            if (n > r->count) *(clear ? &spurious_clear : &spurious_near) += n - r->count;
            if (n != r->count) continue;
            for (int k = 0; k < n; k++) {
                const double err = fabs(ref_to_double((quad)roots.t[k] - r->hits[k].t));
                rel[n_err] = err / fmax(fabs(roots.t[k]), DBL_MIN);
                cond[n_err] = err / (UNIT_ROUNDOFF * ref_to_double(r->hits[k].condition));
                n_err++;
            }
        }
        const double worst_rel = percentile(rel, n_err, 1.0), p99_rel = percentile(rel, n_err, 0.99);
        const double worst_cond = percentile(cond, n_err, 1.0);
        const double p99_cond = percentile(cond, n_err, 0.99);
        printf("%-10s %-15s %7.0f %7.0f   %9.2e %9.2e   %9.3g %9.3g   %5d %5d   %5d %5d\n",
               set->name, torus_solver_name(solver), best_all, best_first, worst_rel, p99_rel,
               worst_cond, p99_cond, missed_clear, spurious_clear, missed_near, spurious_near);
    }
    free(rays);
    free(refs);
    free(rel);
    free(cond);
}

int main(int argc, char **argv)
{
    const int count = argc > 1 ? atoi(argv[1]) : 20000;
    const int repeats = argc > 2 ? atoi(argv[2]) : 5;
    if (count <= 0 || repeats <= 0) {
        fprintf(stderr, "usage: torus_solvers [rays per set > 0] [timing repeats > 0]\n");
        return 2;
    }
    static const ray_set sets[] = {
        {"near", 0.2, 0}, {"far 1e4", 0.2, 1}, {"far 1e6", 0.2, 2},
        {"grazing", 0.2, 3}, {"thin near", 1e-3, 0}, {"thin graze", 1e-3, 3},
    };
    printf("%d rays per set, best of %d timing passes\n", count, repeats);
    printf("%-10s %-15s %7s %7s   %9s %9s   %9s %9s   %11s   %11s\n", "rays", "solver", "ns all",
           "ns 1st", "worst rel", "p99 rel", "worst u*c", "p99 u*c", "clear -/+", "tangent -/+");
    for (size_t i = 0; i < sizeof sets / sizeof sets[0]; i++) run_set(&sets[i], count, repeats);
    return 0;
}
