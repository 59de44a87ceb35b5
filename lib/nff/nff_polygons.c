/* NFF's polygons (lib/nff/nff_reader.h): `p n` then n vertices, `pp n` then n
 * vertices each with its normal. They become triangles of triangleMesh
 * objects, one for the flat and one for the smooth polygons of each
 * material, so a scene of thousands of polygons is a few objects with
 * their own BVH rather than thousands in the scene's.
 *
 * Triangulation. The SPD's polygons are planar and simple but not all
 * convex: a gear's face is one polygon of 144 vertices round its teeth. A
 * fan from one vertex would cover the gaps between the teeth, and even on
 * a convex polygon it makes long slivers whose boxes overlap everything.
 * So polygons are cut by ear clipping in the polygon's plane (projected
 * along its largest normal component, the Newell normal), always cutting
 * the best-shaped ear, the one of largest area for its edge lengths: a
 * quadrilateral is cut along its better diagonal, a convex polygon into
 * rounded triangles rather than a fan. Each cut is O(n) (the ear test of
 * the two neighbours and the choice of the next ear), O(n^2) in all; past
 * NFF_BEST_EAR_VERTICES a concave polygon's ears are tested against a grid
 * of its non-convex corners and chosen from a heap (nff_ear_index.h), about
 * O(n log n) for a simple polygon.
 * Past NFF_BEST_EAR_VERTICES vertices (no SPD polygon comes near) a convex
 * polygon is cut as a zigzag strip instead, O(n), whose triangles are as
 * round as a strip's can be; a concave one keeps ear clipping, which for
 * a polygon that is not simple falls back to a pass per cut, O(n^2): that
 * bounds how many vertices it may have (NFF_MAX_CONCAVE_VERTICES: seconds
 * at most, never a hang).
 * A vertex in line with its neighbours is dropped without a triangle (the
 * triangle has no area). A polygon that is not simple (no ear left, which
 * only a self-crossing polygon or rounding can cause) has its remaining
 * vertices cut at the best convex corner, else at any corner, so every
 * polygon ends; one with no area at all (a zero Newell normal) is dropped,
 * as the mesh module drops triangles with no area.
 *
 * The triangles keep the polygon's winding, so their geometric normals
 * face where the polygon's does. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "nff/nff_ear_index.h"
#include "nff/nff_reader.h"

/* Vertex indices of one mesh are 32-bit (the mesh module's limit). */
#define NFF_MAX_MESH_VERTICES 4294967294.0
#define NFF_BEST_EAR_VERTICES 1024
#define NFF_MAX_CONCAVE_VERTICES 16384
/* Steps of ear clipping (a corner tested against an ear, or scanned for
 * the next cut) one file may take in all: a self-crossing polygon of 16384
 * vertices takes about 10^8, so a file of hundreds of them (a few hundred
 * MB of text) would take many minutes. 2^30 is a few seconds; no simple
 * polygon comes near (the grid and the heap make its steps O(n log n)). */
#define NFF_CLIP_WORK_BUDGET ((uint64_t)1 << 30)

typedef ear_pt pt2;

