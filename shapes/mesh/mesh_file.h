/* Loading a mesh from a file (mesh_file.c). */
#ifndef HITRAY_MESH_FILE_H
#define HITRAY_MESH_FILE_H

#include "mesh.h"

/* `file` relative to `base_dir` unless absolute or base_dir is empty. On
 * failure writes one line (naming the file, and the line in it for a parse
 * error) to `error` and returns HR_ERROR_IO, HR_ERROR_PARAMETER or
 * HR_ERROR_OUT_OF_MEMORY. */
hr_status mesh_load_file(const hr_host *host, const char *file, const char *base_dir, mesh **out,
                         char *error, size_t error_size);

#endif
