/* Tracing a mesh: accel/'s walk of the 4-wide BVH, nearest box first (a
 * conservative float test: it never skips a box the ray meets; an any-hit
 * search takes the boxes in any order), with the three modes of the
 * shape ABI:
 * - first hit: the best t so far prunes every box beyond it;
 * - any hit: stops at the first triangle hit (shadow rays);
 * - all hits: every triangle hit, sorted by t (CSG).
 *
 * What a hit reports:
 * - t from the watertight test (mesh_triangle.h);
 * - point: the barycentric combination b0 A + b1 B + b2 C, which lies in the
 *   triangle; error gamma(7) (|b0 A| + |b1 B| + |b2 C|) per coordinate, the
 *   bound pbrt derives for this interpolation (Pharr, Jakob, Humphreys,
 *   "Physically Based Rendering", 3rd ed., 3.9.4);
 * - normal: the interpolated vertex normals where the triangle has them,
 *   flipped to the side of the geometric normal (B - A) x (C - A); otherwise
 *   the geometric normal;
 * - entering: the geometric normal points against the ray (exact: it is the
 *   sign of the test's determinant);
 * - surface 0: a mesh is one surface.
 * For a closed mesh, all-hits lists are made to alternate (see
 * alternate_closed): rounding can swap two crossings a few ulps apart. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "mesh.h"
#include "mesh_triangle.h"

/* (B - A) x (C - A) with the edges scaled by a power of two first, so tiny
 * or huge triangles neither underflow nor overflow. */
static hr_vec3 geometric_normal(const hr_vec3 *a, const hr_vec3 *b, const hr_vec3 *c)
{
    double e1[3] = {b->x - a->x, b->y - a->y, b->z - a->z};
    double e2[3] = {c->x - a->x, c->y - a->y, c->z - a->z};
    double big = 0.0;
    for (int i = 0; i < 3; i++) big = mesh_max(big, mesh_max(fabs(e1[i]), fabs(e2[i])));
    if (big > 0.0 && isfinite(big)) {
        /* Scaled by 2^-ilogb(big), the exponent read off big's bits and the
         * power of two built from them (ilogb and ldexp are libm calls, and
         * this runs for every hit a closed mesh's search keeps); the product
         * with an exact power of two rounds once, as ldexp does. Subnormal
         * edges and an exponent whose inverse is not a normal double go to
         * ilogb and ldexp. */
        uint64_t bits;
        memcpy(&bits, &big, sizeof bits);
        const int biased = (int)(bits >> 52);
        if (biased > 1 && biased < 2046) {
            const uint64_t scale_bits = (uint64_t)(2046 - biased) << 52; /* 2^(1023 - biased) */
            double scale;
            memcpy(&scale, &scale_bits, sizeof scale);
            for (int i = 0; i < 3; i++) e1[i] *= scale, e2[i] *= scale;
        } else {
            int e = ilogb(big);
            for (int i = 0; i < 3; i++) e1[i] = ldexp(e1[i], -e), e2[i] = ldexp(e2[i], -e);
        }
    }
    hr_vec3 n = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
    return n;
}

