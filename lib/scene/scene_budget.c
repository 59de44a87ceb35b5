/* The scene budget (scene_budget.h). */
#include "scene/scene_budget.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "core/context_internal.h"
#include "util/env_bytes.h"
#include "util/errors.h"

/* What the process may use: RLIMIT_AS where set, physical memory where
 * known, else 2^40 (nothing tells). */
static uint64_t process_memory(void)
{
    uint64_t m = (uint64_t)1 << 40;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) m = (uint64_t)pages * (uint64_t)page;
    struct rlimit r;
    if (getrlimit(RLIMIT_AS, &r) == 0 && r.rlim_cur != RLIM_INFINITY && (uint64_t)r.rlim_cur < m)
        m = (uint64_t)r.rlim_cur;
    return m;
}

hr_status hri_scene_budget_init(hr_context *ctx, hr_scene_budget *b)
{
    memset(b, 0, sizeof *b);
    if (ctx->scene_memory) {
        b->limit = ctx->scene_memory;
        return HR_OK;
    }
    /* Half: the render's own buffers, the scene's acceleration structure and
     * the program around the library need room too. */
    const uint64_t half = process_memory() / 2;
    return hri_env_bytes(ctx, HR_SCENE_MEMORY_ENV, "the memory one scene may take", half, half, UINT64_MAX,
                        &b->limit);
}

static hr_status over(const hr_context *ctx, const hr_scene_budget *b, uint64_t bytes, const char *what_format,
                      va_list ap)
{
    char what[256];
    vsnprintf(what, sizeof what, what_format, ap);
    return hri_error(ctx, HR_ERROR_OUT_OF_MEMORY,
                    "%s needs %llu bytes more than the scene's memory budget of %llu bytes leaves (it holds "
                    "%llu bytes of objects, %llu of shape data, %llu of texels); set %s or "
                    "hr_context_set_scene_memory to raise it",
                    what, (unsigned long long)bytes, (unsigned long long)b->limit,
                    (unsigned long long)b->objects, (unsigned long long)b->shape_data,
                    (unsigned long long)b->texels, HR_SCENE_MEMORY_ENV);
}

static uint64_t used(const hr_scene_budget *b) { return b->objects + b->shape_data + b->texels; }

hr_status hri_scene_budget_charge(const hr_context *ctx, hr_scene_budget *b, uint64_t *kind, uint64_t bytes,
                                 const char *what_format, ...)
{
    if (bytes <= b->limit - used(b)) {
        *kind += bytes;
        return HR_OK;
    }
    va_list ap;
    va_start(ap, what_format);
    hr_status st = over(ctx, b, bytes, what_format, ap);
    va_end(ap);
    return st;
}

hr_status hri_scene_budget_refused(const hr_context *ctx, const hr_scene_budget *b, const char *what_format, ...)
{
    va_list ap;
    va_start(ap, what_format);
    hr_status st = over(ctx, b, b->refused, what_format, ap);
    va_end(ap);
    return st;
}

/* The bytes a block holds. Blocks stay plain calloc blocks, so a module
 * that frees its shape data with free() still works (hr_host never said
 * otherwise); without malloc_usable_size a block counts as asked for and
 * frees are not given back, which overcounts. */
static size_t block_size(void *p, size_t asked)
{
#ifdef __GLIBC__
    (void)asked;
    return malloc_usable_size(p);
#else
    (void)p;
    return asked;
#endif
}

static _Thread_local hr_scene_budget *charging;

void hri_scene_budget_begin(hr_scene_budget *b) { charging = b; }
void hri_scene_budget_end(void) { charging = NULL; }

void *hri_scene_budget_alloc(size_t size)
{
    if (size == 0) size = 1;
    hr_scene_budget *b = charging;
    if (b && size > b->limit - used(b)) {
        b->refused = size;
        return NULL;
    }
    void *p = calloc(1, size);
    if (p && b) b->shape_data += block_size(p, size);
    return p;
}

/* Only a free while a shape is made gives bytes back (a temporary buffer
 * of its reader): the rest go when the scene goes. */
void hri_scene_budget_free(void *p)
{
    hr_scene_budget *b = charging;
#ifdef __GLIBC__
    if (p && b) {
        const size_t n = malloc_usable_size(p);
        b->shape_data -= n < b->shape_data ? n : b->shape_data;
    }
#else
    (void)b;
#endif
    free(p);
}