static double orient(pt2 a, pt2 b, pt2 c)
{
    return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

static double dist2(pt2 a, pt2 b)
{
    return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}

static int same(pt2 a, pt2 b) { return a.x == b.x && a.y == b.y; }

typedef struct clipper {
    const pt2 *p;
    size_t *prev, *next;
    double *quality; /* of the ear at each vertex; -1: no ear; INFINITY: in line */
    /* Past NFF_BEST_EAR_VERTICES: the corners that were not convex at the
     * start (only those can lie in an ear of a simple polygon: a convex one
     * never turns reflex), and which corners are still there. */
    const ear_grid *grid;
    const unsigned char *alive;
    uint64_t *work; /* the file's steps (nff_reader.clip_work) */
} clipper;

static int in_ear(pt2 pa, pt2 pi, pt2 pb, pt2 q)
{
    if (same(q, pa) || same(q, pi) || same(q, pb)) return 0;
    return orient(pa, pi, q) >= 0.0 && orient(pi, pb, q) >= 0.0 && orient(pb, pa, q) >= 0.0;
}

/* Whether a corner of the grid other than a, i, b lies in their ear. */
static int grid_blocks(const clipper *c, size_t a, size_t i, size_t b)
{
    const pt2 pa = c->p[a], pi = c->p[i], pb = c->p[b];
    const pt2 lo = {fmin(pa.x, fmin(pi.x, pb.x)), fmin(pa.y, fmin(pi.y, pb.y))};
    const pt2 hi = {fmax(pa.x, fmax(pi.x, pb.x)), fmax(pa.y, fmax(pi.y, pb.y))};
    size_t x0, y0, x1, y1;
    ear_grid_range(c->grid, lo, hi, &x0, &y0, &x1, &y1);
    for (size_t y = y0; y <= y1; y++)
        for (size_t x = x0; x <= x1; x++) {
            const size_t cell = y * c->grid->nx + x;
            *c->work += c->grid->first[cell + 1] - c->grid->first[cell] + 1;
            for (size_t k = c->grid->first[cell]; k < c->grid->first[cell + 1]; k++) {
                const size_t j = c->grid->items[k];
                if (j != a && j != i && j != b && c->alive[j] && in_ear(pa, pi, pb, c->p[j])) return 1;
            }
        }
    return 0;
}

/* The ear at i, or why not: INFINITY for a vertex in line with its
 * neighbours (dropped first, without a triangle), -1 for a reflex corner
 * or one whose triangle holds another vertex, else the shape of the
 * triangle, area / (sum of squared edges), larger is rounder. */
static double ear_quality(const clipper *c, size_t i)
{
    const size_t a = c->prev[i], b = c->next[i];
    const pt2 pa = c->p[a], pi = c->p[i], pb = c->p[b];
    const double o = orient(pa, pi, pb);
    if (o == 0.0) return INFINITY;
    if (o < 0.0) return -1.0;
    if (c->grid) {
        if (grid_blocks(c, a, i, b)) return -1.0;
    } else {
        for (size_t j = c->next[b]; j != a; j = c->next[j]) {
            ++*c->work;
            if (in_ear(pa, pi, pb, c->p[j])) return -1.0;
        }
    }
    return o / (dist2(pa, pi) + dist2(pi, pb) + dist2(pb, pa));
}

/* The next corner to cut: the best ear; failing one, the best convex
 * corner; failing that, `start`. */
static size_t choose(const clipper *c, size_t start)
{
    size_t best = start, convex = start;
    double best_q = -1.0, convex_q = -INFINITY;
    size_t i = start;
    do {
        if (c->quality[i] > best_q) best_q = c->quality[i], best = i;
        const double o = orient(c->p[c->prev[i]], c->p[i], c->p[c->next[i]]);
        if (o > 0.0 && o > convex_q) convex_q = o, convex = i;
        i = c->next[i];
        ++*c->work;
    } while (i != start);
    return best_q >= 0.0 ? best : convex;
}

/* Triangles of the polygon p[0, n) (counter-clockwise) as index triples
 * into `tris`; returns how many (at most n - 2), or SIZE_MAX once *work
 * passes NFF_CLIP_WORK_BUDGET. `work_idx` holds 2 n indices (the lists'
 * links), `work_q` n qualities. */
static size_t clip_ears(const pt2 *p, size_t n, uint32_t *tris, size_t *work_idx, double *work_q,
                        const ear_grid *grid, unsigned char *alive, ear_heap *heap, uint64_t *work)
{
    clipper c = {p, work_idx, work_idx + n, work_q, grid, alive, work};
    for (size_t i = 0; i < n; i++) {
        c.prev[i] = i ? i - 1 : n - 1;
        c.next[i] = i + 1 < n ? i + 1 : 0;
    }
    for (size_t i = 0; i < n; i++) c.quality[i] = ear_quality(&c, i);
    if (heap)
        for (size_t i = 0; i < n; i++) ear_heap_update(heap, i);
    size_t left = n, count = 0, start = 0;
    while (left > 3) {
        if (*work > NFF_CLIP_WORK_BUDGET) return SIZE_MAX;
        /* The heap's top is choose's best ear but for ties, which it breaks
         * by the lower number rather than the ring's order from `start`. */
        const size_t top = heap ? ear_heap_top(heap) : EAR_HEAP_NONE;
        const size_t i = top != EAR_HEAP_NONE && c.quality[top] >= 0.0 ? top : choose(&c, start);
        const size_t a = c.prev[i], b = c.next[i];
        if (c.quality[i] != INFINITY) {
            tris[3 * count] = (uint32_t)a, tris[3 * count + 1] = (uint32_t)i;
            tris[3 * count + 2] = (uint32_t)b;
            count++;
        }
        c.next[a] = b;
        c.prev[b] = a;
        left--;
        start = a;
        c.quality[a] = ear_quality(&c, a);
        c.quality[b] = ear_quality(&c, b);
        if (heap) {
            alive[i] = 0;
            ear_heap_remove(heap, i);
            ear_heap_update(heap, a);
            ear_heap_update(heap, b);
        }
    }
    const size_t a = c.prev[start], b = c.next[start];
    if (orient(p[a], p[start], p[b]) != 0.0) {
        tris[3 * count] = (uint32_t)a, tris[3 * count + 1] = (uint32_t)start;
        tris[3 * count + 2] = (uint32_t)b;
        count++;
    }
    return count;
}

/* Ear clipping past NFF_BEST_EAR_VERTICES: the same cuts, each ear tested
 * against the corners of the grid cells its triangle covers and the best
 * ear taken from a heap, so a cut costs about log n rather than n. */
static hr_status clip_large(nff_reader *r, nff_word at, const pt2 *p, size_t n, uint32_t *tris,
                            size_t *work_idx, double *work_q, size_t *made)
{
    size_t *reflex = malloc(n * sizeof *reflex);
    unsigned char *alive = malloc(n);
    ear_grid grid = {0};
    ear_heap heap = {0};
    int ok = reflex && alive && ear_heap_init(&heap, n, work_q);
    size_t m = 0;
    if (ok) {
        for (size_t i = 0; i < n; i++) {
            alive[i] = 1;
            if (orient(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) <= 0.0) reflex[m++] = i;
        }
        ok = ear_grid_build(&grid, p, reflex, m);
    }
    if (ok) *made = clip_ears(p, n, tris, work_idx, work_q, &grid, alive, &heap, &r->clip_work);
    ear_grid_free(&grid);
    ear_heap_free(&heap);
    free(alive);
    free(reflex);
    return ok ? HR_OK
              : hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory for a polygon", r->file,
                         (int)at.line);
}