static double dot3(hr_vec3 a, hr_vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

/* The error bound of a hit's point (see the top of the file), on its own:
 * the closed mesh's searches need it for crossings they may never report. */
static double point_error(const mesh *m, uint32_t tri, const double b[3])
{
    const uint32_t *c = m->corners + 3 * (size_t)tri;
    const hr_vec3 *v[3] = {&m->vertices[c[0]], &m->vertices[c[1]], &m->vertices[c[2]]};
    double ex = fabs(b[0] * v[0]->x) + fabs(b[1] * v[1]->x) + fabs(b[2] * v[2]->x);
    double ey = fabs(b[0] * v[0]->y) + fabs(b[1] * v[1]->y) + fabs(b[2] * v[2]->y);
    double ez = fabs(b[0] * v[0]->z) + fabs(b[1] * v[1]->z) + fabs(b[2] * v[2]->z);
    return MESH_GAMMA(7) * mesh_max(ex, mesh_max(ey, ez));
}

/* The fields of a hit every mode writes: t, the point and its error bound,
 * the surface and the entering flag. */
static void fill_point(const mesh *m, uint32_t tri, const mesh_triangle_hit *th, hr_hit *hit)
{
    const uint32_t *c = m->corners + 3 * (size_t)tri;
    const hr_vec3 *v[3] = {&m->vertices[c[0]], &m->vertices[c[1]], &m->vertices[c[2]]};
    const double *b = th->b;
    hit->t = th->t;
    hit->point.x = b[0] * v[0]->x + b[1] * v[1]->x + b[2] * v[2]->x;
    hit->point.y = b[0] * v[0]->y + b[1] * v[1]->y + b[2] * v[2]->y;
    hit->point.z = b[0] * v[0]->z + b[1] * v[1]->z + b[2] * v[2]->z;
    hit->error = point_error(m, tri, b);
    hit->surface = 0;
    hit->entering = th->entering;
}

/* An any-hit answer: only its t is meaningful (HR_TRACE_ANY: the host
 * reads nothing else of a shadow ray's hit), yet every field must be
 * valid. So fill_point's fields, and for the normal the axis the ray runs
 * most along, facing the ray as the entering flag says (against it when
 * entering, as the geometric normal does): the geometric normal and the
 * interpolated vertex normals, most of fill_hit, are not worked out. */
static void fill_any_hit(const mesh *m, const mesh_ray *r, uint32_t tri, const mesh_triangle_hit *th,
                         hr_hit *hit)
{
    fill_point(m, tri, th, hit);
    double n[3] = {0.0, 0.0, 0.0};
    n[r->kz] = (r->d[r->kz] > 0.0) == th->entering ? -1.0 : 1.0;
    hit->normal.x = n[0], hit->normal.y = n[1], hit->normal.z = n[2];
}

/* Writes every field of the hit but `object`, which is the host's. */
static void fill_hit(const mesh *m, const hr_ray *ray, uint32_t tri, const mesh_triangle_hit *th,
                     hr_hit *hit)
{
    fill_point(m, tri, th, hit);
    const uint32_t *c = m->corners + 3 * (size_t)tri;
    const hr_vec3 *v[3] = {&m->vertices[c[0]], &m->vertices[c[1]], &m->vertices[c[2]]};
    const double *b = th->b;
    hr_vec3 ng = geometric_normal(v[0], v[1], v[2]);
    if (ng.x == 0.0 && ng.y == 0.0 && ng.z == 0.0) {
        /* Collinear corners the test still saw with area (rounding): face
         * the ray the way the entering flag says. */
        const double s = th->entering ? -1.0 : 1.0;
        ng.x = s * ray->dir.x, ng.y = s * ray->dir.y, ng.z = s * ray->dir.z;
    }
    hit->normal = ng;
    if (!m->corner_normals) return;
    const uint32_t *cn = m->corner_normals + 3 * (size_t)tri;
    if (cn[0] == MESH_NO_NORMAL || cn[1] == MESH_NO_NORMAL || cn[2] == MESH_NO_NORMAL) return;
    const hr_vec3 *n[3] = {&m->normals[cn[0]], &m->normals[cn[1]], &m->normals[cn[2]]};
    hr_vec3 ns = {b[0] * n[0]->x + b[1] * n[1]->x + b[2] * n[2]->x,
                  b[0] * n[0]->y + b[1] * n[1]->y + b[2] * n[2]->y,
                  b[0] * n[0]->z + b[1] * n[1]->z + b[2] * n[2]->z};
    if (!isfinite(ns.x) || !isfinite(ns.y) || !isfinite(ns.z)) return;
    const double side = dot3(ns, ng);
    if (side == 0.0 || !isfinite(side)) return; /* zero, or in the surface's plane */
    if (side < 0.0) ns.x = -ns.x, ns.y = -ns.y, ns.z = -ns.z;
    hit->normal = ns;
}

/* A mesh's order of its own hits: by t, an entering hit first at equal t
 * (the library's hit_before, lib/trace/object_trace.h, orders a scene's
 * hits by t, object and surface instead), then the lower triangle index in
 * the file (key): the order of all hits does not depend on the walk's. */
typedef struct hit_key {
    double t_error; /* the triangle test's bound on the rounding of t */
    uint32_t index; /* the triangle's index in the file */
    uint32_t paired; /* one of a pair alternate_closed made (set there only) */
} hit_key;

static int mesh_hit_before(const hr_hit *a, hit_key a_key, const hr_hit *b, hit_key b_key)
{
    if (a->t != b->t) return a->t < b->t;
    if (a->entering != b->entering) return a->entering > b->entering; /* a zero-length visit: enter first */
    return a_key.index < b_key.index;
}

/* Sorts hits[0, n) with their keys: insertion sort for the short lists
 * rays usually make, heapsort (no allocation, no recursion) beyond. */
static void swap_hits(hr_hit *h, hit_key *key, size_t i, size_t j)
{
    const hr_hit t = h[i];
    h[i] = h[j], h[j] = t;
    const hit_key k = key[i];
    key[i] = key[j], key[j] = k;
}

static void sift(hr_hit *h, hit_key *key, size_t root, size_t n)
{
    for (;;) {
        size_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && mesh_hit_before(&h[child], key[child], &h[child + 1], key[child + 1])) child++;
        if (!mesh_hit_before(&h[root], key[root], &h[child], key[child])) return;
        swap_hits(h, key, root, child);
        root = child;
    }
}

static void sort_hits(hr_hit *h, hit_key *key, size_t n)
{
    if (n <= 32) {
        for (size_t i = 1; i < n; i++) {
            const hr_hit x = h[i];
            const hit_key kx = key[i];
            size_t j = i;
            while (j > 0 && mesh_hit_before(&x, kx, &h[j - 1], key[j - 1]))
                h[j] = h[j - 1], key[j] = key[j - 1], j--;
            h[j] = x, key[j] = kx;
        }
        return;
    }
    for (size_t i = n / 2; i-- > 0;) sift(h, key, i, n);
    for (size_t end = n; end-- > 1;) {
        swap_hits(h, key, 0, end);
        sift(h, key, 0, end);
    }
}

static double ray_speed(const hr_ray *ray)
{
    return mesh_max(fabs(ray->dir.x), mesh_max(fabs(ray->dir.y), fabs(ray->dir.z)));
}

/* How far apart in t two crossings of a closed mesh may lie and still be
 * put in the other order by alternate_closed: their points' error bounds
 * as distances along the ray, and the bound on the rounding of the earlier
 * one's t, twice (t_errors: the two crossings' bounds where the later's is
 * no larger; their computed t can be in the other order than the exact
 * crossings only within the sum of the two): a ray that runs nearly along thin faces far
 * from the origin (faces 1e15 long and a few units wide, crossed from 1e16
 * away: a fuzz input) has t errors of several times t, and the exact order
 * of its crossings, a few 1e-17 apart in t, is not that of their computed
 * t. Only the earlier one's: the first-hit search, which must find the
 * same near ties, sees crossings as far past its best as its best's t
 * error reaches, not as far as a later crossing's may (a crossing 0.02
 * past a vertex touch, nearly edge on with a t error of 200, whose box
 * the search never reaches: a fuzz input). */
static double slack_of(const hr_ray *ray, double a_error, double a_t, double b_error, double b_t,
                       double t_errors)
{
    return (a_error + b_error) / ray_speed(ray) * 4.0 +
           8.0 * DBL_EPSILON * mesh_max(fabs(a_t), fabs(b_t)) + t_errors;
}

static double closed_slack(const hr_ray *ray, const hr_hit *a, hit_key a_key, const hr_hit *b)
{
    return slack_of(ray, a->error, a->t, b->error, b->t, 2.0 * a_key.t_error);
}

