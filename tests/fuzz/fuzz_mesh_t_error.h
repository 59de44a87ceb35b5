/* The rounding of a mesh's crossings' t along a line (the mesh module's
 * triangle test, shapes/mesh/mesh_triangle.h), which the harnesses allow
 * between a first hit and the all-hits list: first_hit's walks prune by
 * boxes, which bound the exact crossings, while the lists sort computed t,
 * and a crossing's computed t may lie its t error bound (mesh_t_error)
 * from its exact crossing. */
#ifndef HITRAY_FUZZ_MESH_T_ERROR_H
#define HITRAY_FUZZ_MESH_T_ERROR_H

#include <stdint.h>

#include <hitray/hitray.h>

struct mesh;

/* The largest t error bound of any crossing of the line with the mesh's
 * triangles, by testing every one; 0 when the line crosses none. */
double fuzz_mesh_line_t_error(const struct mesh *m, const hr_ray *ray);

/* The same for the top-level object `object` of a committed scene along
 * the world ray `ray` (carried into the object's space as tracing does),
 * when the object is a shape of the mesh module; 0 for any other object. */
double fuzz_scene_mesh_t_error(const hr_scene *scene, int64_t object, const hr_ray *ray);

#endif
