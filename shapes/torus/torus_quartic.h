/* The torus's ray equation and its three root solvers.
 *
 * Kept apart from the module (torus.c) so that bench/programs/torus_solvers.c can time
 * and check the solvers on their own. Everything here is reentrant and works
 * on the caller's stack.
 *
 * The torus: ring radius 1 in the xy-plane about z, tube radius r (0 < r < 1).
 * Its implicit function, outside positive,
 *   f(p) = (|p|^2 + 1 - r^2)^2 - 4 (x^2 + y^2)
 * is rewritten (expand the square around |p|^2 - 1 - r^2) as
 *   f(p) = G^2 + 4 (z^2 - r^2),   G = |p|^2 - 1 - r^2,
 * whose terms are both small near the tube (on the surface G = 2 r cos(phi),
 * z = r sin(phi)), so it keeps its relative accuracy for thin tubes where the
 * textbook form subtracts two numbers near 4.
 *
 * The ray frame (see torus_frame_make): the direction is scaled by an exact
 * power of two and the origin is moved to the point of the line nearest the
 * torus's centre, with one rounding per coordinate (an FMA), so that a ray
 * from 1e6 away meets a quartic whose coefficients are O(1) and whose roots u
 * are O(1); t is then t_shift + u * scale, computed once at the end. */
#ifndef HITRAY_TORUS_QUARTIC_H
#define HITRAY_TORUS_QUARTIC_H

#include <hitray/common.h>

/* The solvers, in order of cost (the names are the `solver` parameter's). */
#define TORUS_SOLVER_FERRARI 0        /* closed form */
#define TORUS_SOLVER_FERRARI_NEWTON 1 /* closed form, each root polished by Newton */
#define TORUS_SOLVER_BRACKETING 2     /* derivative bracketing: misses no root */
#define TORUS_SOLVER_COUNT 3
#define TORUS_SOLVER_DEFAULT TORUS_SOLVER_BRACKETING

/* The name of a solver ("ferrari", ...), or NULL for an unknown number. */
const char *torus_solver_name(int solver);
/* The solver of a name, or -1. */
int torus_solver_find(const char *name);

typedef struct torus_geometry {
    double r;      /* tube radius */
    double r_high; /* r^2 = r_high + r_low exactly (error-free product) */
    double r_low;
} torus_geometry;

void torus_geometry_make(double r, torus_geometry *out);

/* At most four crossings, sorted by t; entering alternates for a full list.
 * A tangent (a double root the solver recognises) is two crossings at the same
 * t: in and out (touching from outside) or out and in (from inside). */
typedef struct torus_roots {
    int count;
    double t[4];
    int entering[4];
} torus_roots;

/* Every crossing of the line with the torus in the open interval
 * (tmin, tmax); with `first_only`, at most the nearest one (the bracketing
 * solver then stops searching once it has it). Returns out->count. */
int torus_solve(const torus_geometry *g, int solver, const hr_ray *ray, double tmin, double tmax,
                int first_only, torus_roots *out);

#endif