/* A closed mesh's crossings alternate along the exact line, entering
 * first (the line starts outside), and the entering flags are exact; only
 * the computed t can put two crossings a rounding apart in the wrong order.
 * So a closed mesh's all-hits query collects the whole line, and where the
 * sorted list breaks the alternation at h[i], the next crossing h[j] of the
 * expected kind within the two hits' error bounds (as distances along the
 * ray) and their t error bounds (slack_of) is made one place with h[i]: a
 * zero-length visit, h[j] first. Where none is that close, the list is
 * left as computed (the surface crosses itself there) and the expectation
 * follows what was found.
 *
 * The place is where the better known of the two lies: h[i]'s t, or h[j]'s
 * where h[j]'s t error is the smaller. (Always h[i]'s lost a tetrahedron
 * 1e37 across to a ray along its edge: a leaving crossing at t = -1 with a
 * t error of 3.9e36, an entering one at 4.2e36 known to 1.7e32; the pair
 * went to t = -1, before tmin = 0, while the any-hit search rightly met
 * the entering one: a fuzz input.) At h[i]'s t the pair takes h[i]'s
 * position and the hits between move down one; at h[j]'s t it takes h[j]'s
 * and those hits move up one, to where their t puts them. Either way the
 * list stays sorted, the pair is never split or moved again, and the scan
 * goes on from h[i]'s position.
 *
 * `surface` holds each hit's mark (MARK_*): inside the caller's interval,
 * outside it, or inside but within its t error of tmin (the triangle
 * test refuses it: it may lie at or before tmin). The pair shares one
 * mark, so that the interval keeps both or neither:
 * - the place's mark where the place's t lies outside the interval: both
 *   now have that t;
 * - the other hit's own mark where the place is refused only for its t
 *   error. The repair says that h[j] comes first along the exact line and
 *   h[i] at or after it, and the place is the better known one; so when
 *   the other lies past tmin by more than its own t error, so does the
 *   place's crossing. (Taking the place's mark there dropped a crossing
 *   clearly inside its triangle, t error 5e-14, with a leaving one at
 *   t = 1 that the ray, in that triangle's plane, saw with a t error of
 *   9.5 from tmin = 0: the ray met the mesh, yet neither hit nor first_hit
 *   said so; a fuzz input.) */
#define MARK_INSIDE 0
#define MARK_OUTSIDE 1
#define MARK_T_ERROR 2

/* The crossing of the expected kind that h[i] pairs with, or 0 (never a
 * valid answer: it lies past i). */
static size_t pair_partner(const hr_ray *ray, const hr_hit *h, const hit_key *key, size_t i, size_t n,
                           int expected)
{
    for (size_t j = i + 1; j < n; j++) {
        if (!(h[j].t - h[i].t <= closed_slack(ray, &h[i], key[i], &h[j]))) return 0;
        if (h[j].entering == expected && !key[j].paired) return j;
    }
    return 0;
}

/* Makes h[i] and h[j] one place, as alternate_closed describes. */
static void make_pair(hr_hit *h, hit_key *key, size_t i, size_t j)
{
    const int at_j = key[j].t_error < key[i].t_error;
    hr_hit first = h[j], second = h[i];
    const hit_key first_key = key[j], second_key = key[i];
    const hr_hit *place = at_j ? &first : &second, *other = at_j ? &second : &first;
    const int mark = place->surface != MARK_T_ERROR ? place->surface : other->surface;
    first.t = second.t = place->t;
    first.surface = second.surface = mark;
    size_t at;
    if (at_j) {
        memmove(&h[i], &h[i + 1], (j - 1 - i) * sizeof *h);
        memmove(&key[i], &key[i + 1], (j - 1 - i) * sizeof *key);
        at = j - 1;
    } else {
        memmove(&h[i + 2], &h[i + 1], (j - 1 - i) * sizeof *h);
        memmove(&key[i + 2], &key[i + 1], (j - 1 - i) * sizeof *key);
        at = i;
    }
    h[at] = first, key[at] = first_key;
    h[at + 1] = second, key[at + 1] = second_key;
    key[at].paired = key[at + 1].paired = 1;
}

static void alternate_closed(const hr_ray *ray, hr_hit *h, hit_key *key, size_t n)
{
    for (size_t i = 0; i < n; i++) key[i].paired = 0;
    int expected = 1;
    for (size_t i = 0; i < n;) {
        /* A pair is a zero-length visit: it leaves the expectation as is. */
        if (key[i].paired) {
            i++;
            continue;
        }
        if (h[i].entering != expected) {
            const size_t j = pair_partner(ray, h, key, i, n, expected);
            if (j) {
                make_pair(h, key, i, j);
                continue;
            }
        }
        expected = !h[i].entering;
        i++;
    }
}

/* Room for one more hit in the host's list, grown through the host. */
static hr_status make_room(const hr_hit_args *args, const hr_host *host)
{
    hr_intersection *out = args->out;
    if (out->count < out->capacity) return HR_OK;
    if (out->capacity > INT32_MAX / 2) return HR_ERROR_OUT_OF_MEMORY;
    int32_t wanted = out->capacity * 2 > out->count + 8 ? out->capacity * 2 : out->count + 8;
    hr_status st = host->reserve(args->call, out, wanted);
    if (st) return st;
    return out->count < out->capacity ? HR_OK : HR_ERROR_OUT_OF_MEMORY;
}

/* The largest error bound fill_hit can give a hit of this mesh: the
 * barycentric sum of a coordinate is at most the largest coordinate
 * magnitude (twice that, generously, for the rounding of the weights). */
double mesh_largest_error(const mesh *m)
{
    const hr_bounds *b = &m->bounds;
    const double big =
        mesh_max(mesh_max(mesh_max(fabs(b->lo.x), fabs(b->hi.x)), mesh_max(fabs(b->lo.y), fabs(b->hi.y))),
             mesh_max(fabs(b->lo.z), fabs(b->hi.z)));
    return MESH_GAMMA(7) * 2.0 * big;
}


/* Crossings a closed mesh's first-hit search remembers (see mesh_trace). */
#define TIE_SEEN 16

/* One of them: the test's answer and its triangle, from which point_error
 * gives its error bound when the near-tie check needs it (rarely: most
 * crossings lie far from the best hit, and no hit need be filled for them). */
typedef struct seen_crossing {
    mesh_triangle_hit th;
    uint32_t tri;
} seen_crossing;

