/* The grid and the heap of ear clipping (nff_ear_index.h). */
#include "nff/nff_ear_index.h"

#include <math.h>
#include <stdlib.h>

int ear_grid_build(ear_grid *g, const ear_pt *p, const size_t *which, size_t m)
{
    g->first = g->items = NULL;
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (size_t k = 0; k < m; k++) {
        const ear_pt q = p[which[k]];
        x0 = fmin(x0, q.x), y0 = fmin(y0, q.y), x1 = fmax(x1, q.x), y1 = fmax(y1, q.y);
    }
    const size_t side = m ? (size_t)sqrt((double)m) + 1 : 1;
    g->nx = g->ny = side;
    g->x0 = m ? x0 : 0.0, g->y0 = m ? y0 : 0.0;
    /* A box of no width has one column: a cell of any width holds it. */
    g->cell_x = m && x1 > x0 ? (x1 - x0) / (double)side : 1.0;
    g->cell_y = m && y1 > y0 ? (y1 - y0) / (double)side : 1.0;
    g->first = calloc(side * side + 1, sizeof *g->first);
    g->items = malloc((m ? m : 1) * sizeof *g->items);
    if (!g->first || !g->items) {
        ear_grid_free(g);
        return 0;
    }
    size_t cx, cy, cx1, cy1;
    for (size_t k = 0; k < m; k++) {
        const ear_pt q = p[which[k]];
        ear_grid_range(g, q, q, &cx, &cy, &cx1, &cy1);
        g->first[cy * side + cx + 1]++;
    }
    for (size_t c = 0; c < side * side; c++) g->first[c + 1] += g->first[c];
    /* Filled by counting back down from each cell's end. */
    for (size_t k = m; k-- > 0;) {
        const ear_pt q = p[which[k]];
        ear_grid_range(g, q, q, &cx, &cy, &cx1, &cy1);
        g->items[--g->first[cy * side + cx + 1]] = which[k];
    }
    /* first[c + 1] now holds cell c's start: shift back by one. */
    for (size_t c = 0; c < side * side; c++) g->first[c] = g->first[c + 1];
    g->first[side * side] = m;
    return 1;
}

void ear_grid_free(ear_grid *g)
{
    free(g->first);
    free(g->items);
    g->first = g->items = NULL;
}

static size_t cell_of(double v, double v0, double cell, size_t n)
{
    const double c = floor((v - v0) / cell);
    if (!(c > 0.0)) return 0;
    return c >= (double)(n - 1) ? n - 1 : (size_t)c;
}

void ear_grid_range(const ear_grid *g, ear_pt lo, ear_pt hi, size_t *cx0, size_t *cy0, size_t *cx1,
                    size_t *cy1)
{
    *cx0 = cell_of(lo.x, g->x0, g->cell_x, g->nx), *cx1 = cell_of(hi.x, g->x0, g->cell_x, g->nx);
    *cy0 = cell_of(lo.y, g->y0, g->cell_y, g->ny), *cy1 = cell_of(hi.y, g->y0, g->cell_y, g->ny);
}

int ear_heap_init(ear_heap *h, size_t n, const double *key)
{
    h->heap = malloc((n ? n : 1) * sizeof *h->heap);
    h->pos = malloc((n ? n : 1) * sizeof *h->pos);
    h->count = 0;
    h->key = key;
    if (!h->heap || !h->pos) {
        ear_heap_free(h);
        return 0;
    }
    for (size_t i = 0; i < n; i++) h->pos[i] = EAR_HEAP_NONE;
    return 1;
}

void ear_heap_free(ear_heap *h)
{
    free(h->heap);
    free(h->pos);
    h->heap = h->pos = NULL;
}

/* Ties go to the lower corner number, so the order is the same on every
 * machine. */
static int above(const ear_heap *h, size_t a, size_t b)
{
    const double ka = h->key[a], kb = h->key[b];
    return ka > kb || (ka == kb && a < b);
}

static void place(ear_heap *h, size_t at, size_t i)
{
    h->heap[at] = i;
    h->pos[i] = at;
}

static void sift(ear_heap *h, size_t at)
{
    const size_t i = h->heap[at];
    while (at > 0 && above(h, i, h->heap[(at - 1) / 2])) {
        place(h, at, h->heap[(at - 1) / 2]);
        at = (at - 1) / 2;
    }
    for (;;) {
        size_t child = 2 * at + 1;
        if (child >= h->count) break;
        if (child + 1 < h->count && above(h, h->heap[child + 1], h->heap[child])) child++;
        if (!above(h, h->heap[child], i)) break;
        place(h, at, h->heap[child]);
        at = child;
    }
    place(h, at, i);
}

void ear_heap_update(ear_heap *h, size_t i)
{
    if (h->pos[i] == EAR_HEAP_NONE) place(h, h->count++, i);
    sift(h, h->pos[i]);
}

void ear_heap_remove(ear_heap *h, size_t i)
{
    const size_t at = h->pos[i];
    if (at == EAR_HEAP_NONE) return;
    h->pos[i] = EAR_HEAP_NONE;
    const size_t last = h->heap[--h->count];
    if (at == h->count) return;
    place(h, at, last);
    sift(h, at);
}

size_t ear_heap_top(const ear_heap *h) { return h->count ? h->heap[0] : EAR_HEAP_NONE; }
