/* Fuzz harness: the mesh readers (shapes/mesh: Hill's .3vn and Wavefront
 * OBJ), on text in memory.
 *
 * Every input is read by both readers (a corpus file is a plain mesh file
 * of either format). A reader either refuses, with HR_ERROR_PARAMETER (or
 * HR_ERROR_OUT_OF_MEMORY) and a message "<name>:<line>: ..." whose line is
 * one of the input's, or fills the builder; mesh_builder_finish then makes
 * the mesh (its BVH) or refuses with a message. A mesh made is traced, as
 * the module's `mesh` class, by a fixed set of rays aimed at its bounds,
 * its centre and its first vertices (rays through vertices and edges are
 * where the watertight test's tie-breaking works), every call checked by
 * the module harness, the three hit functions against each other and the
 * points against the bounds (fuzz_modes.h); along the whole line, a mesh
 * that is closed (every edge used once each way) must be entered as often
 * as it is left: the winding number is 0 at both ends of the line, and a
 * watertight test crosses each sheet once. (Its hits need not alternate:
 * a file's closed surface may pass through itself, where the winding
 * number goes to 2; the regular solids, which are convex, are checked for
 * alternation by fuzz_shapes.c.) The readers must never crash, hang or leak, whatever
 * the bytes (libFuzzer's -timeout and leak checking see to the last two). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_input.h"
#include "fuzz_mesh_t_error.h"
#include "fuzz_modes.h"
#include "hr_test.h"
#include "mesh.h"
#include "module_harness.h"

static harness_module mesh_module;
static const hr_shape_class *mesh_class;

int LLVMFuzzerInitialize(int *argc, char ***argv)
{
    (void)argc;
    (void)argv;
    /* The module's sources are compiled in: its entry point is ours. */
    mesh_module.info = hr_shape_module(HR_SHAPE_ABI_VERSION, harness_host());
    snprintf(mesh_module.path, sizeof mesh_module.path, "(the mesh module, compiled in)");
    mesh_class = harness_find_class(&mesh_module, "mesh");
    if (!mesh_class) fuzz_fail("the mesh module has no class 'mesh'");
    return 0;
}

/* "<name>:<line>: " with 1 <= line <= lines. */
static void check_message(const char *name, const char *error, long lines, hr_status st)
{
    if (st == HR_ERROR_OUT_OF_MEMORY) return;
    if (st != HR_ERROR_PARAMETER) fuzz_fail("%s: refused with status %d: %s", name, (int)st, error);
    const size_t n = strlen(name);
    long line = 0;
    int used = 0;
    if (strncmp(error, name, n) != 0 || error[n] != ':' ||
        sscanf(error + n + 1, "%ld: %n", &line, &used) != 1 || used == 0)
        fuzz_fail("%s: the message does not start with '%s:<line>: ': %s", name, name, error);
    if (line < 1 || line > lines)
        fuzz_fail("%s: the message names line %ld of %ld: %s", name, line, lines, error);
}

static hr_ray ray_between(hr_vec3 from, hr_vec3 to)
{
    hr_ray r = {from, {to.x - from.x, to.y - from.y, to.z - from.z}};
    return r;
}

static void trace_mesh(mesh *m)
{
    harness_shape shape;
    memset(&shape, 0, sizeof shape);
    shape.module = mesh_module;
    shape.cls = mesh_class;
    shape.shape = m;
    const hr_bounds b = m->bounds;
    const hr_vec3 c = {0.5 * b.lo.x + 0.5 * b.hi.x, 0.5 * b.lo.y + 0.5 * b.hi.y,
                       0.5 * b.lo.z + 0.5 * b.hi.z};
    const double size = fmax(b.hi.x - b.lo.x, fmax(b.hi.y - b.lo.y, b.hi.z - b.lo.z)) + 1.0;
    /* From outside the box: along the axes at the centre, and from a
     * corner direction at the centre and at the first vertices. */
    const hr_vec3 from[] = {
        {c.x - 2 * size, c.y, c.z}, {c.x, c.y - 2 * size, c.z}, {c.x, c.y, c.z + 2 * size},
        {c.x + 2 * size, c.y + 1.5 * size, c.z + 1.25 * size},
    };
    hr_vec3 targets[8];
    int target_count = 0;
    targets[target_count++] = c;
    for (uint32_t i = 0; i < m->vertex_count && target_count < 8; i++)
        targets[target_count++] = m->vertices[i];
    const double intervals[][2] = {{0.0, INFINITY}, {-INFINITY, INFINITY}, {0.5, 0.75}};
    for (size_t f = 0; f < sizeof from / sizeof from[0]; f++)
        for (int t = 0; t < target_count; t++)
            for (size_t k = 0; k < sizeof intervals / sizeof intervals[0]; k++) {
                const hr_ray ray = ray_between(from[f], targets[t]);
                if (!(ray.dir.x != 0 || ray.dir.y != 0 || ray.dir.z != 0)) continue;
                const double tmin = intervals[k][0], tmax = intervals[k][1];
                hr_hit all[HARNESS_MAX_HITS];
                const int n =
                    fuzz_trace_modes(&shape, ray, tmin, tmax, m->closed, fuzz_mesh_line_t_error(m, &ray), all);
                /* harness_trace copies at most HARNESS_MAX_HITS: a list that
                 * long may be longer, and its balance cannot be counted. */
                if (!m->closed || tmin != -INFINITY || n >= HARNESS_MAX_HITS) continue;
                int winding = 0;
                for (int i = 0; i < n; i++) winding += all[i].entering ? 1 : -1;
                if (winding != 0)
                    fuzz_fail(FUZZ_RAY_FMT "a closed mesh entered %d times more than left",
                              FUZZ_RAY_ARGS("mesh", ray, tmin, tmax), winding);
            }
}

typedef hr_status (*reader_fn)(mesh_builder *, const char *, size_t, const char *, char *,
                               size_t);

static void read_with(reader_fn reader, const char *name, const char *text, size_t size,
                      long lines)
{
    mesh_builder b;
    mesh_builder_init(&b, harness_host());
    char error[512] = "";
    hr_status st = reader(&b, text, size, name, error, sizeof error);
    if (st) {
        check_message(name, error, lines, st);
        mesh_builder_release(&b);
        return;
    }
    mesh *m = NULL;
    char why[256] = "";
    st = mesh_builder_finish(&b, &m, why, sizeof why);
    mesh_builder_release(&b);
    if (st) {
        if (m) fuzz_fail("%s: mesh_builder_finish refused and still made a mesh", name);
        if (st == HR_ERROR_PARAMETER && !why[0])
            fuzz_fail("%s: mesh_builder_finish refused without a message", name);
        return;
    }
    trace_mesh(m);
    mesh_destroy(m);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    /* A line count for the message check: a line past the last newline
     * counts, and an error at the end of the file names the last line. */
    long lines = 1;
    for (size_t i = 0; i < size; i++) lines += data[i] == '\n';
    const char *text = (const char *)data;
    read_with(mesh_read_3vn, "fuzz.3vn", text, size, lines);
    read_with(mesh_read_obj, "fuzz.obj", text, size, lines);
    fuzz_require_no_failures("mesh");
    return 0;
}
