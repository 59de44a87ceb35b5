#include "csg_combine.h"

#include <math.h>

int csg_inside(int32_t op, int a_inside, int b_inside)
{
    switch (op) {
    case CSG_UNION: return a_inside || b_inside;
    case CSG_INTERSECTION: return a_inside && b_inside;
    default: return a_inside && !b_inside;
    }
}

/* The same place within the two hits' error bounds (see csg_combine.h). */
static int coincident(const hr_hit *p, const hr_hit *q)
{
    if (p->t == q->t) return 1;
    const double tol = p->error + q->error;
    return fabs(p->point.x - q->point.x) <= tol && fabs(p->point.y - q->point.y) <= tol &&
           fabs(p->point.z - q->point.z) <= tol;
}

/* A walk over one operand's hits. */
typedef struct cursor {
    const hr_hit *hits;
    int32_t count, next;
    int inside;
    const hr_hit *last; /* its last hit in the current group, NULL if none */
} cursor;

static cursor cursor_start(const csg_operand *operand)
{
    cursor c = {operand->hits, operand->count, 0, operand->inside != 0, NULL};
    return c;
}

/* The operand whose next hit comes first (a on a tie), NULL when both are done. */
static cursor *earlier(cursor *a, cursor *b)
{
    if (a->next < a->count && (b->next >= b->count || a->hits[a->next].t <= b->hits[b->next].t))
        return a;
    return b->next < b->count ? b : NULL;
}

int32_t csg_combine(int32_t op, const csg_operand *a_operand, const csg_operand *b_operand,
                    double tmin, double tmax, int32_t limit, hr_hit *out)
{
    cursor a = cursor_start(a_operand), b = cursor_start(b_operand);
    int inside = csg_inside(op, a.inside, b.inside);
    int32_t written = 0;
    cursor *c;
    while (written < limit && (c = earlier(&a, &b)) != NULL) {
        /* One group: hits chained by coincidence, in order of t. */
        const int a_before = a.inside;
        const hr_hit *previous = NULL;
        a.last = b.last = NULL;
        while (c != NULL) {
            const hr_hit *h = &c->hits[c->next];
            if (previous && !coincident(previous, h)) break;
            c->inside = h->entering != 0;
            c->last = h;
            c->next++;
            previous = h;
            c = earlier(&a, &b);
        }
        const int now = csg_inside(op, a.inside, b.inside);
        if (now == inside) continue;
        inside = now;
        /* The result changed, so some operand did (b when a did not): it
         * speaks for the group. */
        const int from_a = a.inside != a_before;
        const hr_hit *chosen = from_a ? a.last : b.last;
        if (!(chosen->t < tmax)) break; /* every later hit is further still */
        if (!(chosen->t > tmin)) continue;
        hr_hit h = *chosen;
        h.entering = now;
        if (!from_a && op == CSG_DIFFERENCE) {
            h.normal.x = -h.normal.x;
            h.normal.y = -h.normal.y;
            h.normal.z = -h.normal.z;
        }
        out[written++] = h;
    }
    return written;
}
