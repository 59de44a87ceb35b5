/* The mesh module: triangle and polygon meshes read from files (class
 * `mesh`, parameter `file`), meshes handed over as arrays (class
 * `triangleMesh`, mesh_arrays.c), Hill's regular solids and buckyball built
 * in code (`tetrahedron`, `octahedron`, `dodecahedron`, `icosahedron`,
 * `buckyball`; mesh_solids.c) and Newell's teapot tessellated from its
 * Bezier patches (`teapot`, parameter `tessellation`; mesh_teapot.c).
 *
 * Files: Hill's chapter-6 format (.3vn) or Wavefront OBJ (.obj), see
 * mesh_read_3vn.c and mesh_read_obj.c; a relative name is taken from the
 * scene file's directory (hr_create_args.base_dir). Errors name the file and
 * line. Triangles with two corners at one point have no area and are
 * skipped; a file left with no triangle is refused.
 *
 * Hits: the watertight test of mesh_triangle.h over accel/'s 4-wide BVH,
 * the scene's too (mesh_bvh.c, mesh_trace.c). Surface ids: a mesh is one
 * surface, 0.
 * Entering flags come from the geometric normal (B - A) x (C - A) of each
 * triangle, so a consistently wound closed mesh (counter-clockwise seen
 * from outside, as Hill's files are) is entered and left in turn.
 *
 * Flags: the regular solids are closed (HR_SHAPE_CLOSED). The `mesh` class
 * is not: a file may hold an open surface, whose hits are all reported but
 * need not alternate. A file mesh whose every edge is used once in each
 * direction is closed all the same, and its all-hits lists alternate (the
 * same repair as the solids'); a CSG operand should be such a mesh. */
#include <stdio.h>
#include <string.h>

#include <float.h>
#include <math.h>

#include <hitray/shape_kit_hits.h>
#include <hitray/shape_kit_module.h>

#include "../common/shape_builtin.h"
#include "mesh.h"
#include "mesh_arrays.h"
#include "mesh_bezier.h"
#include "mesh_file.h"
#include "mesh_teapot.h"

/* A ray with an infinite or NaN component has no finite point but its
 * origin (o + t d is infinite or NaN in that coordinate for every t != 0),
 * so it has no hit the contract lets a shape report: it is answered with
 * none before the triangle test, whose shear would divide by it. */
static int ray_is_finite(const hr_ray *r)
{
    return isfinite(r->origin.x) && isfinite(r->origin.y) && isfinite(r->origin.z) &&
           isfinite(r->dir.x) && isfinite(r->dir.y) && isfinite(r->dir.z);
}

/* A ray that is not finite meets nothing (and is not traced). */
static hr_status mesh_trace_finite(const hr_hit_args *args, int32_t mode)
{
    if (!ray_is_finite(&args->ray)) return HR_OK;
    return mesh_trace(args->shape, args, mode);
}

SHAPE_DEFINE_HIT_MODES(mesh, mesh_trace_finite)

static void mesh_bounds(const void *shape, hr_bounds *out)
{
    *out = ((const mesh *)shape)->bounds;
}

static void mesh_destroy_shape(void *shape)
{
    mesh_destroy(shape);
}

static hr_status mesh_create(const hr_create_args *args, void **out_shape)
{
    *out_shape = NULL;
    const hr_param *file_param = shape_param(args, "file");
    const char *file = file_param && file_param->type == HR_PARAM_STRING ? file_param->string : NULL;
    mesh *m = NULL;
    hr_status st = mesh_load_file(args, file, &m);
    if (st) return st;
    *out_shape = m;
    return HR_OK;
}

static hr_status triangle_mesh_create(const hr_create_args *args, void **out_shape)
{
    mesh *m = NULL;
    hr_status st = mesh_arrays_create(args, &m);
    *out_shape = m;
    return st;
}

static hr_status solid_create(const hr_create_args *args, void **out_shape, int solid)
{
    *out_shape = NULL;
    mesh_builder b;
    mesh_builder_init(&b, args->host);
    mesh *m = NULL;
    hr_status st = mesh_solid_build(&b, solid) ? HR_ERROR_OUT_OF_MEMORY
                                               : mesh_builder_finish(&b, &m, args->error,
                                                                     args->error_size);
    mesh_builder_release(&b);
    if (st) return st;
    *out_shape = m;
    return HR_OK;
}

#define DEFINE_SOLID_CREATE(name, solid)                                       \
    static hr_status name##_create(const hr_create_args *args, void **out)     \
    {                                                                          \
        return solid_create(args, out, solid);                                 \
    }
DEFINE_SOLID_CREATE(tetrahedron, MESH_TETRAHEDRON)
DEFINE_SOLID_CREATE(octahedron, MESH_OCTAHEDRON)
DEFINE_SOLID_CREATE(dodecahedron, MESH_DODECAHEDRON)
DEFINE_SOLID_CREATE(icosahedron, MESH_ICOSAHEDRON)
DEFINE_SOLID_CREATE(buckyball, MESH_BUCKYBALL)

