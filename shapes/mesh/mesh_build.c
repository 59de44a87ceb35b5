/* Building a mesh: growing arrays through the host's allocator, fanning
 * polygons into triangles, skipping triangles with no area, and handing the
 * result to the BVH builder. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "mesh.h"

void mesh_builder_init(mesh_builder *b, const hr_host *host)
{
    memset(b, 0, sizeof *b);
    b->host = host;
}

void mesh_builder_release(mesh_builder *b)
{
    const hr_host *host = b->host;
    host->free(b->vertices);
    host->free(b->normals);
    host->free(b->corners);
    host->free(b->corner_normals);
    host->free(b->texcoords);
    host->free(b->corner_texcoords);
    mesh_builder_init(b, host);
}

/* Makes *array hold at least `wanted` items of `size` bytes (keeping
 * `count`), doubling so that n appends cost O(n). */
static int grow(const hr_host *host, void **array, size_t *capacity, size_t count, size_t wanted,
                size_t size)
{
    if (wanted <= *capacity) return 0;
    if (wanted > MESH_MAX_COUNT) return -1;
    size_t cap = *capacity ? *capacity : 64;
    while (cap < wanted) cap *= 2; /* wanted < 2^32: no overflow */
    if (cap > SIZE_MAX / size) return -1;
    void *grown = host->alloc(cap * size);
    if (!grown) return -1;
    if (count) memcpy(grown, *array, count * size);
    host->free(*array);
    *array = grown;
    *capacity = cap;
    return 0;
}

/* Corner, corner-normal and corner-texcoord arrays grow together:
 * capacity in triangles. */
static int grow_triangles(mesh_builder *b, size_t wanted)
{
    if (wanted <= b->triangle_capacity) return 0;
    if (wanted > MESH_MAX_COUNT) return -1;
    size_t cap = b->triangle_capacity ? b->triangle_capacity : 64;
    while (cap < wanted) cap *= 2; /* wanted < 2^32: no overflow */
    uint32_t **arrays[3] = {&b->corners, &b->corner_normals, &b->corner_texcoords};
    uint32_t *grown[3];
    for (int a = 0; a < 3; a++) {
        grown[a] = b->host->alloc(3 * cap * sizeof *grown[a]);
        if (!grown[a]) {
            while (a-- > 0) b->host->free(grown[a]);
            return -1;
        }
    }
    for (int a = 0; a < 3; a++) {
        if (b->triangle_count) memcpy(grown[a], *arrays[a], 3 * b->triangle_count * sizeof *grown[a]);
        b->host->free(*arrays[a]);
        *arrays[a] = grown[a];
    }
    b->triangle_capacity = cap;
    return 0;
}

int mesh_builder_reserve(mesh_builder *b, size_t vertices, size_t normals, size_t triangles)
{
    if (vertices > MESH_MAX_COUNT || normals > MESH_MAX_COUNT || triangles > MESH_MAX_COUNT)
        return -1;
    if (grow(b->host, (void **)&b->vertices, &b->vertex_capacity, b->vertex_count, vertices,
             sizeof *b->vertices))
        return -1;
    if (grow(b->host, (void **)&b->normals, &b->normal_capacity, b->normal_count, normals,
             sizeof *b->normals))
        return -1;
    return grow_triangles(b, triangles);
}

int mesh_builder_add_vertex(mesh_builder *b, hr_vec3 v)
{
    if (b->vertex_count >= MESH_MAX_COUNT) return -1;
    if (grow(b->host, (void **)&b->vertices, &b->vertex_capacity, b->vertex_count,
             b->vertex_count + 1, sizeof *b->vertices))
        return -1;
    b->vertices[b->vertex_count++] = v;
    return 0;
}

int mesh_builder_add_normal(mesh_builder *b, hr_vec3 n)
{
    if (b->normal_count >= MESH_MAX_COUNT) return -1;
    if (grow(b->host, (void **)&b->normals, &b->normal_capacity, b->normal_count,
             b->normal_count + 1, sizeof *b->normals))
        return -1;
    b->normals[b->normal_count++] = n;
    return 0;
}