/* One query: the ray, the caller's arguments, and what the leaves found. */
typedef struct query {
    const mesh *m;
    const hr_hit_args *args;
    mesh_ray r;     /* set up at the first leaf (ray_ready) */
    int ray_ready;
    int32_t mode;
    int tie_check, whole_line;
    int closed_any;  /* a closed mesh's any-hit search (closed_any_blocks) */
    int any_order;   /* an any-hit search from tmin >= 0: leaves in any order (walk_any_order) */
    int needs_first; /* it met a hit it cannot decide on: ask the first-hit search */
    double tie_error;
    double tie_end;    /* how far past the caller's tmax a closed mesh's first-hit search looks */
    double searched_end; /* the least end of the search's interval so far, at most tie_end */
    int window_unseen;   /* its best's window reaches past searched_end (see leaf_loop) */
    double tmin, tmax; /* the interval boxes are tested over */
    int32_t start;     /* the caller's first hit in args->out */
    int phase;         /* see walk: 0, or the sign of the t this walk keeps */
    int32_t back_end;  /* args->out's count after the walk of t < 0 (walk) */
    hr_status status;
    int found;
    mesh_triangle_hit best;
    uint32_t best_tri;
    double best_error; /* point_error of best, in a closed mesh's first-hit search */
    seen_crossing seen[TIE_SEEN];
    int seen_count, seen_overflow;
    /* An all-hits query's file index and t error bound of each hit it
     * appended (sort_hits' keys, alternate_closed's slack): in key_room
     * until that is full, then in memory from the host. */
    hit_key *keys;
    size_t key_capacity;
    hit_key key_room[32];
} query;

/* Room for the key of the all-hits query's hit number `at`. */
static hr_status key_room(query *q, size_t at)
{
    if (at < q->key_capacity) return HR_OK;
    const hr_host *host = q->m->host;
    const size_t wanted = 2 * q->key_capacity;
    hit_key *grown = wanted <= SIZE_MAX / sizeof *grown ? host->alloc(wanted * sizeof *grown) : NULL;
    if (!grown) return HR_ERROR_OUT_OF_MEMORY;
    memcpy(grown, q->keys, q->key_capacity * sizeof *grown);
    if (q->keys != q->key_room) host->free(q->keys);
    q->keys = grown;
    q->key_capacity = wanted;
    return HR_OK;
}

/* Whether a hit X of a closed mesh's any-hit search (tmin >= 0, X inside
 * the caller's interval as the triangle test applies it) settles the
 * answer: the ray is blocked exactly when the first-hit search (the
 * answer a closed mesh's any-hit must give, see mesh_trace) reports a hit,
 * and it does when X lies further than `reach` from both ends of the
 * interval.
 * - The first-hit search finds a hit. It has the any-hit search's
 *   candidates (the same ray and interval, the same test: the triangle
 *   test over (-inf, tmax) and then the caller's tmin with the test's own
 *   expressions), X among them, whatever order either walk takes the
 *   leaves in (the any-hit search's: any, walk_any_order). It passes over
 *   a candidate only past a best it has taken, which lies in the caller's
 *   interval; so it ends with a best, X or one before X. With no near tie,
 *   its best is its answer.
 * - With a near tie it answers the first hit of the all-hits list. That
 *   list holds X (its walk of t >= 0 reaches X's leaf, accel's walk being
 *   conservative as every mode assumes, and the test does the same
 *   arithmetic on the same triangle), unmarked (inside the caller's
 *   interval). alternate_closed changes marks in one way only: it makes
 *   a pair of h[i] and a later h[j] of the other kind, h[j].t - h[i].t <=
 *   closed_slack, whose t error part is twice h[i]'s, at the t of the one
 *   whose t error is the smaller (the place), with one mark: the place's,
 *   or the other's own where the place is refused only for its t error.
 *   Every other hit is shifted with its own mark, and a pair is never
 *   moved again. So X stays in the list unless it is one of a pair whose
 *   place is the other hit and lies outside the interval:
 *   - X = h[j], the place h[i]: h[i]'s t error is at most X's, so h[i].t
 *     lies within a slack with X's t error before X, and h[i].t <= X.t <
 *     tmax;
 *   - X = h[i], the place h[j]: h[j].t lies within a slack with X's t
 *     error after X, and h[j].t >= X.t > tmin.
 * - A slack with X's t error does not reach from X to tmin or to tmax:
 *   every point error bound is at most tie_error (mesh_largest_error), and
 *   the rounded slack is monotone in the errors, so for a partner t with
 *   |t| <= |X.t| the slack's parts are at most reach / 2, and X.t - reach >
 *   tmin and X.t + reach < tmax (checked as computed, which implies them
 *   exactly) put the partner inside, reach's factor 2 covering the
 *   roundings of the differences. A partner before X with |t| > |X.t|
 *   would be negative, and the slack's part in |t|, 8 DBL_EPSILON |t|,
 *   could not reach from below 0 to X.t > reach. One after X, at t, has
 *   t - X.t <= P + 8 DBL_EPSILON t, P the parts other than |t|'s, so
 *   t - X.t <= (P + 8 DBL_EPSILON X.t) / (1 - 8 DBL_EPSILON), within reach.
 * A hit within reach of tmin (a ray starting on the mesh) or tmax (a
 * shadow ray ending on it) is left to the first-hit search. */
static int closed_any_blocks(const query *q, const mesh_triangle_hit *x)
{
    const double reach =
        2.0 * slack_of(&q->args->ray, q->tie_error, x->t, q->tie_error, x->t, 2.0 * x->t_error);
    return x->t - reach > q->tmin && x->t + reach < q->args->tmax;
}

