/* The mesh module's shared types: a triangle mesh as the module keeps it
 * (vertices stored once, triangles as three 32-bit indices, optional
 * per-corner normal indices), the builder the file readers and the regular
 * solids fill, and the BVH over the triangles.
 *
 * Storage per triangle: 12 bytes of vertex indices, 12 more when the mesh
 * has normals, the vertices themselves (24 bytes each, shared: a closed
 * mesh has about half as many vertices as triangles) and the BVH's nodes
 * (accel/bvh4.h: 128 bytes each, four children, small leaves: some 20
 * bytes a triangle, see mesh_bvh.c) and each triangle's index in the file
 * (4 bytes, for the tie rule): some 48 bytes a triangle for a closed mesh
 * without normals (test_shape_mesh_large prints the figure).
 * The BVH orders the triangles themselves, so no index array sits between
 * them and their corners. */
#ifndef HITRAY_MESH_H
#define HITRAY_MESH_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/shape_module.h>

#include "bvh4.h"

/* A corner with no normal (OBJ faces may omit them), or no texture
 * coordinate. */
#define MESH_NO_NORMAL UINT32_MAX
#define MESH_NO_TEXCOORD UINT32_MAX

/* One OBJ `vt`: where on an image texture a vertex lies (mesh_uv.c). */
typedef struct mesh_texcoord {
    double u, v;
} mesh_texcoord;
/* Indices are 32-bit; the largest count of vertices, normals or triangles. */
#define MESH_MAX_COUNT ((size_t)UINT32_MAX - 1u)

/* The BVH's leaves hold at most this many triangles (accel/bvh4.h). */
#define MESH_BVH_MAX_LEAF 8

typedef struct mesh {
    const hr_host *host;
    hr_vec3 *vertices;
    hr_vec3 *normals;      /* NULL when the mesh has none */
    uint32_t *corners;     /* 3 vertex indices per triangle, in BVH order */
    uint32_t *corner_normals; /* 3 normal indices per triangle or NULL */
    uint32_t vertex_count, normal_count, triangle_count;
    /* accel/'s 4-wide BVH over the triangles, in leaf order; its item
     * array, bvh.items[i], is triangle i's index in the file (the order
     * the builder was given), by which exact ties are broken: at one t,
     * the lower file index wins, whatever order the walk takes. */
    accel_bvh4 bvh;
    hr_bounds bounds;
    /* The axis the mesh lies flat across (its bounds' sides equal), or -1,
     * and the root's span on it (accel_bvh4_root_span): mesh_trace turns
     * away the rays that leave it behind without walking. */
    int flat_axis;
    float flat_lo, flat_hi;
    /* Every edge (vertices welded by position) is used once in each
     * direction: a closed, consistently wound surface. */
    int closed;
    /* mesh_largest_error of a closed mesh, 0 for an open one. */
    double largest_error;
    /* Texture coordinates and 3 indices into them per triangle (in BVH
     * order), NULL when no triangle has them all: the (u, v) of
     * hr_shape_class.surface_uv (mesh_uv.c). */
    mesh_texcoord *texcoords;
    uint32_t *corner_texcoords;
    uint32_t texcoord_count;
} mesh;

/* --- Building ------------------------------------------------------------ */

/* What a reader or a solid fills; mesh_builder_finish turns it into a mesh.
 * Arrays grow by doubling through the host's allocator, or are reserved
 * exactly when a file states its counts. */
typedef struct mesh_builder {
    const hr_host *host;
    hr_vec3 *vertices;
    size_t vertex_count, vertex_capacity;
    hr_vec3 *normals;
    size_t normal_count, normal_capacity;
    uint32_t *corners; /* 3 per triangle */
    uint32_t *corner_normals; /* 3 per triangle, MESH_NO_NORMAL where none */
    size_t triangle_count, triangle_capacity;
    size_t degenerate_count; /* triangles skipped: two corners at one point */
    mesh_texcoord *texcoords;
    size_t texcoord_count, texcoord_capacity;
    uint32_t *corner_texcoords; /* 3 per triangle, MESH_NO_TEXCOORD where none */
} mesh_builder;

