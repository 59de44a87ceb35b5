/* Building a mesh: growing arrays through the host's allocator, fanning
 * polygons into triangles, skipping triangles with no area, and handing the
 * result to the BVH builder. */
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

/* Corner and corner-normal arrays grow together: capacity in triangles. */
static int grow_triangles(mesh_builder *b, size_t wanted)
{
    if (wanted <= b->triangle_capacity) return 0;
    if (wanted > MESH_MAX_COUNT) return -1;
    size_t cap = b->triangle_capacity ? b->triangle_capacity : 64;
    while (cap < wanted) cap *= 2; /* wanted < 2^32: no overflow */
    uint32_t *corners = b->host->alloc(3 * cap * sizeof *corners);
    uint32_t *normals = b->host->alloc(3 * cap * sizeof *normals);
    if (!corners || !normals) {
        b->host->free(corners);
        b->host->free(normals);
        return -1;
    }
    if (b->triangle_count) {
        memcpy(corners, b->corners, 3 * b->triangle_count * sizeof *corners);
        memcpy(normals, b->corner_normals, 3 * b->triangle_count * sizeof *normals);
    }
    b->host->free(b->corners);
    b->host->free(b->corner_normals);
    b->corners = corners;
    b->corner_normals = normals;
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

static int same_point(hr_vec3 a, hr_vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

int mesh_builder_add_polygon(mesh_builder *b, const uint32_t *vertices, const uint32_t *normals,
                             size_t count)
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
    host->free(m->nodes);
    host->free(m);
}

/* Copies `count` items into an exactly sized block, so a grown array's
 * slack is not kept for the life of the shape. */
static void *shrink(const hr_host *host, void *array, size_t count, size_t size)
{
    void *exact = host->alloc(count ? count * size : 1);
    if (!exact) return NULL;
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
    m->vertex_count = (uint32_t)b->vertex_count;
    m->normal_count = any_normal ? (uint32_t)b->normal_count : 0;
    m->triangle_count = (uint32_t)b->triangle_count;
    mesh_builder_release(b);
    if (!m->vertices || !m->corners || (any_normal && (!m->normals || !m->corner_normals))) {
        mesh_destroy(m);
        return HR_ERROR_OUT_OF_MEMORY;
    }
    hr_status st = mesh_bvh_build(m);
    if (st == HR_OK) {
        int closed = mesh_is_closed(m);
        if (closed < 0) st = HR_ERROR_OUT_OF_MEMORY;
        m->closed = closed > 0;
    }
    if (st) {
        mesh_destroy(m);
        return st;
    }
    *out = m;
    return HR_OK;
}

/* --- Closedness ------------------------------------------------------------ */

/* In-place heapsort of 64-bit keys: O(n log n), no allocation, no recursion. */
static void sift_down(uint64_t *a, size_t root, size_t n)
{
    for (;;) {
        size_t child = 2 * root + 1;
        if (child >= n) return;
        if (child + 1 < n && a[child + 1] > a[child]) child++;
        if (a[root] >= a[child]) return;
        uint64_t t = a[root];
        a[root] = a[child], a[child] = t;
        root = child;
    }
}

static void sort_keys(uint64_t *a, size_t n)
{
    for (size_t i = n / 2; i-- > 0;) sift_down(a, i, n);
    for (size_t end = n; end-- > 1;) {
        uint64_t t = a[0];
        a[0] = a[end], a[end] = t;
        sift_down(a, 0, end);
    }
}

/* A key that orders vertices by position: the bits of x, y, z folded with a
 * multiplicative hash, then the index. Equal positions give equal hashes,
 * so after sorting, each run of equal hashes is checked by exact comparison. */
static uint64_t position_hash(hr_vec3 v)
{
    uint64_t h = 0x9e3779b97f4a7c15u;
    const double c[3] = {v.x == 0.0 ? 0.0 : v.x, v.y == 0.0 ? 0.0 : v.y, v.z == 0.0 ? 0.0 : v.z};
    for (int i = 0; i < 3; i++) {
        uint64_t bits;
        memcpy(&bits, &c[i], sizeof bits);
        h = (h ^ bits) * 0xbf58476d1ce4e5b9u;
        h ^= h >> 31;
    }
    return h;
}

/* weld[i]: the smallest index of a vertex at the same position as vertex i.
 * Sorting (hash << 32 would lose bits, so a hash of 32 bits and the index)
 * brings equal positions together; collisions of different positions are
 * told apart by comparing coordinates within each run. */
static int weld(const mesh *m, uint32_t *weld_out)
{
    const size_t n = m->vertex_count;
    uint64_t *keys = m->host->alloc((n ? n : 1) * sizeof *keys);
    if (!keys) return -1;
    for (size_t i = 0; i < n; i++)
        keys[i] = (position_hash(m->vertices[i]) & 0xffffffff00000000u) | (uint64_t)i;
    sort_keys(keys, n);
    for (size_t start = 0; start < n;) {
        size_t end = start + 1;
        while (end < n && (keys[end] >> 32) == (keys[start] >> 32)) end++;
        /* Within a run (indices ascending), each vertex welds to the first
         * earlier one at its position. Runs are tiny unless positions repeat. */
        for (size_t i = start; i < end; i++) {
            uint32_t vi = (uint32_t)keys[i];
            weld_out[vi] = vi;
            for (size_t j = start; j < i; j++) {
                uint32_t vj = (uint32_t)keys[j];
                if (weld_out[vj] == vj && same_point(m->vertices[vi], m->vertices[vj])) {
                    weld_out[vi] = vj;
                    break;
                }
            }
        }
        start = end;
    }
    m->host->free(keys);
    return 0;
}

int mesh_is_closed(const mesh *m)
{
    const hr_host *host = m->host;
    const size_t edges = 3 * (size_t)m->triangle_count;
    uint32_t *welded = host->alloc((m->vertex_count ? m->vertex_count : 1) * sizeof *welded);
    uint64_t *keys = host->alloc(edges * sizeof *keys);
    if (!welded || !keys || weld(m, welded)) {
        host->free(welded);
        host->free(keys);
        return -1;
    }
    for (size_t t = 0; t < m->triangle_count; t++)
        for (int k = 0; k < 3; k++) {
            uint64_t a = welded[m->corners[3 * t + k]], b = welded[m->corners[3 * t + (k + 1) % 3]];
            keys[3 * t + k] = a << 32 | b;
        }
    sort_keys(keys, edges);
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
