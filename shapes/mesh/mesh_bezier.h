/* Bicubic Bezier patches tessellated into a mesh builder, with vertex
 * normals from the patch's derivatives (mesh_bezier.c). */
#ifndef HITRAY_MESH_BEZIER_H
#define HITRAY_MESH_BEZIER_H

#include <stdint.h>

#include "mesh.h"

/* The finest tessellation: steps along each side of a patch. */
#define MESH_BEZIER_MAX_LEVEL 128

/* Adds the patch with control points control[4 j + i] (row j, a cubic in u
 * through control[4 j .. 4 j + 3]; the rows blended in v) as a grid of
 * `level` x `level` quads, two triangles each, wound counter-clockwise about
 * Pu x Pv. Every vertex is a point of the surface with the unit normal of
 * the surface there; where a side of the patch has shrunk to a point (a
 * pole) the normal is the limit of the normals approaching it, and a
 * triangle with two corners at the pole is skipped by the builder. A
 * vertex whose normal has no limit gets none (its triangles shade with
 * their geometric normal).
 *
 * Two patches that share a side (the same four control points, in either
 * order) get bitwise the same vertices along it, so the welded mesh has no
 * crack there. `level` in [1, MESH_BEZIER_MAX_LEVEL]. 0, or -1 when out of
 * memory. */
int mesh_bezier_add_patch(mesh_builder *b, const hr_vec3 control[16], uint32_t level);

#endif
