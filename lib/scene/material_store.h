/* Internal: a scene's materials, each kept once. Objects whose materials
 * are the same, byte for byte (their texture parameters too), point at one
 * copy, so that a scene of many objects of few materials (the usual one)
 * pays for each material once rather than 168 bytes and a parameter copy
 * for every object (lib/scene/scene_objects.c). */
#ifndef HITRAY_LIB_SCENE_MATERIAL_STORE_H
#define HITRAY_LIB_SCENE_MATERIAL_STORE_H

#include <stdint.h>

#include <hitray/hitray.h>

typedef struct hri_material_store {
    hr_material **items; /* each with its parameters stored right after it */
    uint32_t count, cap;
    uint32_t *slots;     /* open addressing by hash: index + 1, 0 empty */
    uint32_t slot_count; /* a power of two, at least twice count (0: none yet) */
    const hr_material *last; /* the one the last add returned */
} hri_material_store;

/* The store's copy of `m` (whose parameter_count parameters are read from
 * m->parameters), made on first sight; its `parameters` point into the
 * copy. NULL when out of memory. */
const hr_material *hri_material_store_add(hri_material_store *store, const hr_material *m);
void hri_material_store_free(hri_material_store *store);

#endif
