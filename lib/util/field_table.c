/* The field tables (lib/util/field_table.h), generated from the rows of
 * include/hitray/scene_fields.h. */
#include "util/field_table.h"

#include <stdint.h>
#include <string.h>

/* A row's kind is its member's type; a member of any other type stops the
 * build here. */
#define FIELD_KIND(record, field)                                              \
    _Generic(((record *)0)->field, hr_color: HR_FIELD_COLOR,                   \
             double: HR_FIELD_NUMBER, int32_t: HR_FIELD_INTEGER,              \
             const double *: HR_FIELD_NUMBERS)

#define MATERIAL_ROW(field, word, ...)                                         \
    {word, FIELD_KIND(hr_material, field), offsetof(hr_material, field),      \
     {__VA_ARGS__}},
#define GLOBALS_ROW(field, word, ...)                                          \
    {word, FIELD_KIND(hr_scene_globals, field),                              \
     offsetof(hr_scene_globals, field), {__VA_ARGS__}},

static const hr_field material_fields[] = {HR_MATERIAL_FIELDS(MATERIAL_ROW)};
static const hr_field globals_fields[] = {HR_SCENE_GLOBALS_FIELDS(GLOBALS_ROW)};

const hr_field_table hri_material_field_table = {
    material_fields, sizeof material_fields / sizeof material_fields[0]};
const hr_field_table hri_globals_field_table = {
    globals_fields, sizeof globals_fields / sizeof globals_fields[0]};

/* Every member of the structs has a row, but for struct_size, the material's
 * parameter_count (which comes with `parameters`) and its `reserved`: the
 * rows' members and those fill the struct exactly. */
#define MATERIAL_SIZE(field, ...) +sizeof(((hr_material *)0)->field)
#define GLOBALS_SIZE(field, ...) +sizeof(((hr_scene_globals *)0)->field)
_Static_assert(sizeof(uint32_t) + 2 * sizeof(int32_t) HR_MATERIAL_FIELDS(MATERIAL_SIZE) ==
                   sizeof(hr_material),
               "a member of hr_material has no row in HR_MATERIAL_FIELDS (scene_fields.h)");
_Static_assert(sizeof(uint32_t) HR_SCENE_GLOBALS_FIELDS(GLOBALS_SIZE) == sizeof(hr_scene_globals),
               "a member of hr_scene_globals has no row in HR_SCENE_GLOBALS_FIELDS (scene_fields.h)");

const hr_field *hri_field_find(const hr_field_table *table, const char *word)
{
    for (size_t i = 0; i < table->count; i++)
        if (strcmp(table->fields[i].word, word) == 0) return &table->fields[i];
    return NULL;
}

void hri_fields_default(const hr_field_table *table, void *record)
{
    for (size_t i = 0; i < table->count; i++) {
        const hr_field *f = &table->fields[i];
        void *at = hri_field_in(record, f);
        if (f->kind == HR_FIELD_COLOR) {
            hr_color c = {f->initial[0], f->initial[1], f->initial[2]};
            memcpy(at, &c, sizeof c);
        } else if (f->kind == HR_FIELD_NUMBER) {
            memcpy(at, &f->initial[0], sizeof(double));
        } else if (f->kind == HR_FIELD_INTEGER) {
            int32_t v = (int32_t)f->initial[0];
            memcpy(at, &v, sizeof v);
        }
        /* HR_FIELD_NUMBERS: no parameters, which the zeroed record has. */
    }
}
