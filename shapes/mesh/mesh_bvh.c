/* The mesh's BVH: accel/'s 4-wide BVH (the scene's too) over the
 * triangles' boxes, with the triangles then put in its leaf order, so a
 * leaf is a run of the corner array.
 *
 * A triangle's box is the float box of its corners rounded outward and
 * grown by one more float ulp on every side: it contains every point the
 * double-precision triangle test can accept (whose sheared corners are off
 * by a few double roundings), and being float already, accel keeps it
 * exactly when it rounds child boxes to float. */
#include <float.h>
#include <math.h>
#include <string.h>

#include "mesh.h"

/* The cost of visiting a node, in triangle tests (the SAH's constant). A
 * node tests four boxes in about as many instructions as one watertight
 * triangle test, but nodes cost memory; 2 takes most of the speed of 1 for
 * less memory (measured: bench/results/RESULTS.md, "The mesh BVH's traversal
 * cost"). */
#define TRAVERSAL_COST 2.0

static void triangle_box(const mesh *m, uint32_t t, hr_bounds *out)
{
    const uint32_t *c = m->corners + 3 * (size_t)t;
    double lo[3], hi[3];
    for (int a = 0; a < 3; a++) {
        lo[a] = INFINITY, hi[a] = -INFINITY;
        for (int k = 0; k < 3; k++) {
            const hr_vec3 *v = &m->vertices[c[k]];
            double x = a == 0 ? v->x : a == 1 ? v->y : v->z;
            if (x < lo[a]) lo[a] = x;
            if (x > hi[a]) hi[a] = x;
        }
        /* nextafterf, not accel_float_below: the side may be infinite. */
        lo[a] = nextafterf(accel_float_down(lo[a]), -INFINITY);
        hi[a] = nextafterf(accel_float_up(hi[a]), INFINITY);
    }
    out->lo = (hr_vec3){lo[0], lo[1], lo[2]};
    out->hi = (hr_vec3){hi[0], hi[1], hi[2]};
}

hr_status mesh_bvh_build(mesh *m)
{
    const hr_host *host = m->host;
    const size_t n = m->triangle_count;
    hr_bounds *boxes = host->alloc(n * sizeof *boxes);
    uint32_t *corners = host->alloc(3 * n * sizeof *corners);
    uint32_t *corner_normals = m->corner_normals ? host->alloc(3 * n * sizeof *corner_normals) : NULL;
    uint32_t *corner_texcoords =
        m->corner_texcoords ? host->alloc(3 * n * sizeof *corner_texcoords) : NULL;
    hr_status st = HR_OK;
    if (!boxes || !corners || (m->corner_normals && !corner_normals) ||
        (m->corner_texcoords && !corner_texcoords)) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    for (uint32_t t = 0; t < n; t++) triangle_box(m, t, &boxes[t]);
    /* One thread: the host charges what a shape allocates to its scene
     * through the creating thread (hr_host.alloc), which a thread of the
     * build would bypass. */
    const accel_bvh4_options options = {MESH_BVH_MAX_LEAF, TRAVERSAL_COST, host->alloc, host->free, 1, 1};
    /* The count was checked against ACCEL_BVH4_MAX_ITEMS by the caller:
     * only memory can fail. */
    if (accel_bvh4_build(&m->bvh, boxes, (uint32_t)n, &options) != 0) {
        st = HR_ERROR_OUT_OF_MEMORY;
        goto done;
    }
    host->free(boxes);
    boxes = NULL;
    /* Triangles in leaf order. The BVH's order array stays: each
     * triangle's index in the file, which breaks exact ties (mesh_trace.c). */
    const uint32_t *order = m->bvh.items;
    for (size_t i = 0; i < n; i++) {
        memcpy(corners + 3 * i, m->corners + 3 * (size_t)order[i], 3 * sizeof *corners);
        if (corner_normals)
            memcpy(corner_normals + 3 * i, m->corner_normals + 3 * (size_t)order[i],
                   3 * sizeof *corner_normals);
        if (corner_texcoords)
            memcpy(corner_texcoords + 3 * i, m->corner_texcoords + 3 * (size_t)order[i],
                   3 * sizeof *corner_texcoords);
    }
    host->free(m->corners);
    m->corners = corners;
    corners = NULL;
    if (corner_normals) {
        host->free(m->corner_normals);
        m->corner_normals = corner_normals;
        corner_normals = NULL;
    }
    if (corner_texcoords) {
        host->free(m->corner_texcoords);
        m->corner_texcoords = corner_texcoords;
        corner_texcoords = NULL;
    }
    /* The object's bounds, exact: those of the corners of its triangles. */
    hr_vec3 lo = {INFINITY, INFINITY, INFINITY}, hi = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * n; i++) {
        const hr_vec3 v = m->vertices[m->corners[i]];
        lo.x = fmin(lo.x, v.x), lo.y = fmin(lo.y, v.y), lo.z = fmin(lo.z, v.z);
        hi.x = fmax(hi.x, v.x), hi.y = fmax(hi.y, v.y), hi.z = fmax(hi.z, v.z);
    }
    m->bounds.lo = lo;
    m->bounds.hi = hi;
    m->flat_axis = lo.z == hi.z ? 2 : lo.y == hi.y ? 1 : lo.x == hi.x ? 0 : -1;
    if (m->flat_axis >= 0) accel_bvh4_root_span(&m->bvh, m->flat_axis, &m->flat_lo, &m->flat_hi);
done:
    host->free(boxes);
    host->free(corners);
    host->free(corner_normals);
    host->free(corner_texcoords);
    return st;
}
