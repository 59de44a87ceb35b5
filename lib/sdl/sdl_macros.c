/* SDL macros (lib/sdl/sdl_macros.h): the table and the `def` / `use` commands. */
#include "sdl/sdl_macros.h"

#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_hash.h"
#include "sdl/sdl_source.h"
#include "sdl/sdl_words.h"

void sdl_macros_init(sdl_macro_table *table) { memset(table, 0, sizeof *table); }

void sdl_macros_release(sdl_macro_table *table)
{
    free(table->macros);
    free(table->slots);
    memset(table, 0, sizeof *table);
}

int32_t sdl_macros_find(const sdl_macro_table *table, const char *name)
{
    if (table->slot_count == 0) return -1;
    size_t mask = table->slot_count - 1;
    for (size_t i = sdl_hash_name(name) & mask;; i = (i + 1) & mask) {
        int32_t slot = table->slots[i];
        if (slot == 0) return -1;
        if (strcmp(table->macros[slot - 1].name->text, name) == 0) return slot - 1;
    }
}

static void place_in_slots(int32_t *slots, size_t slot_count, const char *name, int32_t index)
{
    size_t mask = slot_count - 1;
    size_t i = sdl_hash_name(name) & mask;
    while (slots[i] != 0) i = (i + 1) & mask;
    slots[i] = index + 1;
}

hr_status sdl_macros_add(sdl_macro_table *table, const sdl_macro *macro)
{
    if (table->count == table->capacity) {
        if (table->capacity > INT32_MAX / 4) return HR_ERROR_OUT_OF_MEMORY;
        int32_t capacity = table->capacity ? 2 * table->capacity : 16;
        sdl_macro *grown = realloc(table->macros, (size_t)capacity * sizeof *grown);
        if (!grown) return HR_ERROR_OUT_OF_MEMORY;
        table->macros = grown;
        table->capacity = capacity;
    }
    /* Keep the index at most half full so probes stay short. */
    if (2 * ((size_t)table->count + 1) > table->slot_count) {
        size_t slot_count = table->slot_count ? 2 * table->slot_count : 32;
        int32_t *slots = calloc(slot_count, sizeof *slots);
        if (!slots) return HR_ERROR_OUT_OF_MEMORY;
        for (int32_t i = 0; i < table->count; i++)
            place_in_slots(slots, slot_count, table->macros[i].name->text, i);
        free(table->slots);
        table->slots = slots;
        table->slot_count = slot_count;
    }
    table->macros[table->count] = *macro;
    place_in_slots(table->slots, table->slot_count, macro->name->text, table->count);
    table->count++;
    return HR_OK;
}

/* Read the name after `def` / `use` and check its spelling. */
static hr_status read_name(sdl_source *src, sdl_located keyword, sdl_located *name)
{
    hr_status st = sdl_source_next(src, name);
    if (st) return st;
    if (name->token->kind == SDL_TOKEN_WORD && sdl_is_macro_name(name->token->text)) return HR_OK;
    char found[64];
    return sdl_error(src, HR_ERROR_SDL, *name,
                     "expected a macro name after '%s' (a letter, then letters, digits, '.' or "
                     "'_'), found %s",
                     keyword.token->text, sdl_describe(name->token, found, sizeof found));
}

hr_status sdl_macro_define(sdl_source *src, sdl_located keyword)
{
    /* A body ends at the first '}', so a def inside a body could never be
     * complete there; definitions belong to the file's own text. */
    if (sdl_source_in_macro(keyword))
        return sdl_error(src, HR_ERROR_SDL, keyword,
                         "'def' inside a macro body: definitions cannot nest (a body ends at "
                         "its first '}')");
    sdl_located name, open, t;
    hr_status st = read_name(src, keyword, &name);
    if (st) return st;
    int32_t earlier = sdl_macros_find(&src->macros, name.token->text);
    if (earlier >= 0) {
        const sdl_token *first = src->macros.macros[earlier].name;
        return sdl_error(src, HR_ERROR_SDL, name,
                         "macro '%s' is already defined (at %s:%d:%d); a name can be defined "
                         "only once",
                         name.token->text, src->file, (int)first->line, (int)first->column);
    }
    if ((st = sdl_source_next(src, &open))) return st;
    if (open.token->kind != SDL_TOKEN_OPEN) {
        char found[64];
        return sdl_error(src, HR_ERROR_SDL, open, "expected '{' after 'def %s', found %s",
                         name.token->text, sdl_describe(open.token, found, sizeof found));
    }
    /* The body is read from the file's frame (no macro is active here), so
     * its tokens are consecutive in the file's list. */
    sdl_macro macro = {name.token, open.token + 1, 0};
    for (;;) {
        if ((st = sdl_source_next(src, &t))) return st;
        if (t.token->kind == SDL_TOKEN_CLOSE) break;
        if (t.token->kind == SDL_TOKEN_END)
            return sdl_error(src, HR_ERROR_SDL, keyword,
                             "unterminated 'def %s': no '}' closes the body opened at %s:%d:%d",
                             name.token->text, src->file, (int)open.token->line,
                             (int)open.token->column);
        if (t.token->kind == SDL_TOKEN_OPEN)
            return sdl_error(src, HR_ERROR_SDL, t,
                             "'{' inside the body of macro '%s': a body ends at its first '}', "
                             "so definitions cannot nest",
                             name.token->text);
        macro.body_count++;
    }
    if (sdl_macros_add(&src->macros, &macro) != HR_OK)
        return hri_error(src->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory storing macro '%s'",
                        name.token->text);
    return HR_OK;
}

hr_status sdl_macro_use(sdl_source *src, sdl_located keyword)
{
    sdl_located name;
    hr_status st = read_name(src, keyword, &name);
    if (st) return st;
    /* Looked up now, when used: a macro may use one defined after it, as
     * long as that definition comes before this use is expanded. */
    int32_t macro = sdl_macros_find(&src->macros, name.token->text);
    if (macro < 0)
        return sdl_error(src, HR_ERROR_SDL, name,
                         "unknown macro '%s' after 'use' (no 'def %s' before this point)",
                         name.token->text, name.token->text);
    return sdl_source_expand(src, macro, keyword, name);
}
