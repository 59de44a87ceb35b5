/* clock_gettime(CLOCK_MONOTONIC) is POSIX, not C11. */
#define _POSIX_C_SOURCE 200809L

#include "bench_util.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

double bench_now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e9 + ts.tv_nsec;
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bench_percentile(double *v, int n, double p)
{
    if (n == 0) return 0;
    qsort(v, (size_t)n, sizeof *v, compare_doubles);
    int k = (int)ceil(p * n) - 1;
    if (k < 0) k = 0;
    if (k >= n) k = n - 1;
    return v[k];
}

void *bench_checked(void *p)
{
    if (!p) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return p;
}

void bench_errors_init(bench_errors *e, int capacity)
{
    e->rel = bench_checked(malloc((size_t)capacity * sizeof *e->rel));
    e->cond = bench_checked(malloc((size_t)capacity * sizeof *e->cond));
    e->count = 0;
    e->capacity = capacity;
}

void bench_errors_free(bench_errors *e)
{
    free(e->rel);
    free(e->cond);
    e->rel = e->cond = NULL;
    e->count = e->capacity = 0;
}

void bench_errors_add(bench_errors *e, double abs_err, double t, double condition)
{
    if (e->count >= e->capacity) return;
    e->rel[e->count] = abs_err / fmax(fabs(t), DBL_MIN);
    e->cond[e->count] = abs_err / (BENCH_UNIT_ROUNDOFF * condition);
    e->count++;
}

bench_error_summary bench_errors_summarise(bench_errors *e)
{
    bench_error_summary s;
    s.worst_rel = bench_percentile(e->rel, e->count, 1.0);
    s.p99_rel = bench_percentile(e->rel, e->count, 0.99);
    s.worst_cond = bench_percentile(e->cond, e->count, 1.0);
    s.p99_cond = bench_percentile(e->cond, e->count, 0.99);
    return s;
}

void bench_print_error_members(const bench_error_summary *s)
{
    printf("\"worst_rel\": %.3e, \"p99_rel\": %.3e, \"worst_uc\": %.3e, \"p99_uc\": %.3e",
           s->worst_rel, s->p99_rel, s->worst_cond, s->p99_cond);
}

int bench_option(const char *arg, const char *name, const char **value)
{
    const size_t n = strlen(name);
    if (strncmp(arg, name, n) != 0 || arg[n] != '=') return 0;
    *value = arg + n + 1;
    return 1;
}