/* 1 if no corner of the counter-clockwise polygon turns clockwise. */
static int is_convex(const pt2 *p, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (orient(p[(i + n - 1) % n], p[i], p[(i + 1) % n]) < 0.0) return 0;
    return 1;
}

/* A convex polygon as a zigzag strip: (0, 1, n-1), (1, n-2, n-1),
 * (1, 2, n-2), ... taking corners from both ends in turn. Triangles with no
 * area (corners in line) are left out. */
static size_t zigzag(const pt2 *p, size_t n, uint32_t *tris)
{
    size_t lo = 0, hi = n - 1, count = 0;
    int from_low = 1;
    while (hi - lo >= 2) {
        size_t a, b, c;
        if (from_low) a = lo, b = lo + 1, c = hi, lo++;
        else a = lo, b = hi - 1, c = hi, hi--;
        from_low = !from_low;
        if (orient(p[a], p[b], p[c]) == 0.0) continue;
        tris[3 * count] = (uint32_t)a, tris[3 * count + 1] = (uint32_t)b;
        tris[3 * count + 2] = (uint32_t)c;
        count++;
    }
    return count;
}

/* The polygon in its own plane, counter-clockwise: dropped along the
 * largest component of the Newell normal, mirrored if it turned clockwise.
 * 0 if the polygon has no area. */
