/* Newell's teapot: the patch data (mesh_teapot_data.c) and the mesh built
 * from it (mesh_teapot.c). */
#ifndef HITRAY_MESH_TEAPOT_H
#define HITRAY_MESH_TEAPOT_H

#include <stdint.h>

#include "mesh.h"

#define MESH_TEAPOT_POINTS 306
#define MESH_TEAPOT_PATCHES 32

/* Control points in Newell's frame (z up), and each patch's 16 indices into
 * them, row by row (mesh_teapot_data.c says more). */
extern const double mesh_teapot_points[MESH_TEAPOT_POINTS][3];
extern const uint16_t mesh_teapot_patches[MESH_TEAPOT_PATCHES][16];

/* The teapot's size in the shape's space is glutSolidTeapot(1.0)'s, the
 * call Hill's Teapot::drawOpenGL makes: Newell's point (x, y, z) is placed
 * at (x / 2, z / 2 - 3/4, -y / 2), y up, the base at y = -0.75, the knob's
 * top at y = 0.825, the body's widest circle of radius 1, the handle to -x
 * (reaching x = -1.5) and the spout to +x. */
hr_vec3 mesh_teapot_place(const double newell[3]);

/* The default tessellation (steps along each side of a patch): smooth
 * normals hide the facets inside the silhouette, and the silhouette of the
 * body's widest circle, 48 segments around, is within 0.21% of its radius
 * (1 - cos(pi / 48)): under a pixel for a teapot 400 pixels wide. */
#define MESH_TEAPOT_DEFAULT_LEVEL 12

/* The coarsest tessellation: at one step a side, the handle and the spout
 * (each two patches round) would flatten into two copies of one quad. From
 * 6 steps on, every vertex normal is within 90 degrees of the triangles it
 * shades; below, the spout's lip and the knob, which turn about as much
 * within one step, have a few that are not (the mesh shades those triangles
 * with the normal brought to their side, mesh_trace.c). */
#define MESH_TEAPOT_MIN_LEVEL 2

/* The number of triangles at a tessellation: 2 level^2 a patch, less the
 * level slivers of each of the eight patches that meet at the knob's top
 * and the bottom's centre. */
#define MESH_TEAPOT_TRIANGLES(level) (64u * (level) * (level) - 8u * (level))

/* Fills the builder with every patch at `level` (MESH_TEAPOT_MIN_LEVEL ..
 * MESH_BEZIER_MAX_LEVEL),
 * faces wound counter-clockwise seen from outside, a unit normal at each
 * vertex. 0, or -1 when out of memory. */
int mesh_teapot_build(mesh_builder *b, uint32_t level);

#endif
