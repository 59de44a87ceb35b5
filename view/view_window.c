/* The window (view_window.h): an SDL renderer with one streaming texture
 * the size of the image, scaled to the window with the aspect kept. */
#include <math.h>
#include <string.h>

#include "cli.h"
#include "view_window.h"

/* The window's first size: the image's, shrunk to fit the screen where it
 * is larger, or a small image shown at a whole multiple (up to 4) of its
 * size, so that 160x120 is not a postage stamp. The texture keeps the
 * image's size either way; the window may be resized. */
static void first_size(int32_t width, int32_t height, int *ww, int *wh)
{
    SDL_Rect screen;
    double scale = 1.0;
    if (SDL_GetDisplayUsableBounds(0, &screen) == 0 && screen.w > 0 && screen.h > 0) {
        double fit = fmin((double)screen.w / width, (double)screen.h / height);
        if (fit < 1.0) scale = fit;
        else
            for (int zoom = 4; zoom > 1; zoom--)
                if (zoom * width <= 640 && zoom <= fit) {
                    scale = zoom;
                    break;
                }
    }
    *ww = (int)fmax(1.0, floor(width * scale));
    *wh = (int)fmax(1.0, floor(height * scale));
}

int view_window_open(view_window *w, int32_t width, int32_t height, const char *title)
{
    memset(w, 0, sizeof *w);
    w->width = width, w->height = height;
    int ww, wh;
    first_size(width, height, &ww, &wh);
    w->window = SDL_CreateWindow(title, SDL_WINDOWPOS_UNDEFINED, SDL_WINDOWPOS_UNDEFINED, ww, wh,
                                 SDL_WINDOW_RESIZABLE);
    /* Any renderer will do (a software one where no GPU is, as under Xvfb). */
    if (w->window) w->renderer = SDL_CreateRenderer(w->window, -1, 0);
    if (w->window && !w->renderer) w->renderer = SDL_CreateRenderer(w->window, -1, SDL_RENDERER_SOFTWARE);
    if (w->renderer) {
        SDL_RenderSetLogicalSize(w->renderer, (int)width, (int)height);
        w->texture = SDL_CreateTexture(w->renderer, SDL_PIXELFORMAT_RGB24, SDL_TEXTUREACCESS_STREAMING, (int)width,
                                       (int)height);
    }
    if (!w->texture) {
        cli_error("view: cannot open a %dx%d window: %s", (int)width, (int)height, SDL_GetError());
        view_window_close(w);
        return CLI_EXIT_ERROR;
    }
    view_window_redraw(w);
    return 0;
}

void view_window_update(view_window *w, const uint8_t *pixels, const view_rect *changed)
{
    if (changed->width > 0 && changed->height > 0) {
        SDL_Rect rect = {changed->x, changed->y, changed->width, changed->height};
        size_t pitch = 3 * (size_t)w->width;
        SDL_UpdateTexture(w->texture, &rect, pixels + (size_t)changed->y * pitch + 3 * (size_t)changed->x,
                          (int)pitch);
    }
    view_window_redraw(w);
}

void view_window_redraw(view_window *w)
{
    SDL_SetRenderDrawColor(w->renderer, 0, 0, 0, 255);
    SDL_RenderClear(w->renderer);
    SDL_RenderCopy(w->renderer, w->texture, NULL, NULL);
    SDL_RenderPresent(w->renderer);
}

void view_window_title(view_window *w, const char *title) { SDL_SetWindowTitle(w->window, title); }

void view_window_close(view_window *w)
{
    if (w->texture) SDL_DestroyTexture(w->texture);
    if (w->renderer) SDL_DestroyRenderer(w->renderer);
    if (w->window) SDL_DestroyWindow(w->window);
    memset(w, 0, sizeof *w);
}
