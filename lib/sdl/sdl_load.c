/* The public SDL entry points (include/hitray/sdl.h): read the text, cut it
 * into tokens, run the reader over a new scene, frame a camera if the file
 * set none. On any error the partial scene is destroyed and out->scene is
 * NULL. */
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "util/strutil.h"
#include "sdl/load_result.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_lexer.h"
#include "sdl/sdl_reader.h"
#include "sdl/sdl_source.h"
#include "sdl/text_file.h"

static hr_status read_scene(hr_context *ctx, const sdl_token_list *tokens, const char *name,
                            const char *base_dir, const char *file, hr_sdl_result *result)
{
    hr_scene *scene = NULL;
    sdl_source src;
    sdl_reader reader;
    memset(&src, 0, sizeof src);
    memset(&reader, 0, sizeof reader);
    hr_status st = hr_scene_create(ctx, &scene);
    if (!st && file) st = hr_scene_note_file(scene, file); /* the first file it was built from */
    if (!st) st = sdl_source_init(&src, ctx, name, tokens);
    if (!st) st = sdl_reader_init(&reader, ctx, scene, &src, base_dir);
    if (!st) st = sdl_reader_run(&reader);
    if (!st) {
        result->scene = scene;
        result->has_camera = reader.has_camera;
        if (reader.has_camera) {
            result->camera = reader.camera;
        } else {
            hr_camera_default(&result->camera);
            st = hr_scene_frame_camera(scene, &result->camera);
            if (st) {
                /* Framing happens after the last command: the message
                 * names the object, the place is the end of the file. */
                sdl_located end;
                sdl_source_next(&src, &end);
                st = sdl_error(&src, st, end, "%s", hr_context_last_error(ctx));
            }
        }
    }
    sdl_reader_release(&reader);
    sdl_source_release(&src);
    if (st) {
        hr_scene_destroy(scene);
        hri_load_result_empty(result);
    }
    return st;
}

/* `file`: the path the text was read from, NULL for text given. */
static hr_status load_text(hr_context *ctx, const char *text, size_t length, const char *name,
                           const char *base_dir, const char *file, hr_sdl_result *out)
{
    hr_sdl_result result;
    hri_load_result_empty(&result);
    sdl_token_list tokens;
    int32_t bad_line = 0, bad_column = 0;
    hr_status st = sdl_lex(text, length, &tokens, &bad_line, &bad_column);
    if (st == HR_ERROR_SDL)
        hri_error_at(ctx, st, name, bad_line, bad_column,
                    "%s:%d:%d: unexpected NUL byte (is this a text file?)", name, (int)bad_line,
                    (int)bad_column);
    else if (st)
        hri_error(ctx, st, "out of memory reading '%s'", name);
    else
        st = read_scene(ctx, &tokens, name, base_dir, file, &result);
    sdl_token_list_release(&tokens);
    hri_load_result_give(out, &result);
    return st;
}

HR_API hr_status hr_sdl_load_string(hr_context *ctx, const char *text, const char *name,
                                    const char *base_dir, hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "SDL");
    if (st) return st;
    if (!text) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_sdl_load_string: NULL text");
    return load_text(ctx, text, strlen(text), name ? name : "<string>", base_dir, NULL, out);
}

HR_API hr_status hr_sdl_load_file(hr_context *ctx, const char *path, hr_sdl_result *out)
{
    hr_status st = hri_load_result_begin(ctx, out, "SDL");
    if (st) return st;
    if (!path) return hri_error(ctx, HR_ERROR_INVALID_ARGUMENT, "hr_sdl_load_file: NULL path");
    char *text;
    size_t length;
    if ((st = hri_scene_file_read(ctx, path, "scene file", &text, &length))) return st;
    char *base_dir = hri_path_dirname(path);
    if (!base_dir)
        st = hri_error(ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    else
        st = load_text(ctx, text, length, path, base_dir, path, out);
    free(base_dir);
    free(text);
    return st;
}