static int project(const hr_vec3 *v, size_t n, pt2 *out)
{
    /* Everything on the coordinates scaled by a power of two that brings
     * the largest near 1: exact, so the cuts are those of the coordinates
     * as read, but neither the normal's products nor the clipper's
     * overflow for a polygon near 1e308 (which came out as NaN and had the
     * polygon dropped as having no area) or underflow near 1e-300. */
    double big = 0.0;
    for (size_t i = 0; i < n; i++)
        big = fmax(big, fmax(fabs(v[i].x), fmax(fabs(v[i].y), fabs(v[i].z))));
    const double scale = big > 0.0 && isfinite(big) ? ldexp(1.0, -ilogb(big)) : 1.0;
    double nx = 0, ny = 0, nz = 0;
    for (size_t i = 0; i < n; i++) {
        const hr_vec3 p = v[i], q = v[(i + 1) % n];
        const hr_vec3 a = {p.x * scale, p.y * scale, p.z * scale};
        const hr_vec3 b = {q.x * scale, q.y * scale, q.z * scale};
        nx += (a.y - b.y) * (a.z + b.z);
        ny += (a.z - b.z) * (a.x + b.x);
        nz += (a.x - b.x) * (a.y + b.y);
    }
    const double ax = fabs(nx), ay = fabs(ny), az = fabs(nz);
    if (!(ax > 0.0 || ay > 0.0 || az > 0.0)) return 0;
    double area = 0.0;
    for (size_t i = 0; i < n; i++) {
        /* Keep the two coordinates across the dropped axis. */
        const hr_vec3 a = {v[i].x * scale, v[i].y * scale, v[i].z * scale};
        if (az >= ax && az >= ay) out[i] = (pt2){a.x, a.y};
        else if (ay >= ax) out[i] = (pt2){a.z, a.x};
        else out[i] = (pt2){a.y, a.z};
    }
    for (size_t i = 0; i < n; i++) {
        const pt2 a = out[i], b = out[(i + 1) % n];
        area += a.x * b.y - b.x * a.y;
    }
    if (area == 0.0) return 0;
    if (area < 0.0)
        for (size_t i = 0; i < n; i++) out[i].y = -out[i].y;
    return 1;
}

void nff_batch_release(nff_mesh_batch *b)
{
    free(b->points);
    free(b->normals);
    free(b->triangles);
    int smooth = b->smooth;
    memset(b, 0, sizeof *b);
    b->smooth = smooth;
}

/* Room for `more` items of `per` doubles in *array of *capacity items. */
static int grow(double **array, size_t *capacity, size_t count, size_t more, size_t per)
{
    if (count + more <= *capacity) return 0;
    size_t cap = *capacity ? *capacity : 256;
    while (cap < count + more) {
        if (cap > SIZE_MAX / 2 / per / sizeof(double)) return -1;
        cap *= 2;
    }
    double *grown = realloc(*array, cap * per * sizeof *grown);
    if (!grown) return -1;
    *array = grown;
    *capacity = cap;
    return 0;
}

static hr_status append(nff_reader *r, nff_word at, nff_mesh_batch *b, const hr_vec3 *v,
                        const hr_vec3 *normals, size_t n, const uint32_t *tris, size_t count)
{
    if ((double)b->point_count + (double)n > NFF_MAX_MESH_VERTICES)
        return nff_error(r, HR_ERROR_SDL, at,
                         "the polygons of one material have more than %.0f vertices",
                         NFF_MAX_MESH_VERTICES);
    if (grow(&b->points, &b->point_capacity, b->point_count, n, 3) ||
        (b->smooth && grow(&b->normals, &b->normal_capacity, b->point_count, n, 3)) ||
        grow(&b->triangles, &b->triangle_capacity, b->triangle_count, count, 3))
        return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory for polygons",
                        r->file, (int)at.line);
    if (b->point_count == 0 && b->triangle_count == 0) b->first = at;
    for (size_t i = 0; i < n; i++) {
        double *p = b->points + 3 * (b->point_count + i);
        p[0] = v[i].x, p[1] = v[i].y, p[2] = v[i].z;
        if (b->smooth) {
            double *q = b->normals + 3 * (b->point_count + i);
            q[0] = normals[i].x, q[1] = normals[i].y, q[2] = normals[i].z;
        }
    }
    for (size_t t = 0; t < 3 * count; t++)
        b->triangles[3 * b->triangle_count + t] = (double)(b->point_count + tris[t]);
    b->point_count += n;
    b->triangle_count += count;
    return HR_OK;
}

