/* (u, v) on a mesh (hr_shape_class.surface_uv): the OBJ file's texture
 * coordinates, interpolated across the triangle under the hit point.
 *
 * The host gives the hit's point and normal in object space, not its
 * triangle, so the triangle is found again: a short probe along the normal
 * through the point, from a little outside to a little inside the surface,
 * walks the BVH and keeps the crossing nearest the point. The probe's half
 * length is 1e-7 of the mesh's size: far beyond the point's rounding (some
 * 1e-15 of it), far below any triangle worth texturing. Where the probe
 * meets nothing (a point on a silhouette edge, seen exactly edge-on) the
 * answer is the first corner's coordinates of the first triangle: defined,
 * if not meaningful, for a point no pixel shows. */
#include <math.h>

#include "mesh.h"
#include "mesh_triangle.h"

typedef struct uv_probe {
    const mesh *m;
    mesh_ray r;
    double half; /* the point is at t = half along the probe */
    double gap;  /* |t - half| of the best crossing so far */
    uint32_t tri;
    double b[3];
    int found;
} uv_probe;

static int visit_leaf(void *user, uint32_t first, uint32_t count)
{
    uv_probe *q = user;
    const mesh *m = q->m;
    for (uint32_t i = first; i < first + count; i++) {
        const uint32_t *c = m->corners + 3 * (size_t)i;
        mesh_triangle_hit th;
        if (!mesh_triangle_test(&q->r, &m->vertices[c[0]], &m->vertices[c[1]], &m->vertices[c[2]], 0.0,
                                2.0 * q->half, &th))
            continue;
        const double gap = fabs(th.t - q->half);
        /* At an equal gap (coincident triangles), the lower index in the
         * file, whatever order the walk takes. */
        if (q->found && !(gap < q->gap || (gap == q->gap && m->bvh.items[i] < m->bvh.items[q->tri]))) continue;
        q->found = 1, q->gap = gap, q->tri = i;
        q->b[0] = th.b[0], q->b[1] = th.b[1], q->b[2] = th.b[2];
    }
    return ACCEL_WALK_GO_ON;
}

int32_t mesh_uv(const void *shape, const hr_hit *hit, double uv[2])
{
    const mesh *m = shape;
    if (!hit || !uv) return m->corner_texcoords != NULL;
    uv[0] = uv[1] = 0.0;
    if (!m->corner_texcoords) return 1;
    const hr_bounds *bb = &m->bounds;
    const double size = fmax(fmax(fabs(bb->lo.x), fabs(bb->hi.x)),
                             fmax(fmax(fabs(bb->lo.y), fabs(bb->hi.y)), fmax(fabs(bb->lo.z), fabs(bb->hi.z))));
    const hr_vec3 n = hit->normal;
    const double len = sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    uv_probe q = {.m = m, .half = 1e-7 * size};
    uint32_t tri = 0;
    double b[3] = {1.0, 0.0, 0.0};
    if (len > 0.0 && isfinite(len) && q.half > 0.0 && isfinite(q.half)) {
        const hr_vec3 u = {n.x / len, n.y / len, n.z / len};
        const hr_ray probe = {{hit->point.x + q.half * u.x, hit->point.y + q.half * u.y,
                               hit->point.z + q.half * u.z},
                              {-u.x, -u.y, -u.z}};
        double tmax = 2.0 * q.half;
        if (mesh_ray_init(&q.r, &probe)) accel_bvh4_walk(&m->bvh, &probe, 0.0, &tmax, visit_leaf, &q);
        if (q.found) tri = q.tri, b[0] = q.b[0], b[1] = q.b[1], b[2] = q.b[2];
    }
    const uint32_t *tc = m->corner_texcoords + 3 * (size_t)tri;
    for (int k = 0; k < 3; k++) {
        uv[0] += b[k] * m->texcoords[tc[k]].u;
        uv[1] += b[k] * m->texcoords[tc[k]].v;
    }
    return 1;
}