int mesh_builder_add_texcoord(mesh_builder *b, mesh_texcoord t)
{
    if (b->texcoord_count >= MESH_MAX_COUNT) return -1;
    if (grow(b->host, (void **)&b->texcoords, &b->texcoord_capacity, b->texcoord_count,
             b->texcoord_count + 1, sizeof *b->texcoords))
        return -1;
    b->texcoords[b->texcoord_count++] = t;
    return 0;
}

static int same_point(hr_vec3 a, hr_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

int mesh_builder_add_polygon(mesh_builder *b, const uint32_t *vertices, const uint32_t *normals,
                             size_t count)
{
    return mesh_builder_add_polygon_uv(b, vertices, normals, NULL, count);
}

int mesh_builder_add_polygon_uv(mesh_builder *b, const uint32_t *vertices, const uint32_t *normals,
                                const uint32_t *texcoords, size_t count)
{
    for (size_t i = 1; i + 1 < count; i++) {
        const uint32_t v[3] = {vertices[0], vertices[i], vertices[i + 1]};
        const hr_vec3 p0 = b->vertices[v[0]], p1 = b->vertices[v[1]], p2 = b->vertices[v[2]];
        /* Two corners at one point: no area, and no ray can hit it (the
         * test finds a zero determinant). Exactly collinear corners are kept:
         * the test never hits them either, and deciding collinearity exactly
         * is not worth a predicate here. */
        if (same_point(p0, p1) || same_point(p1, p2) || same_point(p0, p2)) {
            b->degenerate_count++;
            continue;
        }
        if (b->triangle_count >= MESH_MAX_COUNT) return -1;
        if (grow_triangles(b, b->triangle_count + 1)) return -1;
        uint32_t *c = b->corners + 3 * b->triangle_count;
        uint32_t *n = b->corner_normals + 3 * b->triangle_count;
        c[0] = v[0], c[1] = v[1], c[2] = v[2];
        n[0] = normals ? normals[0] : MESH_NO_NORMAL;
        n[1] = normals ? normals[i] : MESH_NO_NORMAL;
        n[2] = normals ? normals[i + 1] : MESH_NO_NORMAL;
        uint32_t *tc = b->corner_texcoords + 3 * b->triangle_count;
        tc[0] = texcoords ? texcoords[0] : MESH_NO_TEXCOORD;
        tc[1] = texcoords ? texcoords[i] : MESH_NO_TEXCOORD;
        tc[2] = texcoords ? texcoords[i + 1] : MESH_NO_TEXCOORD;
        b->triangle_count++;
    }
    return 0;
}

void mesh_destroy(mesh *m)
{
    if (!m) return;
    const hr_host *host = m->host;
    host->free(m->vertices);
    host->free(m->normals);
    host->free(m->corners);
    host->free(m->corner_normals);
    host->free(m->texcoords);
    host->free(m->corner_texcoords);
    accel_bvh4_release(&m->bvh);
    host->free(m);
}

/* Copies `count` items into an exactly sized block, so a grown array's
 * slack is not kept for the life of the shape. Frees `array` either way. */
static void *shrink(const hr_host *host, void *array, size_t count, size_t size)
{
    void *exact = host->alloc(count ? count * size : 1);
    if (!exact) {
        host->free(array);
        return NULL;
    }
    if (count) memcpy(exact, array, count * size);
    host->free(array);
    return exact;
}

hr_status mesh_builder_finish(mesh_builder *b, mesh **out, char *error, size_t error_size)
{
    *out = NULL;
    if (b->triangle_count == 0) {
        snprintf(error, error_size, "the mesh has no triangle with area (%zu skipped)",
                 b->degenerate_count);
        return HR_ERROR_PARAMETER;
    }
    if (b->triangle_count > ACCEL_BVH4_MAX_ITEMS) {
        snprintf(error, error_size, "the mesh has %zu triangles, more than its BVH takes (%lu)",
                 b->triangle_count, (unsigned long)ACCEL_BVH4_MAX_ITEMS);
        return HR_ERROR_PARAMETER;
    }
    const hr_host *host = b->host;
    mesh *m = host->alloc(sizeof *m);
    if (!m) return HR_ERROR_OUT_OF_MEMORY;
    m->host = host;
    int any_normal = 0;
    for (size_t i = 0; i < 3 * b->triangle_count && !any_normal; i++)
        any_normal = b->corner_normals[i] != MESH_NO_NORMAL;
    /* Drop what the triangles do not need: normals nobody uses, slack. */
    m->vertices = shrink(host, b->vertices, b->vertex_count, sizeof *b->vertices);
    b->vertices = NULL;
    m->corners = shrink(host, b->corners, 3 * b->triangle_count, sizeof *b->corners);
    b->corners = NULL;
    if (any_normal) {
        m->normals = shrink(host, b->normals, b->normal_count, sizeof *b->normals);
        b->normals = NULL;
        m->corner_normals =
            shrink(host, b->corner_normals, 3 * b->triangle_count, sizeof *b->corner_normals);
        b->corner_normals = NULL;
    }
    /* Texture coordinates only where every triangle has them: (u, v) is
     * the whole surface's or none of it. */
    int all_texcoords = b->texcoord_count > 0;
    for (size_t i = 0; i < 3 * b->triangle_count && all_texcoords; i++)
        all_texcoords = b->corner_texcoords[i] != MESH_NO_TEXCOORD;
    if (all_texcoords) {
        m->texcoords = shrink(host, b->texcoords, b->texcoord_count, sizeof *b->texcoords);
        b->texcoords = NULL;
        m->corner_texcoords =
            shrink(host, b->corner_texcoords, 3 * b->triangle_count, sizeof *b->corner_texcoords);
        b->corner_texcoords = NULL;
        m->texcoord_count = (uint32_t)b->texcoord_count;
    }
    m->vertex_count = (uint32_t)b->vertex_count;
    m->normal_count = any_normal ? (uint32_t)b->normal_count : 0;
    m->triangle_count = (uint32_t)b->triangle_count;
    mesh_builder_release(b);
    if (!m->vertices || !m->corners || (any_normal && (!m->normals || !m->corner_normals)) ||
        (all_texcoords && (!m->texcoords || !m->corner_texcoords))) {
        mesh_destroy(m);
        return HR_ERROR_OUT_OF_MEMORY;
    }
    hr_status st = mesh_bvh_build(m);
    if (st == HR_OK) {
        int closed = mesh_is_closed(m);
        if (closed < 0) st = HR_ERROR_OUT_OF_MEMORY;
        m->closed = closed > 0;
        m->largest_error = m->closed ? mesh_largest_error(m) : 0.0;
    }
    if (st) {
        mesh_destroy(m);
        return st;
    }
    *out = m;
    return HR_OK;
}

/* --- Closedness ------------------------------------------------------------ */

/* Sorts keys[0, n), and vals alongside when given, by key, stably: a
 * least-significant-digit radix sort, a byte a pass, O(n) whatever the
 * keys, no recursion, no comparison. One pass counts every byte's values;
 * a byte that is the same in every key (the high bytes of small indices)
 * needs no pass. tmp_keys and tmp_vals hold n each. */
static void radix_sort(uint64_t *keys, uint32_t *vals, uint64_t *tmp_keys, uint32_t *tmp_vals,
                       size_t n)
{
    if (n < 2) return;
    size_t count[8][256];
    memset(count, 0, sizeof count);
    for (size_t i = 0; i < n; i++)
        for (int d = 0; d < 8; d++) count[d][(keys[i] >> (8 * d)) & 0xff]++;
    uint64_t *from_k = keys, *to_k = tmp_keys;
    uint32_t *from_v = vals, *to_v = tmp_vals;
    for (int d = 0; d < 8; d++) {
        size_t *c = count[d];
        if (c[(keys[0] >> (8 * d)) & 0xff] == n) continue;
        for (size_t v = 0, start = 0; v < 256; v++) {
            const size_t here = c[v];
            c[v] = start;
            start += here;
        }
        for (size_t i = 0; i < n; i++) {
            const size_t to = c[(from_k[i] >> (8 * d)) & 0xff]++;
            to_k[to] = from_k[i];
            if (vals) to_v[to] = from_v[i];
        }
        uint64_t *k = from_k;
        from_k = to_k, to_k = k;
        uint32_t *v = from_v;
        from_v = to_v, to_v = v;
    }
    if (from_k != keys) {
        memcpy(keys, from_k, n * sizeof *keys);
        if (vals) memcpy(vals, from_v, n * sizeof *vals);
    }
}

/* A key whose unsigned order is the order of the coordinates, with -0 and
 * +0 one key (as same_point has them equal). */
static uint64_t coordinate_key(double x)
{
    if (x == 0.0) x = 0.0;
    uint64_t bits;
    memcpy(&bits, &x, sizeof bits);
    return bits >> 63 ? ~bits : bits | (uint64_t)1 << 63;
}

/* weld_out[i]: the first vertex at the same position as vertex i.
 * Vertices sorted by position (x, then y, then z, then index: three stable
 * radix sorts, z first) make each position one run. */
static int weld(const mesh *m, uint32_t *weld_out)
{
    const size_t n = m->vertex_count;
    const hr_vec3 *v = m->vertices;
    const hr_host *host = m->host;
    const size_t room = n ? n : 1;
    uint32_t *order = host->alloc(room * sizeof *order);
    uint32_t *tmp_order = host->alloc(room * sizeof *tmp_order);
    uint64_t *keys = host->alloc(room * sizeof *keys);
    uint64_t *tmp_keys = host->alloc(room * sizeof *tmp_keys);
    if (!order || !tmp_order || !keys || !tmp_keys) {
        host->free(order);
        host->free(tmp_order);
        host->free(keys);
        host->free(tmp_keys);
        return -1;
    }
    for (size_t i = 0; i < n; i++) order[i] = (uint32_t)i;
    for (int axis = 2; axis >= 0; axis--) {
        for (size_t i = 0; i < n; i++) {
            const hr_vec3 *p = &v[order[i]];
            keys[i] = coordinate_key(axis == 0 ? p->x : axis == 1 ? p->y : p->z);
        }
        radix_sort(keys, order, tmp_keys, tmp_order, n);
    }
    for (size_t i = 0; i < n; i++)
        weld_out[order[i]] = i > 0 && same_point(v[order[i]], v[order[i - 1]])
                                 ? weld_out[order[i - 1]]
                                 : order[i];
    host->free(order);
    host->free(tmp_order);
    host->free(keys);
    host->free(tmp_keys);
    return 0;
}

int mesh_is_closed(const mesh *m)
{
    const hr_host *host = m->host;
    const size_t edges = 3 * (size_t)m->triangle_count;
    uint32_t *welded = host->alloc((m->vertex_count ? m->vertex_count : 1) * sizeof *welded);
    uint64_t *keys = host->alloc(edges * sizeof *keys);
    uint64_t *tmp_keys = host->alloc(edges * sizeof *tmp_keys);
    if (!welded || !keys || !tmp_keys || weld(m, welded)) {
        host->free(welded);
        host->free(keys);
        host->free(tmp_keys);
        return -1;
    }
    for (size_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = welded[m->corners[3 * t + k]], b = welded[m->corners[3 * t + (k + 1) % 3]];
            keys[3 * t + k] = a << 32 | b;
        }
    radix_sort(keys, NULL, tmp_keys, NULL, edges);
    host->free(tmp_keys);
    /* Closed: no directed edge twice, and each one's reverse present. */
    int closed = 1;
    for (size_t i = 0; i < edges && closed; i++) {
        if (i + 1 < edges && keys[i + 1] == keys[i]) closed = 0;
        uint64_t reverse = keys[i] << 32 | keys[i] >> 32;
        size_t lo = 0, hi = edges;
        while (lo < hi) {
            size_t mid = lo + (hi - lo) / 2;
            if (keys[mid] < reverse) lo = mid + 1;
            else hi = mid;
        }
        if (lo == edges || keys[lo] != reverse) closed = 0;
    }
    host->free(welded);
    host->free(keys);
    return closed;
}