void mesh_builder_init(mesh_builder *b, const hr_host *host);
void mesh_builder_release(mesh_builder *b);
/* 0 on success, -1 when out of memory. */
int mesh_builder_reserve(mesh_builder *b, size_t vertices, size_t normals, size_t triangles);
int mesh_builder_add_vertex(mesh_builder *b, hr_vec3 v);
int mesh_builder_add_normal(mesh_builder *b, hr_vec3 n);
/* A polygon of `count` >= 3 corners (indices already checked), fanned from
 * its first corner: (0, i, i+1). Triangles with two corners at the same
 * point have no area and are skipped (and counted). `normals` may be NULL.
 * Returns 0, or -1 when out of memory or past MESH_MAX_COUNT triangles. */
int mesh_builder_add_polygon(mesh_builder *b, const uint32_t *vertices, const uint32_t *normals,
                             size_t count);
/* The same with texture coordinates (`texcoords` may be NULL: none). */
int mesh_builder_add_texcoord(mesh_builder *b, mesh_texcoord t);
int mesh_builder_add_polygon_uv(mesh_builder *b, const uint32_t *vertices, const uint32_t *normals,
                                const uint32_t *texcoords, size_t count);

/* Builds the BVH and hands the arrays over to a new mesh (the builder is
 * left empty). On failure writes a message to error and returns a status. */
hr_status mesh_builder_finish(mesh_builder *b, mesh **out, char *error, size_t error_size);
void mesh_destroy(mesh *m);

/* Whether every edge is used once in each direction (vertices welded by
 * exact position). -1: out of memory. */
int mesh_is_closed(const mesh *m);

/* --- Reading files ------------------------------------------------------- */

/* Hill's chapter-6 format (.3vn) and Wavefront OBJ (v, vn, f). `path` is the
 * file to open, `shown` the name used in messages. On failure they write
 * "shown:line: what (found 'token')" to error and return a status. */
hr_status mesh_read_3vn(mesh_builder *b, const char *text, size_t length, const char *shown,
                        char *error, size_t error_size);
hr_status mesh_read_obj(mesh_builder *b, const char *text, size_t length, const char *shown,
                        char *error, size_t error_size);

/* --- The regular solids and the buckyball ------------------------------------ */

#define MESH_TETRAHEDRON 0
#define MESH_OCTAHEDRON 1
#define MESH_DODECAHEDRON 2
#define MESH_ICOSAHEDRON 3
#define MESH_BUCKYBALL 4 /* the truncated icosahedron */

/* Fills the builder with the solid, vertices on the unit sphere, faces wound
 * counter-clockwise seen from outside. 0, or -1 when out of memory. */
int mesh_solid_build(mesh_builder *b, int solid);

/* --- The BVH --------------------------------------------------------------- */

/* The hits of the ray in args (HR_TRACE_ALL, _FIRST or _ANY), appended to
 * args->out (mesh_trace.c). */
hr_status mesh_trace(const mesh *m, const hr_hit_args *args, int32_t mode);

/* The largest error bound a hit of the mesh can have (mesh_trace.c). */
double mesh_largest_error(const mesh *m);

/* Builds m->bvh and orders m->corners (and m->corner_normals and
 * m->corner_texcoords) to match. */
hr_status mesh_bvh_build(mesh *m);

/* --- (u, v) ------------------------------------------------------------------ */

/* hr_shape_class.surface_uv of every mesh class (mesh_uv.c): the triangle
 * under the hit point, its texture coordinates interpolated; 0 on the
 * host's question when the mesh has none. */
int32_t mesh_uv(const void *shape, const hr_hit *hit, double uv[2]);

#endif