/* Whether a walk of one half of the line (walk) keeps hit th of triangle
 * tri. Away from t = 0, when t lies in its half: the other walk finds it
 * too. Within its t error of 0 the t may have the wrong sign, and the walk
 * of the half the crossing really lies in may be the only one to reach its
 * triangle, the other culling the box by the exact geometry: a line
 * entering the octahedron at t = -1.3e-18 through its edge x = 0,
 * y + z = -1 from an origin at x = 1.3e-18 had the crossing given to the
 * face x <= 0 at a t of 0, which the reversed walk left to the walk of
 * t >= 0, and that walk never meets the face's box x <= 0. So either walk
 * keeps such a hit, the second only when the first has not: when no hit
 * of the first walk has this triangle's index (the test is deterministic,
 * so the first walk's hit of the triangle is this one). Not when no hit
 * has the same t, flag and point: at a vertex every triangle round it can
 * give that one hit (the vertex, at one t), and the second of two such
 * was dropped: a ray along an edge of the buckyball, within 1e-17 of its
 * vertices, met four triangles at its far vertex, three of them within
 * their t error of 0, and the list kept three, one entering lost, so the
 * closed solid's hits no longer alternated.
 * For the first or any hit a copy changes nothing. */
static int kept_in_phase(const query *q, uint32_t tri, const mesh_triangle_hit *th)
{
    if (!(fabs(th->t) <= th->t_error)) return (th->t < 0.0) == (q->phase < 0);
    if (q->phase < 0 || q->mode != HR_TRACE_ALL) return 1;
    const uint32_t index = q->m->bvh.items[tri];
    for (int32_t k = q->start; k < q->back_end; k++)
        if (q->keys[k - q->start].index == index) return 0;
    return 1;
}

/* mesh_hit_past for hit th of the leaf's triangle i. */
static int hit_past(const query *q, uint32_t i, const mesh_triangle_hit *th, double tmin)
{
    const uint32_t *c = q->m->corners + 3 * (size_t)i;
    const hr_vec3 *v = q->m->vertices;
    return mesh_hit_past(&q->r, &v[c[0]], &v[c[1]], &v[c[2]], th->t, th->t_error, tmin);
}

/* A filter of mesh_triangle.h: mesh_triangle_quad_fails, or none. */
typedef unsigned (*filter_fn)(const mesh_ray *r, const hr_vec3 *v, const uint32_t *const c[], mesh_lanes *out,
                              int kx, int ky, int kz);

/* Tests triangles [first, end), a leaf, in the query's mode, the ray's
 * axes given as kx, ky, kz (see LEAF_LOOPS), through the SSE2 filter two
 * by two or, given quad (a constant, so inlined: the AVX2 filter), four by
 * four where three or more are left. Returns 1 when the search is
 * over: an any hit found, or an error (in status). */
MESH_AXES_INLINE int leaf_loop(query *q, uint32_t first, uint32_t end, int kx, int ky, int kz, filter_fn quad)
{
    const mesh *m = q->m;
    const hr_hit_args *args = q->args;
    /* Read once: the stores of hits below keep the compiler from assuming
     * that these stay put; tmax is written back where a hit narrows it. */
    const uint32_t *const corners = m->corners;
    const hr_vec3 *const vertices = m->vertices;
    const double test_tmin = q->tie_check ? -INFINITY : q->tmin;
    double tmax = q->tmax;
    /* Triangles a pair or a quad at a time through the filter first (most
     * fail it), each left in turn to the test, or to the test's last steps
     * on the filter's values where its edges agree, so hits are taken in
     * the same order with the same narrowing of tmax as one by one; lanes
     * past the leaf's end repeat the group's first triangle, and are not
     * read. */
    unsigned fails = 0;
    uint32_t group = first, next = first; /* the filter's lanes: from group, until next */
    mesh_lanes lanes_at;
    for (uint32_t i = first; i < end; i++) {
        const uint32_t *c = corners + 3 * (size_t)i;
        if (i == next) {
            const uint32_t left = end - i;
            const uint32_t *const lanes[4] = {c, left > 1 ? c + 3 : c, left > 2 ? c + 6 : c, left > 3 ? c + 9 : c};
            if (quad && left > 2) fails = quad(&q->r, vertices, lanes, &lanes_at, kx, ky, kz), next = i + 4;
            else fails = mesh_triangle_pair_fails(&q->r, vertices, lanes, &lanes_at, kx, ky, kz), next = i + 2;
            group = i;
        }
        const int lane = (int)(i - group);
        if (fails >> lane & 1) continue;
        mesh_triangle_hit th;
        if (fails >> (4 + lane) & 1) {
            const int answer = mesh_filter_finish(&q->r, &lanes_at, lane, test_tmin, tmax, &th);
            if (answer != 1 &&
                (!answer || !mesh_resolve_place(&q->r, &vertices[c[0]], &vertices[c[1]], &vertices[c[2]], test_tmin)))
                continue;
        } else if (!mesh_triangle_test_axes(&q->r, &vertices[c[0]], &vertices[c[1]], &vertices[c[2]], test_tmin,
                                            tmax, &th, kx, ky, kz)) {
            continue;
        }
        /* A hit the walk of the other half of the line finds (walk). */
        if (q->phase && !kept_in_phase(q, i, &th)) continue;
        if (q->mode == HR_TRACE_ALL) {
            hr_status st = make_room(args, m->host);
            if (st) {
                args->out->count = q->start;
                q->status = st;
                return 1;
            }
            st = key_room(q, (size_t)(args->out->count - q->start));
            if (st) {
                args->out->count = q->start;
                q->status = st;
                return 1;
            }
            q->keys[args->out->count - q->start].index = m->bvh.items[i];
            q->keys[args->out->count - q->start].t_error = th.t_error;
            hr_hit *hit = &args->out->hits[args->out->count++];
            fill_hit(m, &args->ray, i, &th, hit);
            /* The caller's interval as mesh_triangle_test applies it (so a
             * hit is kept by the same test in every mode). */
            if (q->whole_line)
                hit->surface = !(th.t > args->tmin && th.t < args->tmax) ? MARK_OUTSIDE
                               : !hit_past(q, i, &th, args->tmin)       ? MARK_T_ERROR
                                                                         : MARK_INSIDE;
            continue;
        }
        if (q->tie_check) {
            if (q->seen_count < TIE_SEEN) {
                q->seen[q->seen_count].th = th;
                q->seen[q->seen_count++].tri = i;
            } else {
                q->seen_overflow = 1;
            }
            /* The caller's interval, as mesh_triangle_test applies it: the
             * search runs past tmax too (see trace_query), for crossings
             * that only the near-tie check may use. */
            if (!(th.t > q->tmin && hit_past(q, i, &th, q->tmin) && th.t < args->tmax)) continue;
        }
        if (q->closed_any) {
            if (closed_any_blocks(q, &th)) {
                q->found = 1;
                q->best = th;
                q->best_tri = i;
            } else {
                q->needs_first = 1;
            }
            return 1;
        }
        /* A tie goes to the entering hit, then to the lower triangle index
         * in the file, as in the all-hits order (mesh_hit_before): a ray
         * through a vertex or an edge where it touches the mesh meets an
         * entering and an exiting triangle at one t, coincident triangles
         * meet it at one t with one flag, and the first hit must be the
         * first of all hits whichever the BVH reaches first. */
        if (q->found && !(th.t < q->best.t ||
                          (th.t == q->best.t && (th.entering > q->best.entering ||
                                                 (th.entering == q->best.entering &&
                                                  m->bvh.items[i] < m->bvh.items[q->best_tri])))))
            continue;
        q->searched_end = mesh_min(q->searched_end, tmax);
        q->found = 1;
        q->best = th;
        q->best_tri = i;
        if (q->mode == HR_TRACE_ANY) return 1;
        /* Nearer hits only from here on, and hits at the same t (an
         * entering one after an exiting best, a lower triangle index after
         * either); a closed mesh's search runs on over the slack of a near
         * tie. The boxes bound the exact crossings while the best is the
         * least computed t, which may lie t_error from its crossing: a
         * crossing whose box lies past the best's t can still have the
         * smaller computed t, the one the all-hits list puts first (a ray
         * nearly along a triangle's plane, 1e14 long, in an NFF polygon
         * gave t errors of 1e-4). So the search runs on twice the best's
         * t error, which holds the crossings whose t is as uncertain as
         * the best's (neighbouring faces seen the same way). */
        tmax = mesh_min(tmax, mesh_next_up(mesh_max(th.t, th.t + 2.0 * th.t_error)));
        if (q->tie_check) {
            q->best_error = point_error(m, i, th.b);
            /* And the best's t error twice (slack_of's t part for a
             * crossing after the best). */
            const double window = (q->best_error + q->tie_error) / ray_speed(&args->ray) * 4.0 +
                                  16.0 * DBL_EPSILON * fabs(th.t) + 2.0 * th.t_error;
            const double window_end = mesh_next_up(th.t + window);
            tmax = fmin(q->tie_end, window_end);
            /* Where the best's window reaches past the least end the
             * search has run under, crossings between that end and the
             * window's are unseen, and alternate_closed may pair one
             * with the best: then the answer is the all-hits list's
             * (finish_query). Two ways it happens:
             * - a window cut at tie_end, which allows for the points'
             *   slack past the caller's tmax, not for the best's t error
             *   (a leaving crossing at t = 0.75 with a t error of 0.145 and
             *   tmax = 0.8, the list moving an entering one up from t = 1,
             *   a fuzz input altered);
             * - a best taking over at the same t (or just before) with a
             *   wider window than the one it replaces (a fuzz input: a
             *   leaving crossing at t = 1 with a t error of 1.4e-13
             *   narrowed the end to 1 + 2.9e-13, an entering one at
             *   1 + 4.6e-10 was refused, and a leaving one at t = 1 with a
             *   t error of 4.8e-5 and a lower index took over, whose slack
             *   holds the entering one). */
            q->window_unseen = !(window_end <= q->searched_end);
        }
        q->tmax = tmax;
    }
    return 0;
}

