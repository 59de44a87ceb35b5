/* Hill's chapter-6 mesh format (.3vn):
 *
 *   numVerts numNorms numFaces
 *   x y z            (numVerts times)
 *   nx ny nz         (numNorms times)
 *   n v1 .. vn m1 .. mn   (numFaces times: n corners, their vertex
 *                          indices, then their normal indices; 0-based)
 *
 * Tokens are separated by any white space. Counts are checked against the
 * bytes left before anything is allocated from them, so a count of 1e18 in
 * a small file is an error, not an allocation. Faces are fanned into
 * triangles from their first corner. */
#include <string.h>

#include "mesh.h"
#include "mesh_text.h"

static hr_status read_count(mesh_text *t, const char *what, uint64_t *out, mesh_token *tok_out)
{
    mesh_token tok = mesh_text_next(t, 1, 0);
    *tok_out = tok;
    if (!mesh_parse_whole(&tok, MESH_MAX_COUNT, out))
        return mesh_text_error(t, &tok, "expected the number of %s (a whole number up to %zu)",
                               what, MESH_MAX_COUNT);
    return HR_OK;
}

static hr_status read_vector(mesh_text *t, const char *what, uint64_t index, hr_vec3 *out)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        mesh_token tok = mesh_text_next(t, 1, 0);
        int ok = mesh_parse_number(&tok, &c[k]);
        if (ok < 0)
            return mesh_text_error(t, &tok, "%s %llu: coordinate out of range (at most %g)", what,
                                   (unsigned long long)index, MESH_MAX_COORDINATE);
        if (ok == 0)
            return mesh_text_error(t, &tok, "%s %llu: expected a number", what,
                                   (unsigned long long)index);
    }
    out->x = c[0], out->y = c[1], out->z = c[2];
    return HR_OK;
}

/* Reads `n` indices below `limit` into out[]. */
static hr_status read_indices(mesh_text *t, uint64_t face, const char *what, uint64_t limit,
                              uint32_t *out, uint64_t n)
{
    for (uint64_t i = 0; i < n; i++) {
        mesh_token tok = mesh_text_next(t, 1, 0);
        uint64_t v;
        if (!mesh_parse_whole(&tok, MESH_MAX_COUNT, &v))
            return mesh_text_error(t, &tok, "face %llu: expected a %s index",
                                   (unsigned long long)face, what);
        if (v >= limit)
            return mesh_text_error(t, &tok, "face %llu: %s index %llu out of range (the file has %llu)",
                                   (unsigned long long)face, what, (unsigned long long)v,
                                   (unsigned long long)limit);
        out[i] = (uint32_t)v;
    }
    return HR_OK;
}

hr_status mesh_read_3vn(mesh_builder *b, const char *text, size_t length, const char *shown,
                        char *error, size_t error_size)
{
    mesh_text t;
    mesh_text_init(&t, text, length, shown, error, error_size);
    uint64_t nv, nn, nf;
    mesh_token count_tok;
    hr_status st;
    if ((st = read_count(&t, "vertices", &nv, &count_tok)) ||
        (st = read_count(&t, "normals", &nn, &count_tok)) ||
        (st = read_count(&t, "faces", &nf, &count_tok)))
        return st;
    /* Every number takes at least one byte and a separator: a vertex or a
     * normal 3 numbers, a face at least 7. */
    const uint64_t tokens = (uint64_t)mesh_text_remaining(&t) / 2 + 1;
    if (nv > tokens / 3 || nn > tokens / 3 || nf > tokens / 7 ||
        3 * nv + 3 * nn + 7 * nf > tokens) {
        return mesh_text_error(&t, &count_tok,
                               "the counts (%llu vertices, %llu normals, %llu faces) need more "
                               "numbers than the rest of the file holds",
                               (unsigned long long)nv, (unsigned long long)nn,
                               (unsigned long long)nf);
    }
    if (mesh_builder_reserve(b, nv, nn, nf)) return HR_ERROR_OUT_OF_MEMORY;
    for (uint64_t i = 0; i < nv; i++) {
        hr_vec3 v;
        if ((st = read_vector(&t, "vertex", i, &v))) return st;
        if (mesh_builder_add_vertex(b, v)) return HR_ERROR_OUT_OF_MEMORY;
    }
    for (uint64_t i = 0; i < nn; i++) {
        hr_vec3 v;
        if ((st = read_vector(&t, "normal", i, &v))) return st;
        if (mesh_builder_add_normal(b, v)) return HR_ERROR_OUT_OF_MEMORY;
    }
    uint32_t *corners = NULL, *normals = NULL;
    uint64_t capacity = 0;
    for (uint64_t f = 0; f < nf && !st; f++) {
        mesh_token tok = mesh_text_next(&t, 1, 0);
        uint64_t n;
        if (!mesh_parse_whole(&tok, MESH_MAX_COUNT, &n)) {
            st = mesh_text_error(&t, &tok, "face %llu: expected its number of corners",
                                 (unsigned long long)f);
            break;
        }
        if (n < 3) {
            st = mesh_text_error(&t, &tok, "face %llu: a face needs at least 3 corners",
                                 (unsigned long long)f);
            break;
        }
        if (2 * n > (uint64_t)mesh_text_remaining(&t) / 2 + 1) {
            st = mesh_text_error(&t, &tok,
                                 "face %llu: %llu corners need more numbers than the rest of "
                                 "the file holds",
                                 (unsigned long long)f, (unsigned long long)n);
            break;
        }
        if (n > capacity) {
            b->host->free(corners);
            b->host->free(normals);
            capacity = n > 2 * capacity ? n : 2 * capacity;
            corners = b->host->alloc((size_t)capacity * sizeof *corners);
            normals = b->host->alloc((size_t)capacity * sizeof *normals);
            if (!corners || !normals) {
                st = HR_ERROR_OUT_OF_MEMORY;
                break;
            }
        }
        if ((st = read_indices(&t, f, "vertex", nv, corners, n)) ||
            (st = read_indices(&t, f, "normal", nn, normals, n)))
            break;
        if (mesh_builder_add_polygon(b, corners, normals, (size_t)n)) st = HR_ERROR_OUT_OF_MEMORY;
    }
    b->host->free(corners);
    b->host->free(normals);
    if (st) return st;
    mesh_token extra = mesh_text_next(&t, 1, 0);
    if (extra.length)
        return mesh_text_error(&t, &extra, "unexpected text after the last of %llu faces",
                               (unsigned long long)nf);
    return HR_OK;
}
