/* Cost and accuracy of the torus module's root solvers (shapes/torus), the
 * numbers quoted in the `solver` parameter's help.
 *
 *   build/bench/torus_solvers [--rays=N] [--repeats=N] [--solver=NAME]
 *                             [--set=NAME] [--no-reference] [--json]
 *
 * For each set of rays (fixed seed) and each solver it prints
 * - ns per solve: wall time of torus_solve over the whole set, all hits
 *   (time_all) and first hit after t = 0 only (time_first, the query of a
 *   renderer's primary ray), the best of `repeats` passes (a busy machine
 *   only slows passes down: take the fastest). For numbers that do not
 *   depend on the machine's load, bench/drivers/torus_solvers_instructions.sh runs
 *   this under callgrind with --no-reference and divides the instructions
 *   of time_all and time_first by the solves;
 * - |t error| against roots computed in __float128 by Sturm sequences
 *   (tests/reference/quad_reference.c), over the rays where the solver and the
 *   reference agree on the count: the worst and the 99th percentile, both
 *   relative to |t| and in units of u * condition (u = 2^-53; the condition
 *   is the root's sensitivity to rounding of the inputs, quad_reference.h);
 * - missed (-) and spurious (+) roots: hits fewer or more than the
 *   reference's, split into rays clear of any tangency (reference margin
 *   > 1e-12: the line is that far from touching, or its chords are that
 *   long, so the count is certain and a solver must match it) and rays
 *   within 1e-12 of one (rounding of the ray itself may rightly decide a
 *   touch, a miss or a tiny chord; the reference can be wrong there too,
 *   e.g. for lines lying exactly in the tangent plane z = tube).
 * With --json each row is one JSON object on a line of its own instead (for
 * bench/drivers/run_accuracy.py, which quotes them in docs/accuracy.md).
 * Ray sets: "near" (origins around the bounds, aimed into them, with zero
 * direction components and origins on faces mixed in), "far 1e4" and
 * "far 1e6" (from that far, aimed into the bounds), "grazing" (tangent to
 * the surface at a random point, moved off it by 10^-4 .. 10^-12 either
 * way), each for tube 0.2; "thin near" and "thin graze" for tube 1e-3. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_util.h"
#include "quad_reference.h"
#include "random_rays.h"
#include "torus_quartic.h"

#define CLEAR_MARGIN 1e-12 /* see "missed and spurious" above */

typedef struct ray_set {
    const char *name;
    double tube;
    int kind; /* 0 near, 1 far 1e4, 2 far 1e6, 3 grazing */
} ray_set;

/* Both timing loops are functions of their own so that callgrind can count
 * their instructions apart. */
__attribute__((noinline)) static double time_all(const torus_geometry *g, int solver,
                                                 const hr_ray *rays, int count)
{
    volatile int sink = 0;
    torus_roots roots;
    const double start = bench_now_ns();
    for (int i = 0; i < count; i++)
        sink += torus_solve(g, solver, &rays[i], -INFINITY, INFINITY, 0, &roots);
    (void)sink;
    return (bench_now_ns() - start) / count;
}

__attribute__((noinline)) static double time_first(const torus_geometry *g, int solver,
                                                   const hr_ray *rays, int count)
{
    volatile int sink = 0;
    torus_roots roots;
    const double start = bench_now_ns();
    for (int i = 0; i < count; i++)
        sink += torus_solve(g, solver, &rays[i], 0.0, INFINITY, 1, &roots);
    (void)sink;
    return (bench_now_ns() - start) / count;
}