/* leaf_loop with the axes as constants: one copy for each order
 * mesh_ray_init can choose (kz, then kx and ky in turn or swapped); the
 * walk's answer from leaf_loop's. */
#define LEAF_LOOPS(quad)                                                                           \
    int over;                                                                                      \
    switch (q->r.kz * 3 + q->r.kx) {                                                               \
    case 0 * 3 + 1: over = leaf_loop(q, first, end, 1, 2, 0, quad); break;                         \
    case 0 * 3 + 2: over = leaf_loop(q, first, end, 2, 1, 0, quad); break;                         \
    case 1 * 3 + 2: over = leaf_loop(q, first, end, 2, 0, 1, quad); break;                         \
    case 1 * 3 + 0: over = leaf_loop(q, first, end, 0, 2, 1, quad); break;                         \
    case 2 * 3 + 0: over = leaf_loop(q, first, end, 0, 1, 2, quad); break;                         \
    default: over = leaf_loop(q, first, end, 1, 0, 2, quad); break;                                \
    }                                                                                              \
    return over ? ACCEL_WALK_STOP : ACCEL_WALK_GO_ON

/* The triangle test's ray, set up at the first leaf: many walks meet
 * none. 0 for a zero direction, which meets no triangle. */
static int ray_ready(query *q)
{
    if (!q->ray_ready) q->ray_ready = mesh_ray_init(&q->r, &q->args->ray);
    return q->ray_ready;
}

/* The walk's leaf callback: triangles [first, first + count). */
static int leaf_of(void *user, uint32_t first, uint32_t count)
{
    query *q = user;
    const uint32_t end = first + count;
    if (!ray_ready(q)) return ACCEL_WALK_STOP;
    LEAF_LOOPS(NULL);
}

#if MESH_FILTER_AVX2
/* The same compiled for AVX2 CPUs, with the four-lane filter: the scalar
 * test is the same code (AVX2 brings no FMA), the filter's lanes the same
 * values. */
__attribute__((target("avx2"))) static int leaf_of_avx2(void *user, uint32_t first, uint32_t count)
{
    query *q = user;
    const uint32_t end = first + count;
    if (!ray_ready(q)) return ACCEL_WALK_STOP;
    LEAF_LOOPS(mesh_triangle_quad_fails);
}
#endif
#undef LEAF_LOOPS

/* accel's leaf callback. */
typedef int (*leaf_fn)(void *user, uint32_t first, uint32_t count);

/* The leaf callback for this CPU: with the AVX2 filter where it runs. */
static inline leaf_fn leaf_callback(void)
{
#if MESH_FILTER_AVX2
    if (mesh_filter_avx2_usable()) return leaf_of_avx2;
#endif
    return leaf_of;
}

