/* Wavefront OBJ, the geometry of it: `v x y z [w]` vertices, `vn x y z`
 * normals, `vt u [v [w]]` texture coordinates and `f` faces whose corners
 * are `v`, `v/vt`, `v//vn` or `v/vt/vn` (1-based; negative indices count
 * back from the latest vertex, normal or texture coordinate, as OBJ
 * defines). A face uses normals only when every corner names one, and
 * texture coordinates likewise (a texture index past the `vt`s defined,
 * which files without any `vt` carry, gives the corner none). Polygons are
 * fanned into triangles from their first corner. Groups, objects, smoothing
 * groups, materials, lines and points are read past; any other statement
 * is an error, so a file that is not OBJ is not taken for an empty one.
 * '#' starts a comment. */
#include <string.h>

#include "mesh.h"
#include "mesh_text.h"

static const char *const ignored[] = {"vp", "o", "g", "s", "usemtl", "mtllib", "l", "p"};

static hr_status read_vector(mesh_text *t, const mesh_token *keyword, hr_vec3 *out, int extra)
{
    double c[3];
    for (int k = 0; k < 3; k++) {
        mesh_token tok = mesh_text_next(t, 0, 1);
        int ok = mesh_parse_number(&tok, &c[k]);
        if (ok < 0)
            return mesh_text_error(t, &tok, "'%.*s': coordinate out of range (at most %g)",
                                   (int)keyword->length, keyword->start, MESH_MAX_COORDINATE);
        if (ok == 0)
            return mesh_text_error(t, &tok, "'%.*s': expected a number", (int)keyword->length,
                                   keyword->start);
    }
    /* A vertex may carry a weight or a colour after x y z: numbers, read
     * and not used. */
    for (int k = 0;; k++) {
        mesh_token tok = mesh_text_next(t, 0, 1);
        if (!tok.length) break;
        double ignored_value;
        if (k >= extra || mesh_parse_number(&tok, &ignored_value) != 1)
            return mesh_text_error(t, &tok, "'%.*s': unexpected text after the coordinates",
                                   (int)keyword->length, keyword->start);
    }
    out->x = c[0], out->y = c[1], out->z = c[2];
    return HR_OK;
}

/* `vt u [v [w]]`: v defaults to 0, w is read and not used. */
static hr_status read_texcoord(mesh_text *t, const mesh_token *keyword, mesh_texcoord *out)
{
    double c[3] = {0.0, 0.0, 0.0};
    int k = 0;
    for (;; k++) {
        mesh_token tok = mesh_text_next(t, 0, 1);
        if (!tok.length) break;
        int ok = k < 3 ? mesh_parse_number(&tok, &c[k]) : 0;
        if (ok < 0)
            return mesh_text_error(t, &tok, "'vt': coordinate out of range (at most %g)",
                                   MESH_MAX_COORDINATE);
        if (ok == 0)
            return mesh_text_error(t, &tok, k < 3 ? "'vt': expected a number"
                                                  : "'vt': unexpected text after the coordinates");
    }
    if (k == 0) return mesh_text_error(t, keyword, "'vt': expected at least u");
    out->u = c[0], out->v = c[1];
    return HR_OK;
}

/* One index of a corner: 1-based, or negative from the end; 0 and
 * references past what is defined so far are errors. */
static int resolve_index(const char *s, size_t n, size_t defined, uint32_t *out)
{
    int negative = n > 0 && s[0] == '-';
    mesh_token digits = {s + negative, n - (size_t)negative, 0};
    uint64_t v;
    if (!mesh_parse_whole(&digits, MESH_MAX_COUNT, &v) || v == 0 || v > defined) return 0;
    *out = (uint32_t)(negative ? defined - v : v - 1);
    return 1;
}

typedef struct corner_buffers {
    uint32_t *vertices, *normals, *texcoords;
    size_t capacity;
} corner_buffers;