static hr_status teapot_create(const hr_create_args *args, void **out_shape)
{
    *out_shape = NULL;
    const hr_param *level_param = shape_param(args, "tessellation");
    const double level = level_param && level_param->type == HR_PARAM_NUMBER
                             ? level_param->number
                             : MESH_TEAPOT_DEFAULT_LEVEL;
    /* The host checked the range; a fraction of a step it cannot see. */
    if (!(level >= MESH_TEAPOT_MIN_LEVEL && level <= MESH_BEZIER_MAX_LEVEL) ||
        level != floor(level)) {
        snprintf(args->error, args->error_size,
                 "parameter 'tessellation' is %g; it must be a whole number of steps along each "
                 "side of a patch, from %d to %d",
                 level, MESH_TEAPOT_MIN_LEVEL, MESH_BEZIER_MAX_LEVEL);
        return HR_ERROR_PARAMETER;
    }
    mesh_builder b;
    mesh_builder_init(&b, args->host);
    mesh *m = NULL;
    hr_status st = mesh_teapot_build(&b, (uint32_t)level)
                       ? HR_ERROR_OUT_OF_MEMORY
                       : mesh_builder_finish(&b, &m, args->error, args->error_size);
    mesh_builder_release(&b);
    if (st == HR_ERROR_OUT_OF_MEMORY)
        snprintf(args->error, args->error_size,
                 "out of memory tessellating the teapot into %u triangles",
                 MESH_TEAPOT_TRIANGLES((uint32_t)level));
    *out_shape = m;
    return st;
}

static const hr_param_spec mesh_params[] = {
    {"file", HR_PARAM_STRING, 1, 0.0, 0.0, 0.0,
     "mesh file: Wavefront OBJ if the name ends in .obj, else Hill's chapter-6 format (.3vn); "
     "relative to the scene file", 0},
};

static const hr_param_spec triangle_mesh_params[] = {
    {"points", HR_PARAM_NUMBERS, 1, 0.0, -DBL_MAX, DBL_MAX, "x y z of each vertex", 0},
    {"triangles", HR_PARAM_NUMBERS, 1, 0.0, 0.0, (double)MESH_MAX_COUNT,
     "three vertex indices (from 0) per triangle, counter-clockwise seen from outside", 0},
    {"normals", HR_PARAM_NUMBERS, 0, 0.0, -DBL_MAX, DBL_MAX,
     "optional: x y z per vertex, shading normals interpolated across each triangle", 0},
};

static const hr_param_spec teapot_params[] = {
    {"tessellation", HR_PARAM_NUMBER, 0, MESH_TEAPOT_DEFAULT_LEVEL, MESH_TEAPOT_MIN_LEVEL,
     MESH_BEZIER_MAX_LEVEL,
     "steps along each side of each of the 32 patches, a whole number: 64 n^2 - 8 n triangles "
     "(9,120 at the default 12), some 60 bytes each", 0},
};

/* Every triangle of a mesh is one surface. */
static const char *const mesh_surface_names[1] = {"mesh"};

#define MESH_CLASS_FIELDS(name_, flags_, help_, params_, count_, create_)      \
    .struct_size = sizeof(hr_shape_class), .flags = flags_, .name = name_,     \
    .help = help_, .params = params_, .param_count = count_,                   \
    .surface_count = 1, .create = create_, .destroy = mesh_destroy_shape,      \
    .bounds = mesh_bounds, .hit = mesh_hit, .first_hit = mesh_first_hit,       \
    .any_hit = mesh_any_hit, .surface_names = mesh_surface_names
#define MESH_CLASS(name_, flags_, help_, params_, count_, create_)             \
    {MESH_CLASS_FIELDS(name_, flags_, help_, params_, count_, create_)}

/* Only a file can hold texture coordinates (OBJ's vt): the one class with
 * (u, v) (mesh_uv.c). */
static const hr_shape_class mesh_class = {
    MESH_CLASS_FIELDS("mesh", 0,
                      "triangle or polygon mesh from a file (Hill's .3vn, or OBJ); one surface; "
                      "(u, v) from an OBJ file's vt",
                      mesh_params, 1, mesh_create),
    .surface_uv = mesh_uv,
};
static const hr_shape_class triangle_mesh_class =
    MESH_CLASS("triangleMesh", 0,
               "triangle mesh from arrays given by the caller (points, triangles, normals); "
               "one surface",
               triangle_mesh_params, 3, triangle_mesh_create);
static const hr_shape_class tetrahedron_class =
    MESH_CLASS("tetrahedron", HR_SHAPE_CLOSED, "regular tetrahedron, vertices on the unit sphere",
               NULL, 0, tetrahedron_create);
static const hr_shape_class octahedron_class =
    MESH_CLASS("octahedron", HR_SHAPE_CLOSED, "regular octahedron, vertices (+-1, 0, 0) and so on",
               NULL, 0, octahedron_create);
static const hr_shape_class dodecahedron_class =
    MESH_CLASS("dodecahedron", HR_SHAPE_CLOSED,
               "regular dodecahedron, vertices on the unit sphere", NULL, 0, dodecahedron_create);
static const hr_shape_class icosahedron_class =
    MESH_CLASS("icosahedron", HR_SHAPE_CLOSED,
               "regular icosahedron, vertices on the unit sphere", NULL, 0, icosahedron_create);

static const hr_shape_class buckyball_class =
    MESH_CLASS("buckyball", HR_SHAPE_CLOSED,
               "truncated icosahedron (12 pentagons, 20 hexagons), vertices on the unit sphere",
               NULL, 0, buckyball_create);
static const hr_shape_class teapot_class =
    MESH_CLASS("teapot", HR_SHAPE_SDL_BARE,
               "Newell's teapot from its 32 Bezier patches, smooth normals, glutSolidTeapot(1)'s "
               "size (y up, base at y = -0.75); open, as Newell made it",
               teapot_params, 1, teapot_create);

SHAPE_MODULE("mesh",
             "triangle meshes from Hill's .3vn and OBJ files or from arrays, the regular solids, "
             "the buckyball and Newell's teapot",
             SHAPE_BUILTIN_METADATA, &mesh_class, &tetrahedron_class, &octahedron_class,
             &dodecahedron_class, &icosahedron_class, &triangle_mesh_class, &buckyball_class,
             &teapot_class);