hr_status nff_read_polygon(nff_reader *r, nff_word p, int smooth)
{
    /* Each vertex takes at least "0 0 0" and a separator (pp: twice that),
     * so the text left bounds the count before anything is allocated. */
    const size_t bytes = smooth ? 12 : 6;
    int64_t n;
    hr_status st = nff_read_count(r, p, "the number of vertices", 3, 4294967294.0, &n);
    if (st) return st;
    if ((uint64_t)n > (nff_remaining(&r->lx) + 1) / bytes)
        return nff_error(r, HR_ERROR_SDL, p,
                         "'%.*s %lld': %lld vertices need at least %llu bytes, and the file has "
                         "%zu left",
                         (int)p.length, p.text, (long long)n, (long long)n,
                         (unsigned long long)n * bytes - 1, nff_remaining(&r->lx));
    const size_t count = (size_t)n;
    /* One block: vertices, normals, the plane's points, the triangles, the
     * clipper's lists and qualities. */
    const size_t size = count * (2 * sizeof(hr_vec3) + sizeof(pt2) + 3 * sizeof(uint32_t) +
                                 2 * sizeof(size_t) + sizeof(double));
    char *block = malloc(size);
    if (!block)
        return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "%s:%d: out of memory for a polygon",
                        r->file, (int)p.line);
    hr_vec3 *v = (hr_vec3 *)block, *normals = v + count;
    pt2 *plane = (pt2 *)(normals + count);
    double *quality = (double *)(plane + count);
    size_t *idx = (size_t *)(quality + count);
    uint32_t *tris = (uint32_t *)(idx + 2 * count);
    for (size_t i = 0; i < count && !st; i++) {
        double x[6];
        st = nff_read_numbers(r, p, smooth ? "x y z nx ny nz of each vertex" : "x y z of each vertex",
                              smooth ? 6 : 3, x, NULL);
        v[i] = (hr_vec3){x[0], x[1], x[2]};
        if (smooth) normals[i] = (hr_vec3){x[3], x[4], x[5]};
    }
    if (!st && project(v, count, plane)) {
        const int strip = count > NFF_BEST_EAR_VERTICES && is_convex(plane, count);
        if (!strip && count > NFF_MAX_CONCAVE_VERTICES) {
            free(block);
            return nff_error(r, HR_ERROR_SDL, p,
                             "'%.*s %zu' is a concave polygon of more than %d vertices, which "
                             "ear clipping would take too long over: split it",
                             (int)p.length, p.text, count, NFF_MAX_CONCAVE_VERTICES);
        }
        size_t made = 0;
        if (strip) made = zigzag(plane, count, tris);
        else if (count <= NFF_BEST_EAR_VERTICES)
            made = clip_ears(plane, count, tris, idx, quality, NULL, NULL, NULL, &r->clip_work);
        else if ((st = clip_large(r, p, plane, count, tris, idx, quality, &made))) {
            free(block);
            return st;
        }
        if (made == SIZE_MAX) {
            free(block);
            return nff_error(r, HR_ERROR_SDL, p,
                             "'%.*s %zu': ear clipping this file's polygons passed its budget of %llu "
                             "steps here (self-crossing concave polygons cost n^2 each): split them "
                             "or make them simple",
                             (int)p.length, p.text, count, (unsigned long long)NFF_CLIP_WORK_BUDGET);
        }
        if (made) st = append(r, p, smooth ? &r->smooth : &r->flat, v, normals, count, tris, made);
    }
    free(block);
    return st;
}

static hr_status flush(nff_reader *r, nff_mesh_batch *b)
{
    if (b->triangle_count == 0) {
        nff_batch_release(b);
        return HR_OK;
    }
    hr_param params[3];
    memset(params, 0, sizeof params);
    params[0].name = "points";
    params[0].type = HR_PARAM_NUMBERS;
    params[0].numbers = b->points;
    params[0].count = (int64_t)(3 * b->point_count);
    params[1].name = "triangles";
    params[1].type = HR_PARAM_NUMBERS;
    params[1].numbers = b->triangles;
    params[1].count = (int64_t)(3 * b->triangle_count);
    params[2].name = "normals";
    params[2].type = HR_PARAM_NUMBERS;
    params[2].numbers = b->normals;
    params[2].count = (int64_t)(3 * b->point_count);
    hr_status st = nff_add_object(r, b->first, "triangleMesh", params, b->smooth ? 3 : 2, NULL);
    nff_batch_release(b);
    return st;
}

hr_status nff_flush_polygons(nff_reader *r)
{
    hr_status st = flush(r, &r->flat);
    hr_status st2 = flush(r, &r->smooth);
    return st ? st : st2;
}
