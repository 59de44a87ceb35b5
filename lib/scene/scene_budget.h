/* The scene budget: the memory one scene's objects, shape data (a mesh's
 * triangles) and pixmaps' texels may take in all, checked before each is
 * allocated, so a small file (5M spheres in 97 KB of gzip, twenty lines
 * of one PNG, `teapot 128` ten times) cannot take the machine's memory. */
#ifndef HITRAY_LIB_SCENE_BUDGET_H
#define HITRAY_LIB_SCENE_BUDGET_H

#include <stddef.h>
#include <stdint.h>

#include <hitray/hitray.h>

#define HR_SCENE_MEMORY_ENV "HITRAY_MAX_SCENE_MEMORY"

typedef struct hr_scene_budget {
    uint64_t limit;
    uint64_t objects, shape_data, texels; /* bytes charged, by kind */
    uint64_t refused;                     /* the last request refused, bytes */
} hr_scene_budget;

/* The budget a new scene of `ctx` gets: hr_context_set_scene_memory's, or
 * HITRAY_MAX_SCENE_MEMORY, or half of what the process may use (the lesser
 * of RLIMIT_AS and physical memory). */
hr_status hri_scene_budget_init(hr_context *ctx, hr_scene_budget *b);
/* Charges `bytes` of `kind` (one of the budget's counters), or refuses
 * with an HR_ERROR_OUT_OF_MEMORY naming what was asked for (printf's
 * `what_format` and the arguments after it, formatted only then), the
 * amounts and how to raise the limit, charging nothing. */
hr_status hri_scene_budget_charge(const hr_context *ctx, hr_scene_budget *b, uint64_t *kind, uint64_t bytes,
                                 const char *what_format, ...) __attribute__((format(printf, 5, 6)));
/* The refusal's message after a shape's create failed for want of budget
 * (b->refused set by the allocator). */
hr_status hri_scene_budget_refused(const hr_context *ctx, const hr_scene_budget *b, const char *what_format, ...)
    __attribute__((format(printf, 3, 4)));

/* Shape data: hr_host.alloc and free. Between begin and end on this thread
 * (a shape's create) every allocation is charged to `b`, or refused past
 * its limit, and every free gives its bytes back. */
void hri_scene_budget_begin(hr_scene_budget *b);
void hri_scene_budget_end(void);
void *hri_scene_budget_alloc(size_t size);
void hri_scene_budget_free(void *p);

#endif