/* An any-hit search from tmin >= 0. An open mesh's any hit is any
 * triangle hit in the interval, which every order of the leaves finds, and
 * a closed mesh's (closed_any) is whether the first-hit search finds a
 * hit, which does not depend on the order either (closed_any_blocks): the
 * walk that skips sorting children. Out of line: inlined in walk, the
 * second walk cost the other queries' frame (measured: bench/results/RESULTS.md,
 * "The mesh's any-hit walk in any order"). */
static __attribute__((noinline)) void walk_any_order(query *q)
{
    leaf_fn leaf_of_cpu = leaf_callback();
    if (isnan(q->tmax)) return;
    accel_bvh4_walk_any(&q->m->bvh, &q->args->ray, q->tmin, &q->tmax, leaf_of_cpu, q);
}

/* Every leaf whose box the ray may meet over the query's interval, which
 * the leaves narrow as they find hits. An interval from 0 or later is one
 * walk. One that starts before 0 (the whole line of a closed mesh's
 * all-hits list, or a caller's own) is walked in two halves, each from 0:
 * the reversed ray for t < 0, then the ray, each keeping the hits of its
 * half so that none is reported twice. accel's walk would take a negative
 * start by moving the origin back, but it culls nothing once that origin
 * is far out (tmin = -1e80) or the start is -inf: it visits every leaf,
 * where the two halves still cull. A NaN bound meets nothing, as in the
 * triangle test. */
static void walk(query *q)
{
    if (q->any_order) {
        walk_any_order(q);
        return;
    }
    leaf_fn leaf_of_cpu = leaf_callback();
    const accel_bvh4 *bvh = &q->m->bvh;
    const hr_ray *ray = &q->args->ray;
    if (isnan(q->tmin) || isnan(q->tmax)) return;
    if (q->tmin >= 0.0) {
        accel_bvh4_walk(bvh, ray, q->tmin, &q->tmax, leaf_of_cpu, q);
        return;
    }
    hr_ray back = *ray;
    back.dir.x = -ray->dir.x, back.dir.y = -ray->dir.y, back.dir.z = -ray->dir.z;
    /* Along the reversed ray, the hits tmin < t < tmax are at s = -t, from
     * -tmax (or 0) to -tmin; a nearer hit found there bounds nothing
     * ahead of it, so the walk's end stays put. */
    double back_end = -q->tmin;
    q->phase = -1;
    if (accel_bvh4_walk(bvh, &back, q->tmax < 0.0 ? -q->tmax : 0.0, &back_end, leaf_of_cpu, q) ==
        ACCEL_WALK_STOP)
        return;
    if (!(q->tmax >= 0.0)) return;
    q->phase = 1;
    q->back_end = q->mode == HR_TRACE_ALL ? q->args->out->count : 0;
    accel_bvh4_walk(bvh, ray, 0.0, &q->tmax, leaf_of_cpu, q);
}

/* Whether a crossing the first-hit search saw forms a near tie with its
 * best: of the other kind and within closed_slack of it. tie_error bounds
 * every crossing's error and the rounded slack grows with the errors, so
 * the slack with tie_error rules out most crossings without point_error. */
static int near_tie_with_best(const query *q, const seen_crossing *s)
{
    if (s->th.entering == q->best.entering) return 0;
    const hr_ray *ray = &q->args->ray;
    const double apart = fabs(s->th.t - q->best.t);
    const double t_errors = 2.0 * (s->th.t < q->best.t ? s->th.t_error : q->best.t_error);
    if (apart > slack_of(ray, q->tie_error, s->th.t, q->best_error, q->best.t, t_errors)) return 0;
    return apart <= slack_of(ray, point_error(q->m, s->tri, s->th.b), s->th.t, q->best_error, q->best.t,
                             t_errors);
}

/* Whether a crossing the first-hit search saw sorts before its best (in
 * the all-hits order, mesh_hit_before) as one that alternate_closed may
 * pair with a crossing as far as the best or past it: its slack, which
 * holds twice its own t error, reaches the best's t. Such a crossing lies
 * outside the caller's interval, or within its t error of tmin (else it
 * would be the best), and a pair of it and a crossing of the interval is
 * kept where it was refused only for its t error, or where the pair lies
 * at the other's t: one the search passed
 * over once its end had narrowed to the best's window, or one it saw past
 * the best but weighed against the best alone (a leaving crossing at t = 1
 * with a t error of 500, refused for it from tmin = 0, before a leaving
 * best at t = 1 with a t error of 1.4e-13, and the list moved an entering
 * crossing up from 1 + 5e-4 onto the first: a fuzz input). Its pair
 * with a crossing from past the caller's tmax is marked outside it: with
 * no best, no such pair keeps a hit. The slack's part
 * in |t| is taken at the best's t: past it the distance grows faster than
 * the slack. */
static int place_reaches_best(const query *q, const seen_crossing *s)
{
    if (s->tri == q->best_tri || !(s->th.t <= q->best.t)) return 0;
    const hr_ray *ray = &q->args->ray;
    const double apart = q->best.t - s->th.t;
    const double t_errors = 2.0 * s->th.t_error;
    if (!(apart <= slack_of(ray, q->tie_error, s->th.t, q->tie_error, q->best.t, t_errors))) return 0;
    if (s->th.t == q->best.t && (s->th.entering < q->best.entering ||
                                 (s->th.entering == q->best.entering &&
                                  q->m->bvh.items[s->tri] > q->m->bvh.items[q->best_tri])))
        return 0; /* at the best's t, after it */
    return apart <= slack_of(ray, point_error(q->m, s->tri, s->th.b), s->th.t, q->tie_error, q->best.t,
                             t_errors);
}

static hr_status trace_query(const mesh *m, const hr_hit_args *args, int32_t mode);

