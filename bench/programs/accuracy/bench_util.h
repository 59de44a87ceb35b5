/* Helpers shared by the accuracy and cost benchmarks (bench/programs/torus_solvers.c
 * and bench/programs/accuracy/): a monotonic clock, percentiles and the ray sets'
 * error bookkeeping, so each program prints its numbers the same way. */
#ifndef HR_BENCH_UTIL_H
#define HR_BENCH_UTIL_H

#include <float.h>

/* The unit roundoff of double, u = 2^-53: errors are quoted in units of
 * u * condition (the error a backward-stable computation may make). */
#define BENCH_UNIT_ROUNDOFF (DBL_EPSILON / 2)

/* Nanoseconds of CLOCK_MONOTONIC. */
double bench_now_ns(void);

/* The p-quantile (0 < p <= 1) of v[0..n-1], sorting v in place; 0 if n is 0.
 * p = 1 is the largest value. */
double bench_percentile(double *v, int n, double p);

/* |t error| samples of one row: relative to |t| and in units of
 * u * condition, with room for `capacity` of each. */
typedef struct bench_errors {
    double *rel, *cond;
    int count, capacity;
} bench_errors;

/* Allocates the room or exits with a message: a benchmark has no use for a
 * partial result. */
void bench_errors_init(bench_errors *e, int capacity);
void bench_errors_free(bench_errors *e);
/* One root: |t - t_ref| given, with t and the reference's condition. */
void bench_errors_add(bench_errors *e, double abs_err, double t, double condition);

/* The worst and 99th percentile of each kind (sorts the samples). */
typedef struct bench_error_summary {
    double worst_rel, p99_rel, worst_cond, p99_cond;
} bench_error_summary;
bench_error_summary bench_errors_summarise(bench_errors *e);

/* The summary as JSON members (no braces): "worst_rel": ..., ... */
void bench_print_error_members(const bench_error_summary *s);

/* 1 when `arg` is NAME=VALUE for this name; *value then points at VALUE. */
int bench_option(const char *arg, const char *name, const char **value);

/* Exits with a message when p is NULL (an allocation failed). */
void *bench_checked(void *p);

#endif
