/* What makes ear clipping of a large polygon fast (nff_polygons.c): a grid
 * of the corners that may lie inside an ear, so an ear's test looks only
 * at the cells its triangle covers, and a heap of the ears by quality, so
 * the best is found without a pass over the polygon. */
#ifndef HITRAY_LIB_NFF_EAR_INDEX_H
#define HITRAY_LIB_NFF_EAR_INDEX_H

#include <stddef.h>

typedef struct ear_pt {
    double x, y;
} ear_pt;

/* The corners given, bucketed in a grid of about one corner a cell. */
typedef struct ear_grid {
    double x0, y0, cell_x, cell_y;
    size_t nx, ny;
    size_t *first; /* nx * ny + 1 offsets into `items` */
    size_t *items;
} ear_grid;

/* A grid of the n corners of p listed in `which` (count m); 0 when out of
 * memory. ear_grid_free frees what it holds. */
int ear_grid_build(ear_grid *g, const ear_pt *p, const size_t *which, size_t m);
void ear_grid_free(ear_grid *g);
/* The cells of the box [lo, hi] as a range of cell coordinates. */
void ear_grid_range(const ear_grid *g, ear_pt lo, ear_pt hi, size_t *cx0, size_t *cy0, size_t *cx1,
                    size_t *cy1);

/* A max-heap of corners by key, each corner at most once, its key
 * changeable in place. */
typedef struct ear_heap {
    size_t *heap, *pos; /* pos[i]: where corner i is, or EAR_HEAP_NONE */
    size_t count;
    const double *key;
} ear_heap;
#define EAR_HEAP_NONE ((size_t)-1)

int ear_heap_init(ear_heap *h, size_t n, const double *key);
void ear_heap_free(ear_heap *h);
/* After key[i] changed (or to add i). */
void ear_heap_update(ear_heap *h, size_t i);
void ear_heap_remove(ear_heap *h, size_t i);
size_t ear_heap_top(const ear_heap *h);

#endif
