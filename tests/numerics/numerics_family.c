#include "numerics_family.h"

#include <math.h>

#include "hr_test.h"

quad nf_qabs(quad x)
{
    return x < 0 ? -x : x;
}

void nf_compare_ray(const harness_shape *s, ref_shape ref, const nf_probe *p, nc_result *out)
{
    ref_trace expect;
    ref_trace_ray(ref, p->ray, &expect);
    hr_hit h[HARNESS_MAX_HITS];
    const int n = harness_trace(s, p->ray, -INFINITY, INFINITY, HARNESS_ALL, h);
    const double dlen = sqrt(p->ray.dir.x * p->ray.dir.x + p->ray.dir.y * p->ray.dir.y +
                             p->ray.dir.z * p->ray.dir.z);
    double distance = p->distance, band = p->band;
    if (isnan(distance)) {
        distance = expect.margin;
        for (int i = 0; i < expect.count; i++) {
            const double b = NF_T_FACTOR * NC_U * ref_to_double(expect.hits[i].condition) * dlen;
            if (b > band) band = b;
        }
    }
    int same = n == expect.count;
    for (int i = 0; same && i < n; i++)
        same = h[i].surface == expect.hits[i].surface &&
               h[i].entering == expect.hits[i].entering;
    if (!same) {
        const int odd = (n - expect.count) % 2 != 0;
        nc_note(out, odd ? INFINITY : fabs(distance) > band ? fabs(distance) / band : 0);
        if (odd || fabs(distance) > band)
            CHECK_MSG(0,
                      "%s ray (%.17g %.17g %.17g) + t (%.17g %.17g %.17g): %d hits, reference %d "
                      "(distance %.3g, band %.3g)",
                      s->cls->name, p->ray.origin.x, p->ray.origin.y, p->ray.origin.z,
                      p->ray.dir.x, p->ray.dir.y, p->ray.dir.z, n, expect.count, distance, band);
        return;
    }
    for (int i = 0; i < n; i++) {
        const double cond = ref_to_double(expect.hits[i].condition);
        quad err = nf_qabs((quad)h[i].t - expect.hits[i].t);
        /* Within the band, the two crossings of a near-tangency are a
         * near-double root: f stays within its rounding over the whole
         * chord between them, so any point of the chord is a root to within
         * rounding (first-order condition numbers do not see this: there
         * the error grows like the square root of the noise). A crossing
         * must then lie in the chord of its partner, the nearer neighbour,
         * to within 8 u cond. A touch (both at one t) is such a pair. */
        if (fabs(distance) <= band && n > 1) {
            const quad ti = expect.hits[i].t;
            int j = i == 0 ? 1 : i - 1;
            if (i > 0 && i + 1 < n &&
                nf_qabs(expect.hits[i + 1].t - ti) < nf_qabs(expect.hits[i - 1].t - ti))
                j = i + 1;
            const quad tj = expect.hits[j].t, t = h[i].t;
            const quad a = ti < tj ? ti : tj, b = ti < tj ? tj : ti;
            err = t < a ? a - t : t > b ? t - b : 0;
        }
        const double e = ref_to_double(err);
        nc_note(out, e == 0 ? 0 : e / (NF_T_FACTOR * NC_U * cond));
    }
    if (n == 0) nc_note(out, 0);
}

void nf_run_family(const char *module, const char *cls, double s, nf_probe_fn make, int rays,
                   uint64_t seed, nc_result *out)
{
    harness_shape shape;
    if (!harness_open(&shape, module, cls, s)) {
        harness_close(&shape);
        return;
    }
    const ref_shape ref = ref_shape_of(cls, s, NAN);
    ray_rng rng;
    rng_seed(&rng, seed);
    for (int i = 0; i < rays; i++) {
        nf_probe p = {{{0, 0, 0}, {0, 0, 0}}, NAN, 0};
        make(&rng, i, &p);
        nf_compare_ray(&shape, ref, &p, out);
    }
    harness_close(&shape);
}

void nf_signed_zeros(const harness_shape *s, hr_ray ray, nc_result *out)
{
    hr_hit base[HARNESS_MAX_HITS], h[HARNESS_MAX_HITS];
    const int n = harness_hits(s, ray, base);
    for (int mask = 1; mask < 64; mask++) {
        hr_ray r = ray;
        double *v[6] = {&r.origin.x, &r.origin.y, &r.origin.z, &r.dir.x, &r.dir.y, &r.dir.z};
        for (int j = 0; j < 6; j++)
            if ((mask >> j & 1) && *v[j] == 0) *v[j] = -0.0;
        const int m = harness_hits(s, r, h);
        int same = m == n && n > 0;
        for (int i = 0; same && i < n; i++)
            same = h[i].t == base[i].t && h[i].surface == base[i].surface &&
                   h[i].entering == base[i].entering && h[i].point.x == base[i].point.x &&
                   h[i].point.y == base[i].point.y && h[i].point.z == base[i].point.z;
        CHECK_MSG(same, "%s: signed zeros %#x change the hits of (%g %g %g) + t (%g %g %g)",
                  s->cls->name, mask, ray.origin.x, ray.origin.y, ray.origin.z, ray.dir.x,
                  ray.dir.y, ray.dir.z);
        nc_note(out, same ? 0 : INFINITY);
    }
}