/* trace_query's answer once the walk is over. */
static hr_status finish_query(const mesh *m, const hr_hit_args *args, query *q)
{
    if (q->needs_first) return trace_query(m, args, HR_TRACE_FIRST);
    const int32_t start = q->start;
    int near_tie = q->found && (q->seen_overflow || q->window_unseen);
    for (int k = 0; q->found && !near_tie && k < q->seen_count; k++)
        near_tie = near_tie_with_best(q, &q->seen[k]) || place_reaches_best(q, &q->seen[k]);
    if (near_tie) {
        const hr_status st = mesh_trace(m, args, HR_TRACE_ALL);
        if (st == HR_OK && args->out->count > start + 1) args->out->count = start + 1;
        return st;
    }
    if (q->mode != HR_TRACE_ALL) {
        if (!q->found) return HR_OK;
        hr_hit *hit = &args->out->hits[args->out->count++];
        if (q->mode == HR_TRACE_ANY) fill_any_hit(m, &q->r, q->best_tri, &q->best, hit);
        else fill_hit(m, &args->ray, q->best_tri, &q->best, hit);
        return HR_OK;
    }
    hr_hit *hits = args->out->hits + start;
    const size_t count = (size_t)(args->out->count - start);
    sort_hits(hits, q->keys, count);
    if (q->whole_line) {
        alternate_closed(&args->ray, hits, q->keys, count);
        int32_t kept = start;
        for (size_t i = 0; i < count; i++) {
            if (hits[i].surface) continue;
            args->out->hits[kept] = hits[i];
            args->out->hits[kept++].surface = 0;
        }
        args->out->count = kept;
    }
    return HR_OK;
}

/* mesh_trace past its first question: out of line, so that the rays a
 * flat mesh turns away never enter its large frame. */
static __attribute__((noinline)) hr_status trace_query(const mesh *m, const hr_hit_args *args, int32_t mode)
{
    /* Field by field: the crossings' array stays unwritten until used. */
    query q;
    q.ray_ready = 0;
    q.m = m;
    q.args = args;
    q.status = HR_OK;
    q.phase = 0;
    q.back_end = 0;
    q.found = 0;
    q.best_tri = 0;
    q.best_error = 0.0;
    q.seen_count = q.seen_overflow = 0;
    q.window_unseen = 0;
    q.needs_first = 0;
    q.keys = q.key_room;
    q.key_capacity = sizeof q.key_room / sizeof *q.key_room;
    /* A closed mesh's any hit is its first hit: the all-hits repair (see
     * alternate_closed and the first-hit search below) may drop a touch at
     * a vertex whose crossings come out a rounding apart, and a shadow ray
     * must not be blocked by a touch a camera ray does not see. So any-hit
     * answers whether the first-hit search finds a hit: it stops at the
     * first hit it meets where that hit settles the answer
     * (closed_any_blocks: all but hits within a rounding of tmin or tmax),
     * and asks the first-hit search otherwise, and always for an interval
     * from before 0. */
    q.closed_any = mode == HR_TRACE_ANY && m->closed && args->tmin >= 0.0;
    if (mode == HR_TRACE_ANY && m->closed && !q.closed_any) mode = HR_TRACE_FIRST;
    q.mode = mode;
    /* An any-hit search still (an open mesh's, or closed_any) takes the
     * leaves in any order (walk_any_order). */
    q.any_order = mode == HR_TRACE_ANY && args->tmin >= 0.0;
    /* A closed mesh's first hit must be the first of its all-hits list,
     * which alternate_closed may have reordered where an entering and an
     * exiting crossing lie within rounding of each other (a ray through a
     * vertex or an edge: the two triangles' t differ by a few ulps, and the
     * nearer may be the exiting one). The all-hits query tests triangles
     * over the whole line, and a crossing it pairs may be one the
     * caller's interval refuses on its own (within its t error of tmin:
     * a degenerate triangle at a vertex can have a t error of 10). So the
     * first-hit search of a closed mesh tests triangles over the whole
     * line too, remembers the crossings it sees (its best hit kept to the
     * caller's interval), looks as far past its best hit as a near tie can
     * reach, and when one of them forms a near tie with the best, or there
     * were too many to remember, takes the answer from the all-hits list
     * itself (rare: rays through vertices and edges). */
    q.tie_check = mode == HR_TRACE_FIRST && m->closed;
    q.tie_error = m->largest_error;
    /* A closed mesh's list is put in order over the whole line (see
     * alternate_closed); hits outside (tmin, tmax) are dropped after. */
    q.whole_line = mode == HR_TRACE_ALL && m->closed;
    q.tmin = q.whole_line ? -INFINITY : args->tmin;
    q.tmax = q.whole_line ? INFINITY : args->tmax;
    /* A near tie may lie past the caller's tmax: alternate_closed pairs a
     * crossing from there with one inside the interval (an
     * entering crossing at t = tmax that rounding put just after an
     * exiting one at tmax - 1 ulp: found by fuzzing). So the first-hit
     * search sees crossings as far past tmax as the widest window of a
     * best hit before it reaches (both error bounds at most tie_error),
     * and takes none of them as its best; a best whose window, with its
     * t error, reaches further takes the answer from the all-hits list
     * (window_unseen in leaf_loop). */
    q.tie_end = args->tmax;
    if (q.tie_check)
        q.tmax = q.tie_end = mesh_next_up(args->tmax + 2.0 * q.tie_error / ray_speed(&args->ray) * 4.0 +
                                          16.0 * DBL_EPSILON * fabs(args->tmax));
    q.searched_end = q.tmax;
    q.start = args->out->count;
    walk(&q);
    const hr_status st = q.status ? q.status : finish_query(m, args, &q);
    if (q.keys != q.key_room) m->host->free(q.keys);
    return st;
}

hr_status mesh_trace(const mesh *m, const hr_hit_args *args, int32_t mode)
{
    /* A ray that leaves a flat mesh behind (one from the floor that is this
     * mesh, or its neighbour, which the scene's walk asks too): every walk
     * would find no leaf, being from args->tmin but for a closed mesh's
     * all-hits list. */
    if (m->flat_axis >= 0 && !(mode == HR_TRACE_ALL && m->closed) &&
        accel_bvh4_root_missed_on(&m->bvh, &args->ray, args->tmin, m->flat_axis, m->flat_lo, m->flat_hi))
        return HR_OK;
    return trace_query(m, args, mode);
}
