#include "mesh_support.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hr_test.h"

hr_param mesh_numbers_param(const char *name, const double *values, int64_t count)
{
    hr_param p;
    memset(&p, 0, sizeof p);
    p.name = name;
    p.type = HR_PARAM_NUMBERS;
    p.numbers = values;
    p.count = count;
    return p;
}

const char *mesh_data_path(const char *name, char *buf, size_t size)
{
    snprintf(buf, size, "%s/tests/data/meshes/%s", HR_TEST_SOURCE_DIR, name);
    return buf;
}

const char *mesh_build_path(const char *name, char *buf, size_t size)
{
    snprintf(buf, size, "%s/tests/%s", HR_TEST_BINARY_DIR, name);
    return buf;
}

hr_status mesh_create_file(const harness_module *module, const char *file, void **shape,
                           char *error, size_t error_size)
{
    return mesh_create_file_on(module, harness_host(), file, shape, error, error_size);
}

hr_status mesh_create_file_on(const harness_module *module, const hr_host *host, const char *file,
                              void **shape, char *error, size_t error_size)
{
    const hr_shape_class *cls = harness_find_class(module, "mesh");
    *shape = NULL;
    if (!cls) return HR_ERROR_MODULE;
    hr_param param;
    memset(&param, 0, sizeof param);
    param.name = "file";
    param.type = HR_PARAM_STRING;
    param.string = file;
    const void *objects[1] = {NULL};
    hr_create_args args;
    memset(&args, 0, sizeof args);
    args.struct_size = sizeof args;
    args.param_count = 1;
    args.params = &param;
    args.objects = objects;
    args.host = host;
    args.error = error;
    args.error_size = error_size;
    args.base_dir = "";
    error[0] = '\0';
    return cls->create(&args, shape);
}

int mesh_open_file(harness_shape *out, const char *file)
{
    memset(out, 0, sizeof *out);
    if (!harness_load("mesh", &out->module)) return 0;
    out->cls = harness_find_class(&out->module, "mesh");
    char error[512];
    hr_status st = mesh_create_file(&out->module, file, &out->shape, error, sizeof error);
    CHECK_MSG(st == HR_OK && out->shape, "mesh %s: status %d: %s", file, (int)st, error);
    return st == HR_OK && out->shape != NULL;
}

int mesh_open_text(harness_shape *out, const char *name, const char *text)
{
    char path[1024];
    mesh_build_path(name, path, sizeof path);
    FILE *f = fopen(path, "w");
    CHECK_MSG(f != NULL, "%s: not written", path);
    if (!f) return 0;
    const int written = fputs(text, f) >= 0;
    const int closed = fclose(f) == 0;
    CHECK_MSG(written && closed, "%s: not written", path);
    return written && closed && mesh_open_file(out, path);
}

void mesh_check_first_is_all_first(const char *name, const char *text, hr_ray ray)
{
    harness_shape shape;
    if (!mesh_open_text(&shape, name, text)) return;
    hr_hit all[HARNESS_MAX_HITS], first[HARNESS_MAX_HITS];
    const int n_all = harness_trace(&shape, ray, 0.0, INFINITY, HARNESS_ALL, all);
    const int n_first = harness_trace(&shape, ray, 0.0, INFINITY, HARNESS_FIRST, first);
    CHECK_MSG(n_all >= 1 && n_first == 1, "%s: %d hits, %d first hits", name, n_all, n_first);
    if (n_all >= 1 && n_first == 1)
        CHECK_MSG(first[0].t == all[0].t && first[0].entering == all[0].entering,
                  "%s: first hit t %a entering %d, all hits' first t %a entering %d", name, first[0].t,
                  (int)first[0].entering, all[0].t, (int)all[0].entering);
    harness_close(&shape);
}
