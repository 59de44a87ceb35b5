/* Loading a mesh from a file (mesh_file.c). */
#ifndef HITRAY_MESH_FILE_H
#define HITRAY_MESH_FILE_H

#include "mesh.h"

/* `file` relative to the create's base_dir unless absolute or base_dir is
 * empty; the file read is told to the host (hr_host.file_read, where the
 * host has it). On failure writes one line (naming the file, and the line
 * in it for a parse error) to args->error and returns HR_ERROR_IO,
 * HR_ERROR_PARAMETER or HR_ERROR_OUT_OF_MEMORY. */
hr_status mesh_load_file(const hr_create_args *args, const char *file, mesh **out);

#endif
