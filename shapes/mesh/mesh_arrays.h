/* A mesh from arrays given as HR_PARAM_NUMBERS parameters (mesh_arrays.c). */
#ifndef HITRAY_MESH_ARRAYS_H
#define HITRAY_MESH_ARRAYS_H

#include "mesh.h"

/* Reads `points`, `triangles` and `normals` from args; on a refusal writes
 * the parameter and what is wrong to args->error and returns
 * HR_ERROR_PARAMETER (or HR_ERROR_OUT_OF_MEMORY). */
hr_status mesh_arrays_create(const hr_create_args *args, mesh **out);

#endif
