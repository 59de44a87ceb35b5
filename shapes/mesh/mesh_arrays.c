/* A mesh from arrays the caller hands over (class `triangleMesh`), for
 * programs and readers that make their triangles in memory, such as the NFF
 * reader's polygons: no file is written and read back.
 *
 * Parameters (HR_PARAM_NUMBERS, see include/hitray/common.h):
 *   points     x y z of each vertex
 *   triangles  three vertex indices per triangle, counted from 0
 *   normals    optional: x y z per vertex (the same count as points), the
 *              shading normals interpolated across each triangle
 * The host has checked that every element is finite and every index within
 * [0, MESH_MAX_COUNT]; here the counts are checked against each other and
 * each index against the vertex count. The triangles then go through the
 * same builder as the files' (triangles with two corners at one point are
 * skipped), so hits are the same watertight test. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <hitray/shape_kit_module.h>

#include "mesh.h"
#include "mesh_arrays.h"
#include "mesh_text.h"

static const hr_param *find(const hr_create_args *args, const char *name)
{
    const hr_param *p = shape_param(args, name);
    return p && p->type == HR_PARAM_NUMBERS ? p : NULL;
}

static size_t element_count(const hr_param *p)
{
    return p && p->count > 0 ? (size_t)p->count : 0;
}

/* Checks every count and index before anything is allocated. */
static hr_status check_arrays(const hr_param *points, const hr_param *normals,
                              const hr_param *triangles, char *error, size_t error_size)
{
    const size_t np = element_count(points), nn = element_count(normals),
                 nt = element_count(triangles);
    if (np % 3 || np == 0) {
        snprintf(error, error_size,
                 "parameter 'points' must hold 3 numbers per vertex and at least one vertex, "
                 "not %zu numbers",
                 np);
        return HR_ERROR_PARAMETER;
    }
    if (nt % 3 || nt == 0) {
        snprintf(error, error_size,
                 "parameter 'triangles' must hold 3 vertex indices per triangle and at least "
                 "one triangle, not %zu numbers",
                 nt);
        return HR_ERROR_PARAMETER;
    }
    if (nn != 0 && nn != np) {
        snprintf(error, error_size,
                 "parameter 'normals' must be empty or hold one normal per vertex (%zu numbers), "
                 "not %zu numbers",
                 np, nn);
        return HR_ERROR_PARAMETER;
    }
    if (np / 3 > MESH_MAX_COUNT || nt / 3 > MESH_MAX_COUNT) {
        snprintf(error, error_size, "more than %zu vertices or triangles", MESH_MAX_COUNT);
        return HR_ERROR_PARAMETER;
    }
    /* The host checked these; a host (or test) that did not gets the same
     * answer, never a mesh with NaN corners. */
    for (size_t i = 0; i < np; i++)
        if (!isfinite(points->numbers[i]) || (nn && !isfinite(normals->numbers[i]))) {
            snprintf(error, error_size, "element %zu of parameter '%s' is not a finite number",
                     i, isfinite(points->numbers[i]) ? "normals" : "points");
            return HR_ERROR_PARAMETER;
        }
    /* The readers' coordinate limit (mesh_text.h): the triangle test
     * multiplies three coordinates, which must stay inside double's range;
     * past it the edge functions overflow and a hit's barycentric point
     * comes out anywhere. */
    for (size_t i = 0; i < np; i++)
        if (fabs(points->numbers[i]) > MESH_MAX_COORDINATE) {
            snprintf(error, error_size,
                     "element %zu of parameter 'points' is %g, beyond the coordinates a mesh "
                     "takes (at most %g)",
                     i, points->numbers[i], MESH_MAX_COORDINATE);
            return HR_ERROR_PARAMETER;
        }
    const double vertex_count = (double)(np / 3);
    for (size_t i = 0; i < nt; i++) {
        const double v = triangles->numbers[i];
        if (!(v >= 0.0 && v < vertex_count && v == floor(v))) {
            snprintf(error, error_size,
                     "parameter 'triangles': element %zu (corner %zu of triangle %zu) is %g, "
                     "not a vertex index in [0, %zu)",
                     i, i % 3, i / 3, v, np / 3);
            return HR_ERROR_PARAMETER;
        }
    }
    return HR_OK;
}

static int fill(mesh_builder *b, const hr_param *points, const hr_param *normals,
                const hr_param *triangles)
{
    const size_t vertices = element_count(points) / 3, with_normals = element_count(normals) > 0,
                 count = element_count(triangles) / 3;
    if (mesh_builder_reserve(b, vertices, with_normals ? vertices : 0, count)) return -1;
    for (size_t i = 0; i < vertices; i++) {
        const double *p = points->numbers + 3 * i;
        if (mesh_builder_add_vertex(b, (hr_vec3){p[0], p[1], p[2]})) return -1;
        if (with_normals) {
            const double *n = normals->numbers + 3 * i;
            if (mesh_builder_add_normal(b, (hr_vec3){n[0], n[1], n[2]})) return -1;
        }
    }
    for (size_t t = 0; t < count; t++) {
        const double *c = triangles->numbers + 3 * t;
        const uint32_t corners[3] = {(uint32_t)c[0], (uint32_t)c[1], (uint32_t)c[2]};
        if (mesh_builder_add_polygon(b, corners, with_normals ? corners : NULL, 3)) return -1;
    }
    return 0;
}

hr_status mesh_arrays_create(const hr_create_args *args, mesh **out)
{
    *out = NULL;
    const hr_param *points = find(args, "points"), *normals = find(args, "normals"),
                   *triangles = find(args, "triangles");
    hr_status st = check_arrays(points, normals, triangles, args->error, args->error_size);
    if (st) return st;
    mesh_builder b;
    mesh_builder_init(&b, args->host);
    st = fill(&b, points, normals, triangles)
             ? HR_ERROR_OUT_OF_MEMORY
             : mesh_builder_finish(&b, out, args->error, args->error_size);
    mesh_builder_release(&b);
    if (st == HR_ERROR_OUT_OF_MEMORY)
        snprintf(args->error, args->error_size, "out of memory building a mesh of %zu triangles",
                 element_count(triangles) / 3);
    return st;
}
