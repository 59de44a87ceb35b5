/* Internal: the field tables of include/hitray/scene_fields.h as data, for
 * the code that finds a field by its SDL keyword or walks every field. */
#ifndef HITRAY_LIB_UTIL_FIELD_TABLE_H
#define HITRAY_LIB_UTIL_FIELD_TABLE_H

#include <stddef.h>

#include <hitray/hitray.h>

/* How a field is read and stored; its member's type in the struct. */
typedef enum hr_field_kind {
    HR_FIELD_COLOR,   /* hr_color */
    HR_FIELD_NUMBER,  /* double */
    HR_FIELD_INTEGER, /* int32_t */
    HR_FIELD_NUMBERS  /* hr_material.parameters with its parameter_count */
} hr_field_kind;

typedef struct hr_field {
    const char *word; /* SDL's keyword */
    hr_field_kind kind;
    size_t offset;    /* of the member in its struct */
    double initial[3]; /* the default: r g b, or one number */
} hr_field;

typedef struct hr_field_table {
    const hr_field *fields;
    size_t count;
} hr_field_table;

extern const hr_field_table hri_material_field_table; /* hr_material */
extern const hr_field_table hri_globals_field_table;  /* hr_scene_globals */

/* The field whose SDL keyword is `word`, NULL if none. */
const hr_field *hri_field_find(const hr_field_table *table, const char *word);

/* Where `field` lies in `record`, a struct of the table's type. */
static inline void *hri_field_in(void *record, const hr_field *field)
{
    return (char *)record + field->offset;
}

/* Set every field of `record`, zeroed before, to its default. */
void hri_fields_default(const hr_field_table *table, void *record);

#endif
