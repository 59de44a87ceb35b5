/* A scene's materials, each kept once (material_store.h). */
#include "scene/material_store.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* The bytes two materials must share: every field up to `parameters`, then
 * the parameters themselves. */
#define MATERIAL_FIELDS offsetof(hr_material, parameters)

/* Eight bytes at a time (a material is 160 of them before `parameters`,
 * a multiple of eight, and parameters are doubles), each word mixed in by a
 * multiply and a shift. */
static uint64_t mix(uint64_t h, const void *bytes, size_t words)
{
    const unsigned char *b = bytes;
    for (size_t i = 0; i < words; i++) {
        uint64_t w;
        memcpy(&w, b + 8 * i, sizeof w);
        h = (h ^ w) * 0x9e3779b97f4a7c15ull;
        h ^= h >> 29;
    }
    return h;
}

_Static_assert(offsetof(hr_material, parameters) % 8 == 0, "the fields before parameters are whole words");

static uint64_t material_hash(const hr_material *m)
{
    uint64_t h = mix(0, m, MATERIAL_FIELDS / 8);
    if (m->parameter_count > 0) h = mix(h, m->parameters, (size_t)m->parameter_count);
    return h;
}

static int same_material(const hr_material *a, const hr_material *b)
{
    return memcmp(a, b, MATERIAL_FIELDS) == 0 &&
           (a->parameter_count <= 0 ||
            memcmp(a->parameters, b->parameters, (size_t)a->parameter_count * sizeof(double)) == 0);
}

/* Puts item index i into the slots (there is room). */
static void place(hri_material_store *st, uint32_t i)
{
    uint32_t k = (uint32_t)material_hash(st->items[i]) & (st->slot_count - 1);
    while (st->slots[k]) k = (k + 1) & (st->slot_count - 1);
    st->slots[k] = i + 1;
}

/* Room for one more item, and slots at least twice the items. */
static int grow(hri_material_store *st)
{
    if (st->count == st->cap) {
        uint32_t cap = st->cap ? 2 * st->cap : 8;
        hr_material **items = realloc(st->items, (size_t)cap * sizeof *items);
        if (!items) return 0;
        st->items = items, st->cap = cap;
    }
    if (2 * (st->count + 1) > st->slot_count) {
        uint32_t n = st->slot_count ? 2 * st->slot_count : 16;
        uint32_t *slots = calloc(n, sizeof *slots);
        if (!slots) return 0;
        free(st->slots);
        st->slots = slots, st->slot_count = n;
        for (uint32_t i = 0; i < st->count; i++) place(st, i);
    }
    return 1;
}

const hr_material *hri_material_store_add(hri_material_store *st, const hr_material *m)
{
    /* Objects added one after another mostly share a material (a scene
     * file's current one): the last stored or found, before any hashing. */
    if (st->last && same_material(st->last, m)) return st->last;
    if (st->slot_count) {
        uint32_t k = (uint32_t)material_hash(m) & (st->slot_count - 1);
        for (; st->slots[k]; k = (k + 1) & (st->slot_count - 1))
            if (same_material(st->items[st->slots[k] - 1], m)) return st->last = st->items[st->slots[k] - 1];
    }
    if (!grow(st)) return NULL;
    const size_t params = m->parameter_count > 0 ? (size_t)m->parameter_count : 0;
    hr_material *copy = malloc(sizeof *copy + params * sizeof(double));
    if (!copy) return NULL;
    *copy = *m;
    double *stored = (double *)(void *)(copy + 1);
    if (params) memcpy(stored, m->parameters, params * sizeof(double));
    copy->parameters = params ? stored : NULL;
    st->items[st->count] = copy;
    place(st, st->count++);
    return st->last = copy;
}

void hri_material_store_free(hri_material_store *st)
{
    for (uint32_t i = 0; i < st->count; i++) free(st->items[i]);
    free(st->items);
    free(st->slots);
    memset(st, 0, sizeof *st);
}