static void run_set(const ray_set *set, int count, int repeats, int only_solver,
                    int with_reference, int json)
{
    torus_geometry g;
    torus_geometry_make(set->tube, &g);
    const hr_bounds b = {{-1 - set->tube, -1 - set->tube, -set->tube},
                         {1 + set->tube, 1 + set->tube, set->tube}};
    ray_rng rng;
    rng_seed(&rng, UINT64_C(0xbe4c4) + (uint64_t)set->kind);
    hr_ray *rays = bench_checked(malloc((size_t)count * sizeof *rays));
    ref_trace *refs = bench_checked(malloc((size_t)count * sizeof *refs));
    bench_errors errors;
    bench_errors_init(&errors, count * 4);
    const ref_shape ref = ref_shape_of("torus", set->tube, NAN);
    for (int i = 0; i < count; i++) {
        rays[i] = set->kind == 0   ? random_ray_near(&rng, &b)
                  : set->kind == 1 ? random_ray_far(&rng, &b, 1e4)
                  : set->kind == 2 ? random_ray_far(&rng, &b, 1e6)
                                   : random_ray_grazing_torus(&rng, set->tube);
        if (with_reference) ref_trace_ray(ref, rays[i], &refs[i]);
    }
    for (int solver = 0; solver < TORUS_SOLVER_COUNT; solver++) {
        if (only_solver >= 0 && solver != only_solver) continue;
        double best_all = INFINITY, best_first = INFINITY;
        for (int rep = 0; rep < repeats; rep++) {
            double ns = time_all(&g, solver, rays, count);
            if (ns < best_all) best_all = ns;
            ns = time_first(&g, solver, rays, count);
            if (ns < best_first) best_first = ns;
        }
        if (!with_reference && json) {
            printf("{\"set\": \"%s\", \"tube\": %g, \"solver\": \"%s\", \"rays\": %d, "
                   "\"repeats\": %d, \"ns_all\": %.1f, \"ns_first\": %.1f}\n",
                   set->name, set->tube, torus_solver_name(solver), count, repeats, best_all,
                   best_first);
            continue;
        }
        if (!with_reference) {
            printf("%-10s %-15s %7.0f %7.0f\n", set->name, torus_solver_name(solver), best_all,
                   best_first);
            continue;
        }
        errors.count = 0;
        int missed_clear = 0, spurious_clear = 0, missed_near = 0, spurious_near = 0;
        for (int i = 0; i < count; i++) {
            torus_roots roots;
            const int n = torus_solve(&g, solver, &rays[i], -INFINITY, INFINITY, 0, &roots);
            const ref_trace *r = &refs[i];
            const int clear = r->margin > CLEAR_MARGIN;
            if (n < r->count) *(clear ? &missed_clear : &missed_near) += r->count - n;
            if (n > r->count) *(clear ? &spurious_clear : &spurious_near) += n - r->count;
            if (n != r->count) continue;
            for (int k = 0; k < n; k++)
                bench_errors_add(&errors, fabs(ref_to_double((quad)roots.t[k] - r->hits[k].t)),
                                 roots.t[k], ref_to_double(r->hits[k].condition));
        }
        const bench_error_summary e = bench_errors_summarise(&errors);
        if (json) {
            printf("{\"set\": \"%s\", \"tube\": %g, \"solver\": \"%s\", \"rays\": %d, "
                   "\"repeats\": %d, \"ns_all\": %.1f, \"ns_first\": %.1f, \"roots\": %d, ",
                   set->name, set->tube, torus_solver_name(solver), count, repeats, best_all,
                   best_first, errors.count);
            bench_print_error_members(&e);
            printf(", \"missed_clear\": %d, \"spurious_clear\": %d, \"missed_tangent\": %d, "
                   "\"spurious_tangent\": %d}\n",
                   missed_clear, spurious_clear, missed_near, spurious_near);
            continue;
        }
        printf("%-10s %-15s %7.0f %7.0f   %9.2e %9.2e   %9.3g %9.3g   %5d %5d   %5d %5d\n",
               set->name, torus_solver_name(solver), best_all, best_first, e.worst_rel, e.p99_rel,
               e.worst_cond, e.p99_cond, missed_clear, spurious_clear, missed_near, spurious_near);
    }
    free(rays);
    free(refs);
    bench_errors_free(&errors);
}

static int usage(void)
{
    fprintf(stderr, "usage: torus_solvers [--rays=N] [--repeats=N] [--solver=ferrari|"
                    "ferrari-newton|bracketing] [--set=NAME] [--no-reference] [--json]\n");
    return 2;
}

int main(int argc, char **argv)
{
    static const ray_set sets[] = {
        {"near", 0.2, 0}, {"far 1e4", 0.2, 1}, {"far 1e6", 0.2, 2},
        {"grazing", 0.2, 3}, {"thin near", 1e-3, 0}, {"thin graze", 1e-3, 3},
    };
    const int set_count = (int)(sizeof sets / sizeof sets[0]);
    int count = 20000, repeats = 5, only_solver = -1, only_set = -1, with_reference = 1, json = 0;
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (bench_option(argv[i], "--rays", &v)) count = atoi(v);
        else if (bench_option(argv[i], "--repeats", &v)) repeats = atoi(v);
        else if (bench_option(argv[i], "--solver", &v)) {
            only_solver = torus_solver_find(v);
            if (only_solver < 0) return usage();
        } else if (bench_option(argv[i], "--set", &v)) {
            for (int k = 0; k < set_count; k++)
                if (strcmp(v, sets[k].name) == 0) only_set = k;
            if (only_set < 0) return usage();
        } else if (strcmp(argv[i], "--no-reference") == 0) with_reference = 0;
        else if (strcmp(argv[i], "--json") == 0) json = 1;
        else return usage();
    }
    if (count <= 0 || repeats <= 0) return usage();
    if (!json) {
        printf("%d rays per set, best of %d timing passes\n", count, repeats);
        if (with_reference)
            printf("%-10s %-15s %7s %7s   %9s %9s   %9s %9s   %11s   %11s\n", "rays", "solver",
                   "ns all", "ns 1st", "worst rel", "p99 rel", "worst u*c", "p99 u*c",
                   "clear -/+", "tangent -/+");
        else
            printf("%-10s %-15s %7s %7s\n", "rays", "solver", "ns all", "ns 1st");
    }
    for (int i = 0; i < set_count; i++)
        if (only_set < 0 || i == only_set)
            run_set(&sets[i], count, repeats, only_solver, with_reference, json);
    return 0;
}
