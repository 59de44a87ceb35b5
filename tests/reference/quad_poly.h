/* Real roots of a polynomial of degree up to 4 in quad precision, for the
 * torus reference. Independent of the module's solvers on purpose: the roots
 * are isolated by counting them with a Sturm sequence (so none is missed
 * however close two are), then refined by bisection and Newton steps in
 * __float128. */
#ifndef HR_TEST_QUAD_POLY_H
#define HR_TEST_QUAD_POLY_H

typedef __float128 quad;

/* p(x) = sum c[i] x^i, i = 0..degree. */
quad quad_poly_eval(const quad *c, int degree, quad x);

/* The distinct real roots of p in (lo, hi], sorted, at most `degree` of
 * them. A root that Sturm's count finds but p does not change sign across
 * (a root of even multiplicity) is located by the count alone and flagged in
 * `even[i]` (may be NULL). The caller must pass a p with c[degree] != 0.
 * Returns the number of roots written. */
int quad_poly_roots(const quad *c, int degree, quad lo, quad hi, quad *roots, int *even);

#endif
