/* SDL's makePixmap N FILE (Hill): read an image and make it pixmap N of
 * the scene, for objects whose material has `texture N`. A relative FILE is
 * found beside the scene file, as mesh files are. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/errors.h"
#include "sdl/sdl_diag.h"
#include "sdl/sdl_reader.h"
#include "util/strutil.h"

hr_status sdl_cmd_make_pixmap(sdl_reader *r, sdl_located keyword)
{
    int64_t index;
    hr_status st = sdl_read_whole(r, keyword, 1.0, (double)INT32_MAX, &index);
    if (st) return st;
    sdl_located file;
    if ((st = sdl_source_next(r->src, &file))) return st;
    if (file.token->kind != SDL_TOKEN_WORD) {
        char found[64];
        return sdl_error(r->src, HR_ERROR_SDL, file, "expected a file name after 'makePixmap %lld', found %s",
                         (long long)index, sdl_describe(file.token, found, sizeof found));
    }
    const char *name = file.token->text;
    const int relative = name[0] != '/' && r->base_dir && r->base_dir[0];
    char *path = relative ? hri_path_join(r->base_dir, name) : hri_strdup(name);
    if (!path) return hri_error(r->ctx, HR_ERROR_OUT_OF_MEMORY, "out of memory");
    hr_image *image = NULL;
    st = hr_image_read(r->ctx, path, &image);
    if (st == HR_OK) {
        st = hr_scene_set_pixmap(r->scene, (int32_t)index, image);
        hr_image_destroy(image);
    }
    if (st == HR_OK) st = hr_scene_note_file(r->scene, path);
    free(path);
    if (st) return sdl_error(r->src, st, file, "makePixmap %lld: %s", (long long)index,
                             hr_context_last_error(r->ctx));
    return HR_OK;
}