static hr_status read_face(mesh_builder *b, mesh_text *t, const mesh_token *keyword,
                           corner_buffers *buf)
{
    size_t n = 0;
    int all_normals = 1, all_texcoords = 1;
    for (;;) {
        mesh_token tok = mesh_text_next(t, 0, 1);
        if (!tok.length) break;
        if (n == buf->capacity) {
            /* Corners are bounded by the tokens of the line, hence by the file. */
            size_t cap = buf->capacity ? 2 * buf->capacity : 16;
            uint32_t **arrays[3] = {&buf->vertices, &buf->normals, &buf->texcoords};
            uint32_t *grown[3];
            for (int a = 0; a < 3; a++) {
                grown[a] = b->host->alloc(cap * sizeof *grown[a]);
                if (!grown[a]) {
                    while (a-- > 0) b->host->free(grown[a]);
                    return HR_ERROR_OUT_OF_MEMORY;
                }
            }
            for (int a = 0; a < 3; a++) {
                if (n) memcpy(grown[a], *arrays[a], n * sizeof *grown[a]);
                b->host->free(*arrays[a]);
                *arrays[a] = grown[a];
            }
            buf->capacity = cap;
        }
        /* v, v/vt, v//vn, v/vt/vn */
        const char *s = tok.start, *end = tok.start + tok.length;
        const char *slash1 = memchr(s, '/', tok.length);
        const char *vend = slash1 ? slash1 : end;
        if (!resolve_index(s, (size_t)(vend - s), b->vertex_count, &buf->vertices[n]))
            return mesh_text_error(t, &tok,
                                   "face corner %zu: vertex index missing or out of range (%zu "
                                   "vertices so far)",
                                   n + 1, b->vertex_count);
        buf->normals[n] = MESH_NO_NORMAL;
        buf->texcoords[n] = MESH_NO_TEXCOORD;
        if (slash1) {
            const char *slash2 = memchr(slash1 + 1, '/', (size_t)(end - slash1 - 1));
            if (slash2) {
                if (memchr(slash2 + 1, '/', (size_t)(end - slash2 - 1)))
                    return mesh_text_error(t, &tok, "face corner %zu: more than three indices",
                                           n + 1);
                if (slash2 + 1 == end ||
                    !resolve_index(slash2 + 1, (size_t)(end - slash2 - 1), b->normal_count,
                                   &buf->normals[n]))
                    return mesh_text_error(t, &tok,
                                           "face corner %zu: normal index missing or out of "
                                           "range (%zu normals so far)",
                                           n + 1, b->normal_count);
            }
            /* The texture index must be well formed; one past the `vt`s
             * defined gives the corner no texture coordinate. */
            const char *tend = slash2 ? slash2 : end;
            if (tend > slash1 + 1) {
                mesh_token tex = {slash1 + 1, (size_t)(tend - slash1 - 1), 0};
                uint64_t index;
                int neg = tex.start[0] == '-';
                mesh_token digits = {tex.start + neg, tex.length - (size_t)neg, 0};
                if (!mesh_parse_whole(&digits, MESH_MAX_COUNT, &index))
                    return mesh_text_error(t, &tok, "face corner %zu: bad texture index", n + 1);
                if (!resolve_index(tex.start, tex.length, b->texcoord_count, &buf->texcoords[n]))
                    buf->texcoords[n] = MESH_NO_TEXCOORD;
            } else if (!slash2) {
                return mesh_text_error(t, &tok, "face corner %zu: nothing after '/'", n + 1);
            }
        }
        if (buf->normals[n] == MESH_NO_NORMAL) all_normals = 0;
        if (buf->texcoords[n] == MESH_NO_TEXCOORD) all_texcoords = 0;
        n++;
    }
    if (n < 3)
        return mesh_text_error(t, keyword, "a face needs at least 3 corners, this one has %zu", n);
    if (mesh_builder_add_polygon_uv(b, buf->vertices, all_normals ? buf->normals : NULL,
                                    all_texcoords ? buf->texcoords : NULL, n))
        return HR_ERROR_OUT_OF_MEMORY;
    return HR_OK;
}

hr_status mesh_read_obj(mesh_builder *b, const char *text, size_t length, const char *shown,
                        char *error, size_t error_size)
{
    mesh_text t;
    mesh_text_init(&t, text, length, shown, error, error_size);
    corner_buffers buf = {NULL, NULL, NULL, 0};
    hr_status st = HR_OK;
    while (!st) {
        mesh_token keyword = mesh_text_next(&t, 1, 1);
        if (!keyword.length) break;
        if (mesh_token_is(&keyword, "v")) {
            hr_vec3 v;
            if (!(st = read_vector(&t, &keyword, &v, 4)) && mesh_builder_add_vertex(b, v))
                st = HR_ERROR_OUT_OF_MEMORY;
        } else if (mesh_token_is(&keyword, "vn")) {
            hr_vec3 n;
            if (!(st = read_vector(&t, &keyword, &n, 0)) && mesh_builder_add_normal(b, n))
                st = HR_ERROR_OUT_OF_MEMORY;
        } else if (mesh_token_is(&keyword, "vt")) {
            mesh_texcoord tc;
            if (!(st = read_texcoord(&t, &keyword, &tc)) && mesh_builder_add_texcoord(b, tc))
                st = HR_ERROR_OUT_OF_MEMORY;
        } else if (mesh_token_is(&keyword, "f")) {
            st = read_face(b, &t, &keyword, &buf);
        } else {
            int known = 0;
            for (size_t i = 0; i < sizeof ignored / sizeof ignored[0]; i++)
                known |= mesh_token_is(&keyword, ignored[i]);
            if (!known)
                st = mesh_text_error(&t, &keyword,
                                     "unknown OBJ statement (expected v, vn, f, or one of vt "
                                     "vp o g s usemtl mtllib l p)");
            mesh_text_skip_line(&t);
        }
    }
    b->host->free(buf.vertices);
    b->host->free(buf.normals);
    b->host->free(buf.texcoords);
    return st;
}
