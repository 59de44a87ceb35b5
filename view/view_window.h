/* The window (view_window.c): the one part of the viewer, with the event
 * loop in view_main.c, that knows SDL. */
#ifndef HITRAY_VIEW_WINDOW_H
#define HITRAY_VIEW_WINDOW_H

#include <SDL.h>

#include "view.h"

typedef struct view_window {
    SDL_Window *window;
    SDL_Renderer *renderer;
    SDL_Texture *texture;
    int32_t width, height; /* the image's, which the texture has */
} view_window;

/* SDL's video must be initialised. 0 on success; otherwise the error is
 * reported (one line) and nothing is left open. */
int view_window_open(view_window *w, int32_t width, int32_t height, const char *title);
/* Put the rectangle `changed` of `pixels` (the image's size, 8-bit sRGB
 * RGB rows of 3 x width bytes) into the texture and draw the window. */
void view_window_update(view_window *w, const uint8_t *pixels, const view_rect *changed);
/* Draw what is shown again (after an expose or a resize). */
void view_window_redraw(view_window *w);
void view_window_title(view_window *w, const char *title);
void view_window_close(view_window *w);

#endif
