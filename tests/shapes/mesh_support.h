/* Helpers of the mesh module's tests: opening a `mesh` shape on a file (the
 * harness only sets number parameters), paths of the test data, and writing
 * generated OBJ files into the build tree. */
#ifndef HR_TEST_MESH_SUPPORT_H
#define HR_TEST_MESH_SUPPORT_H

#include <stddef.h>
#include <stdint.h>

#include "module_harness.h"

/* A parameter of type HR_PARAM_NUMBERS: `count` numbers at `values` (the
 * triangleMesh class's points, triangles and normals). */
hr_param mesh_numbers_param(const char *name, const double *values, int64_t count);

/* HR_TEST_SOURCE_DIR "/tests/data/meshes/" name */
const char *mesh_data_path(const char *name, char *buf, size_t size);
/* HR_TEST_BINARY_DIR "/tests/" name, for generated files */
const char *mesh_build_path(const char *name, char *buf, size_t size);

/* Creates class `mesh` of the loaded module on `file` (base_dir ""), with
 * the harness's host. Returns create's status; the message in error. */
hr_status mesh_create_file(const harness_module *module, const char *file, void **shape,
                           char *error, size_t error_size);
/* The same with another host (an older one, one whose services fail). */
hr_status mesh_create_file_on(const harness_module *module, const hr_host *host, const char *file,
                              void **shape, char *error, size_t error_size);

/* harness_open for a `mesh` on `file`. 1 on success. */
int mesh_open_file(harness_shape *out, const char *file);
/* Writes `text` to mesh_build_path(name) and opens a `mesh` on it. 1 on
 * success; a failure is a failed check. */
int mesh_open_text(harness_shape *out, const char *name, const char *text);
/* Opens a `mesh` on `text` (mesh_open_text), traces `ray` over (0, inf)
 * for all hits and for the first, and checks that there is a first hit and
 * that it is all hits' first: the same t and entering flag (a closed
 * mesh's first-hit search against its all-hits list). */
void mesh_check_first_is_all_first(const char *name, const char *text, hr_ray ray);

#endif
