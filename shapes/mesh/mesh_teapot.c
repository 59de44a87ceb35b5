/* The teapot as a mesh: Newell's 32 patches placed as glutSolidTeapot(1.0)
 * places them (Hill drew his teapot with that call; his ray tracer had no
 * hit code for it) and tessellated by mesh_bezier.c.
 *
 * The surface is open, as Newell modelled it: the lid rests inside the
 * rim with a gap between them, the handle and the spout pass into the body
 * without meeting it along an edge, and the spout's mouth is open. Every
 * other side of a patch is shared with another patch, so at a tessellation
 * of n steps 16 n edges of the welded mesh are used once (the rim's inner
 * circle, the lid's edge, the two ends of the handle and of the spout) and
 * every other edge twice, once each way. */
#include "mesh_bezier.h"
#include "mesh_teapot.h"

hr_vec3 mesh_teapot_place(const double newell[3])
{
    /* glutSolidTeapot: rotate 270 degrees about x, scale by 1/2, translate
     * by (0, 0, -1.5), applied to Newell's points in that order from the
     * right. Halving is exact; the rest rounds once. */
    return (hr_vec3){0.5 * newell[0], 0.5 * newell[2] - 0.75, -0.5 * newell[1]};
}

int mesh_teapot_build(mesh_builder *b, uint32_t level)
{
    if (level < MESH_TEAPOT_MIN_LEVEL || level > MESH_BEZIER_MAX_LEVEL) return -1;
    const size_t grid = (size_t)(level + 1) * (level + 1);
    if (mesh_builder_reserve(b, MESH_TEAPOT_PATCHES * grid, MESH_TEAPOT_PATCHES * grid,
                             MESH_TEAPOT_TRIANGLES(level)))
        return -1;
    for (int k = 0; k < MESH_TEAPOT_PATCHES; k++) {
        hr_vec3 control[16];
        for (int c = 0; c < 16; c++)
            control[c] = mesh_teapot_place(mesh_teapot_points[mesh_teapot_patches[k][c]]);
        if (mesh_bezier_add_patch(b, control, level)) return -1;
    }
    return 0;
}
