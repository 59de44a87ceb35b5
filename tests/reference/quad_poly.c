#include "quad_poly.h"

#include <quadmath.h>

#define MAX_DEGREE 4

typedef struct poly {
    int degree;
    quad c[MAX_DEGREE + 1];
} poly;

static quad qabs(quad x)
{
    return x < 0 ? -x : x;
}

quad quad_poly_eval(const quad *c, int degree, quad x)
{
    quad v = c[degree];
    for (int i = degree - 1; i >= 0; i--) v = v * x + c[i];
    return v;
}

/* The remainder of a / b, negated (the next Sturm polynomial). Coefficients
 * below 1e-28 of the largest in a count as zero: the chain's rounding, far
 * below anything a double ray can express. */
static poly negated_remainder(const poly *a, const poly *b)
{
    poly r = *a;
    quad scale = 0;
    for (int i = 0; i <= a->degree; i++)
        if (qabs(a->c[i]) > scale) scale = qabs(a->c[i]);
    for (int k = a->degree - b->degree; k >= 0; k--) {
        const quad factor = r.c[k + b->degree] / b->c[b->degree];
        for (int i = 0; i <= b->degree; i++) r.c[k + i] -= factor * b->c[i];
        r.c[k + b->degree] = 0;
    }
    r.degree = b->degree - 1;
    while (r.degree > 0 && qabs(r.c[r.degree]) <= 1e-28Q * scale) r.degree--;
    for (int i = 0; i <= r.degree; i++) r.c[i] = -r.c[i];
    if (r.degree == 0 && qabs(r.c[0]) <= 1e-28Q * scale) r.degree = -1; /* zero */
    return r;
}

typedef struct sturm {
    int count;
    poly p[MAX_DEGREE + 2];
} sturm;

static void sturm_make(const quad *c, int degree, sturm *s)
{
    s->p[0].degree = degree;
    for (int i = 0; i <= degree; i++) s->p[0].c[i] = c[i];
    s->p[1].degree = degree - 1;
    for (int i = 1; i <= degree; i++) s->p[1].c[i - 1] = i * c[i];
    s->count = 2;
    while (s->count < MAX_DEGREE + 2 && s->p[s->count - 1].degree > 0) {
        poly r = negated_remainder(&s->p[s->count - 2], &s->p[s->count - 1]);
        if (r.degree < 0) break;
        s->p[s->count++] = r;
    }
}

/* Sign changes of the chain at x. */
static int sturm_changes(const sturm *s, quad x)
{
    int changes = 0, last = 0;
    for (int i = 0; i < s->count; i++) {
        const quad v = quad_poly_eval(s->p[i].c, s->p[i].degree, x);
        const int sign = (v > 0) - (v < 0);
        if (sign == 0) continue;
        if (last != 0 && sign != last) changes++;
        last = sign;
    }
    return changes;
}

/* The root of p in (a, b] where p(a), p(b) have opposite signs: bisection
 * down to 1e-12 of the interval, then Newton steps kept inside the bracket. */
static quad refine(const quad *c, int degree, quad a, quad b)
{
    quad fa = quad_poly_eval(c, degree, a);
    const quad width = b - a;
    for (int i = 0; i < 200 && b - a > 1e-12Q * width; i++) {
        const quad m = (a + b) / 2;
        const quad fm = quad_poly_eval(c, degree, m);
        if (fm == 0) return m;
        if ((fm > 0) == (fa > 0)) a = m, fa = fm;
        else b = m;
    }
    quad x = (a + b) / 2;
    for (int i = 0; i < 20; i++) {
        quad d = c[degree] * degree;
        for (int k = degree - 1; k >= 1; k--) d = d * x + c[k] * k;
        const quad f = quad_poly_eval(c, degree, x);
        if (f == 0 || d == 0) break;
        const quad next = x - f / d;
        if (!(next >= a && next <= b)) break;
        if (qabs(next - x) <= 1e-33Q * (qabs(x) + width)) {
            x = next;
            break;
        }
        x = next;
    }
    return x;
}

int quad_poly_roots(const quad *c, int degree, quad lo, quad hi, quad *roots, int *even)
{
    sturm s;
    sturm_make(c, degree, &s);
    struct {
        quad a, b;
        int na, nb;
    } stack[256];
    int top = 0, found = 0;
    stack[top].a = lo, stack[top].b = hi;
    stack[top].na = sturm_changes(&s, lo), stack[top].nb = sturm_changes(&s, hi);
    top++;
    /* Intervals are popped right half first pushed last, so roots come out
     * in increasing order. */
    while (top > 0 && found < degree) {
        top--;
        const quad a = stack[top].a, b = stack[top].b;
        const int na = stack[top].na, nb = stack[top].nb;
        const int inside = na - nb;
        if (inside <= 0) continue;
        const quad fa = quad_poly_eval(c, degree, a), fb = quad_poly_eval(c, degree, b);
        const int tiny = b - a <= 1e-30Q * (qabs(a) + qabs(b) + 1e-30Q);
        if (inside == 1 && fb == 0) {
            roots[found] = b;
            if (even) even[found] = 0;
            found++;
            continue;
        }
        if (inside == 1 && (fa > 0) != (fb > 0) && fa != 0) {
            roots[found] = refine(c, degree, a, b);
            if (even) even[found] = 0;
            found++;
            continue;
        }
        if (tiny || top + 2 > 256) {
            for (int k = 0; k < inside && found < degree; k++) {
                roots[found] = (a + b) / 2;
                if (even) even[found] = 1;
                found++;
            }
            continue;
        }
        const quad m = (a + b) / 2;
        const int nm = sturm_changes(&s, m);
        stack[top].a = m, stack[top].b = b, stack[top].na = nm, stack[top].nb = nb;
        top++;
        stack[top].a = a, stack[top].b = m, stack[top].na = na, stack[top].nb = nm;
        top++;
    }
    return found;
}
