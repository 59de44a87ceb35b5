/* The hard-case catalogue's runner. Each test program of tests/numerics has a
 * table of cases (id, shape, setup, why it is hard, tolerance rule, and the
 * function that runs it); nc_run_table runs every case, prints one line per
 * case with its measured worst error in units of its own tolerance (so a
 * drift toward the limit shows before it fails), fails a case whose worst
 * ratio exceeds 1 or that measured nothing, and checks that CATALOG.md
 * describes every case id of the table, so catalogue and code cannot drift
 * apart. */
#ifndef HR_TEST_NUMERICS_CASES_H
#define HR_TEST_NUMERICS_CASES_H

#include <float.h>

#include <hitray/common.h>

#define NC_U (DBL_EPSILON / 2) /* the unit roundoff u = 2^-53 */

/* What one case measured: its worst error over the tolerance (<= 1 passes),
 * how many samples (rays, hits, pixels) it compared, and for the cases whose
 * tolerance is "none at all", how many events (holes, double hits,
 * self-hits, darkened pixels) it saw (0 passes). `note` may carry a short
 * extra measurement for the printed line. */
typedef struct nc_result {
    double worst;
    long samples;
    long events;
    char note[200];
} nc_result;

typedef struct nc_case {
    const char *id; /* e.g. "Q03"; CATALOG.md has a section for it */
    const char *shape;
    const char *setup;
    const char *why_hard;
    const char *tolerance;
    void (*run)(nc_result *out);
} nc_case;

/* Runs the cases; returns hr_test_end()'s value. */
int nc_run_table(const char *program, const nc_case *cases, int count);

/* Folds one measured ratio into a result (NaN counts as infinitely bad). */
void nc_note(nc_result *r, double ratio);

/* gamma(n) = n u / (1 - n u), the bound of n chained roundings. */
double nc_gamma(int n);

#endif
