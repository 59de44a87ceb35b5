/* Tessellating a bicubic Bezier patch (mesh_bezier.h).
 *
 * Points come from de Casteljau's construction, with one twist: each
 * interpolation a + s (b - a) is written from the nearer end (s below one
 * half: from a; above: from b with 1 - s; at one half exactly: the mean).
 * The rule gives the same bits whichever way round a curve is walked, so a
 * side shared by two patches, walked forwards by one and backwards by the
 * other, or as a row by one and a column by the other, has the same
 * vertices in both; and four equal control points give that point exactly,
 * so a pole is one vertex and its slivers are found and skipped. The
 * parameters are k / level and (level - k) / level, each rounded once, so
 * walking back swaps them exactly.
 *
 * Normals: Pu x Pv, where Pu and Pv are the partial derivatives (three
 * times the difference of de Casteljau's last two points). At a pole one of
 * them is zero; there the normal is the limit of Pu x Pv along the patch,
 * which is Puv x Pv when Pu vanishes (Pu grows as v Puv away from the side
 * v = 0) and Pu x Puv when Pv does. */
#include <math.h>

#include "mesh_bezier.h"

/* A derivative this much smaller than the other (relative to it) has
 * vanished: the side is a pole. Far below the relative size of any
 * derivative of a patch one would draw, far above rounding's 1e-16. */
#define POLE_RATIO 1e-12

static hr_vec3 lerp(hr_vec3 a, hr_vec3 b, double s, double r)
{
    if (s < r) return (hr_vec3){a.x + s * (b.x - a.x), a.y + s * (b.y - a.y), a.z + s * (b.z - a.z)};
    if (r < s) return (hr_vec3){b.x + r * (a.x - b.x), b.y + r * (a.y - b.y), b.z + r * (a.z - b.z)};
    return (hr_vec3){(a.x + b.x) * 0.5, (a.y + b.y) * 0.5, (a.z + b.z) * 0.5};
}

static hr_vec3 sub(hr_vec3 a, hr_vec3 b) { return (hr_vec3){a.x - b.x, a.y - b.y, a.z - b.z}; }
static hr_vec3 scale(hr_vec3 a, double k) { return (hr_vec3){k * a.x, k * a.y, k * a.z}; }
static double length(hr_vec3 a) { return sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }
static hr_vec3 cross(hr_vec3 a, hr_vec3 b)
{
    return (hr_vec3){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* The cubic through p[0], p[stride], p[2 stride], p[3 stride] at parameter
 * s (r = 1 - s): its point, and its derivative in *d. */
static hr_vec3 cubic(const hr_vec3 *p, int stride, double s, double r, hr_vec3 *d)
{
    const hr_vec3 a = lerp(p[0], p[stride], s, r), b = lerp(p[stride], p[2 * stride], s, r),
                  c = lerp(p[2 * stride], p[3 * stride], s, r);
    const hr_vec3 q0 = lerp(a, b, s, r), q1 = lerp(b, c, s, r);
    *d = scale(sub(q1, q0), 3.0);
    return lerp(q0, q1, s, r);
}

/* The surface point at (u, v) given as (su, ru) and (sv, rv), and its unit
 * normal in *normal (1), or 0 when the normal has no limit there. */
static int surface(const hr_vec3 control[16], double su, double ru, double sv, double rv,
                   hr_vec3 *point, hr_vec3 *normal)
{
    hr_vec3 rows[4], row_du[4];
    for (int j = 0; j < 4; j++) rows[j] = cubic(control + 4 * j, 1, su, ru, &row_du[j]);
    hr_vec3 pv, puv;
    *point = cubic(rows, 1, sv, rv, &pv);
    const hr_vec3 pu = cubic(row_du, 1, sv, rv, &puv);
    const double lu = length(pu), lv = length(pv);
    hr_vec3 n;
    if (lu <= POLE_RATIO * lv) n = cross(puv, pv);
    else if (lv <= POLE_RATIO * lu) n = cross(pu, puv);
    else n = cross(pu, pv);
    const double ln = length(n);
    if (!(ln > 0.0) || !isfinite(ln)) return 0;
    *normal = scale(n, 1.0 / ln);
    return 1;
}

int mesh_bezier_add_patch(mesh_builder *b, const hr_vec3 control[16], uint32_t level)
{
    /* The vertex and normal indices of the previous row of the grid and of
     * this one (MESH_NO_NORMAL where a vertex has none). */
    uint32_t vertex[2][MESH_BEZIER_MAX_LEVEL + 1], normal[2][MESH_BEZIER_MAX_LEVEL + 1];
    if (level < 1 || level > MESH_BEZIER_MAX_LEVEL) return -1;
    const double n = (double)level;
    for (uint32_t j = 0; j <= level; j++) {
        const double sv = (double)j / n, rv = (double)(level - j) / n;
        uint32_t *row = vertex[j & 1], *row_normal = normal[j & 1];
        for (uint32_t i = 0; i <= level; i++) {
            hr_vec3 p, nrm;
            const int has_normal =
                surface(control, (double)i / n, (double)(level - i) / n, sv, rv, &p, &nrm);
            row[i] = (uint32_t)b->vertex_count;
            if (mesh_builder_add_vertex(b, p)) return -1;
            row_normal[i] = MESH_NO_NORMAL;
            if (has_normal) {
                row_normal[i] = (uint32_t)b->normal_count;
                if (mesh_builder_add_normal(b, nrm)) return -1;
            }
        }
        if (j == 0) continue;
        const uint32_t *below = vertex[(j - 1) & 1], *below_normal = normal[(j - 1) & 1];
        for (uint32_t i = 0; i < level; i++) {
            /* (i, j-1), (i+1, j-1), (i+1, j), (i, j): counter-clockwise
             * about Pu x Pv. Fanned from the first corner, so a pole side
             * costs one of the two triangles whichever side it is. */
            const uint32_t quad[4] = {below[i], below[i + 1], row[i + 1], row[i]};
            const uint32_t quad_normal[4] = {below_normal[i], below_normal[i + 1],
                                             row_normal[i + 1], row_normal[i]};
            if (mesh_builder_add_polygon(b, quad, quad_normal, 4)) return -1;
        }
    }
    return 0;
}
