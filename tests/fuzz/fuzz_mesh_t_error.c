/* The t error bounds of mesh crossings (fuzz_mesh_t_error.h). A scene's
 * object is reached through the library's own types (lib/scene), as only a
 * test may: the public queries carry no t error. */
#include "fuzz_mesh_t_error.h"

#include <math.h>
#include <string.h>

#include "mesh.h"
#include "mesh_triangle.h"
#include "scene/scene_internal.h"

double fuzz_mesh_line_t_error(const mesh *m, const hr_ray *ray)
{
    mesh_ray r;
    if (!mesh_ray_init(&r, ray)) return 0.0;
    double worst = 0.0;
    for (uint32_t i = 0; i < m->triangle_count; i++) {
        const uint32_t *c = m->corners + 3 * (size_t)i;
        mesh_triangle_hit th;
        if (mesh_triangle_test(&r, &m->vertices[c[0]], &m->vertices[c[1]], &m->vertices[c[2]],
                               -INFINITY, INFINITY, &th) &&
            th.t_error > worst)
            worst = th.t_error;
    }
    return worst;
}

/* Whether the object's shape comes from the mesh module (whose every class
 * makes a `mesh`): the module file is named mesh.<suffix>. */
static int is_mesh(const hr_object *o)
{
    const char *path = o->module_path;
    if (!path) return 0;
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    return strncmp(base, "mesh.", 5) == 0;
}

double fuzz_scene_mesh_t_error(const hr_scene *scene, int64_t object, const hr_ray *ray)
{
    if (object < 0 || object >= scene->object_count) return 0.0;
    const hr_object *o = scene->objects[object];
    if (!o->top_level || o->parent || !is_mesh(o)) return 0.0;
    hr_ray local = *ray;
    if (!o->identity) {
        local.origin = hri_xform_point_as(o->inv, o->diagonal, ray->origin);
        local.dir = hri_xform_vector_as(o->inv, o->diagonal, ray->dir);
    }
    return fuzz_mesh_line_t_error(o->shape, &local);
}
