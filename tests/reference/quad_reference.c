#include "quad_reference.h"

#include <math.h>
#include <quadmath.h>
#include <string.h>

#include "quad_poly.h"

ref_shape ref_shape_of(const char *class_name, double s, double t)
{
    ref_shape r = {REF_SPHERE, 0.0, 0.0};
    if (strcmp(class_name, "plane") == 0) r.kind = REF_PLANE;
    else if (strcmp(class_name, "square") == 0) r.kind = REF_SQUARE;
    else if (strcmp(class_name, "cube") == 0) r.kind = REF_CUBE;
    else if (strcmp(class_name, "cylinder") == 0) r.kind = REF_TAPERED, r.s = 1.0;
    else if (strcmp(class_name, "cone") == 0) r.kind = REF_TAPERED, r.s = 0.0;
    else if (strcmp(class_name, "taperedCylinder") == 0) r.kind = REF_TAPERED, r.s = s;
    else if (strcmp(class_name, "taperedTube") == 0) r.kind = REF_TUBE, r.s = s, r.t = t;
    else if (strcmp(class_name, "torus") == 0) r.kind = REF_TORUS, r.s = isnan(s) ? 0.2 : s;
    return r;
}

double ref_to_double(quad q)
{
    return (double)q;
}

typedef struct qvec {
    quad x, y, z;
} qvec;

static qvec qv(hr_vec3 v)
{
    qvec q = {v.x, v.y, v.z};
    return q;
}

static quad qabs(quad x)
{
    return x < 0 ? -x : x;
}

static quad qmin(quad a, quad b)
{
    return a < b ? a : b;
}

static quad qmax(quad a, quad b)
{
    return a > b ? a : b;
}

static quad qdot(qvec a, qvec b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static quad qcomp(qvec v, int axis)
{
    return axis == 0 ? v.x : axis == 1 ? v.y : v.z;
}

static qvec qat(qvec o, qvec d, quad t)
{
    qvec p = {o.x + t * d.x, o.y + t * d.y, o.z + t * d.z};
    return p;
}

/* Collects crossings and the margin while one shape is traced. */
typedef struct collector {
    ref_trace *out;
    qvec o, d;
    quad margin;
} collector;

static void note_margin(collector *c, quad m)
{
    m = qabs(m);
    if (m < c->margin) c->margin = m;
}

/* A candidate crossing at t with outward normal n: kept when `valid`; its
 * distance from the patch boundary (`edge_margin`) and its grazing angle feed
 * the margin whether kept or not. */
static void add_crossing(collector *c, quad t, int surface, qvec n, int valid, quad edge_margin,
                         quad condition)
{
    note_margin(c, edge_margin);
    const quad dn = qdot(c->d, n);
    const quad cosine = dn / (sqrtq(qdot(c->d, c->d)) * sqrtq(qdot(n, n)));
    if (valid) note_margin(c, cosine);
    if (!valid || c->out->count >= 8) return;
    ref_hit *h = &c->out->hits[c->out->count++];
    h->t = t;
    h->surface = surface;
    h->entering = dn < 0;
    h->condition = condition;
}

/* Roots of a t^2 + 2 b t + c (textbook formula, in quad). Returns the count;
 * the margin learns the chord between the roots (or how far from real they
 * are), scaled to a length by |d|. */
static int quadric_roots(collector *col, quad a, quad b, quad c, quad roots[2])
{
    const quad dlen = sqrtq(qdot(col->d, col->d));
    const quad disc = b * b - a * c;
    if (a == 0) {
        if (b == 0) return 0;
        roots[0] = -c / (2 * b);
        return 1;
    }
    if (disc < 0) {
        note_margin(col, -disc / (qabs(a) + dlen * dlen) * 4);
        return 0;
    }
    const quad root = sqrtq(disc);
    roots[0] = (-b - root) / a;
    roots[1] = (-b + root) / a;
    if (roots[0] > roots[1]) {
        quad t = roots[0];
        roots[0] = roots[1];
        roots[1] = t;
    }
    note_margin(col, (roots[1] - roots[0]) * dlen);
    return 2;
}

/* The condition of a quadric root (see ref_hit.condition). */
static quad quadric_condition(collector *col, quad t, quad w_at_t, quad w_sensitivity,
                              quad sqrt_disc)
{
    const qvec p = qat(col->o, col->d, t);
    const quad spread = qabs(p.x) * (qabs(col->o.x) + qabs(t * col->d.x)) +
                        qabs(p.y) * (qabs(col->o.y) + qabs(t * col->d.y)) +
                        qabs(p.z) * (qabs(col->o.z) + qabs(t * col->d.z)) +
                        qabs(w_at_t) * w_sensitivity;
    return qabs(t) + (sqrt_disc > 0 ? spread / sqrt_disc : (quad)INFINITY);
}

static void trace_sphere(collector *col)
{
    const qvec o = col->o, d = col->d;
    const quad a = qdot(d, d), b = qdot(o, d), c = qdot(o, o) - 1;
    quad roots[2];
    const int n = quadric_roots(col, a, b, c, roots);
    if (n != 2) return;
    const quad sqrt_disc = sqrtq(qmax(b * b - a * c, 0));
    for (int i = 0; i < 2; i++) {
        const qvec p = qat(o, d, roots[i]);
        add_crossing(col, roots[i], 0, p, 1, 1, quadric_condition(col, roots[i], 0, 0, sqrt_disc));
    }
}

/* The plane z = h crossed inside |x|, |y| <= half (square) or radius
 * `radius` (disk; an annulus where `hole` > 0); half < 0 and radius < 0:
 * unbounded. */
static void trace_flat_z(collector *col, quad h, int surface, quad normal_z, quad half,
                         quad radius, quad hole)
{
    const qvec o = col->o, d = col->d;
    if (d.z == 0) return;
    const quad t = (h - o.z) / d.z;
    const qvec p = qat(o, d, t);
    int valid = 1;
    quad edge = 1;
    if (half >= 0) {
        valid = qabs(p.x) <= half && qabs(p.y) <= half;
        edge = qmin(qabs(half - qabs(p.x)), qabs(half - qabs(p.y)));
    } else if (radius >= 0) {
        const quad rho = sqrtq(p.x * p.x + p.y * p.y);
        valid = rho <= radius && rho >= hole;
        edge = qmin(qabs(radius - rho), hole > 0 ? qabs(rho - hole) : (quad)INFINITY);
    }
    const qvec n = {0, 0, normal_z};
    add_crossing(col, t, surface, n, valid, edge, qabs(t));
}

static void trace_cube(collector *col)
{
    const qvec o = col->o, d = col->d;
    for (int axis = 0; axis < 3; axis++) {
        const quad da = qcomp(d, axis), oa = qcomp(o, axis);
        if (da == 0) {
            note_margin(col, 1 - qabs(oa)); /* running along a face plane */
            continue;
        }
        for (int side = 0; side < 2; side++) {
            const quad face = side == 0 ? 1 : -1;
            const quad t = (face - oa) / da;
            const qvec p = qat(o, d, t);
            int valid = 1;
            quad edge = 1;
            for (int j = 0; j < 3; j++) {
                if (j == axis) continue;
                const quad pj = qcomp(p, j);
                if (qabs(pj) > 1) valid = 0;
                edge = qmin(edge, qabs(1 - qabs(pj)));
            }
            qvec n = {0, 0, 0};
            if (axis == 0) n.x = face;
            else if (axis == 1) n.y = face;
            else n.z = face;
            add_crossing(col, t, 2 * axis + side, n, valid, edge, qabs(t));
        }
    }
}

/* The wall of radius r0 + (s - 1) z over 0 <= z <= 1, as `surface`; its
 * outward normal reversed when `inward` (the tube's inner wall). */
static void trace_wall(collector *col, double s, quad r0, int surface, int inward)
{
    const qvec o = col->o, d = col->d;
    const quad k = (quad)s - 1;
    const quad w0 = r0 + k * o.z, omega = k * d.z;
    const quad a = d.x * d.x + d.y * d.y - omega * omega;
    const quad b = o.x * d.x + o.y * d.y - w0 * omega;
    const quad c = o.x * o.x + o.y * o.y - w0 * w0;
    quad roots[2];
    const int n = quadric_roots(col, a, b, c, roots);
    const quad sqrt_disc = sqrtq(qmax(b * b - a * c, 0));
    for (int i = 0; i < n; i++) {
        const quad t = roots[i];
        const qvec p = qat(o, d, t);
        const quad w = r0 + k * p.z;
        const int valid = p.z >= 0 && p.z <= 1 && w >= 0;
        const quad sign = inward ? -1 : 1;
        const qvec normal = {sign * p.x, sign * p.y, -sign * k * w};
        const quad edge = qmin(qabs(p.z), qabs(1 - p.z));
        const quad sensitivity = qabs(w0) + qabs(omega * t);
        add_crossing(col, t, surface, normal, valid, edge,
                     quadric_condition(col, t, w, sensitivity, n == 2 ? sqrt_disc : qabs(b)));
    }
}

static void trace_tapered(collector *col, double s)
{
    trace_wall(col, s, 1, 0, 0);
    trace_flat_z(col, 0, 1, -1, -1, 1, 0);
    if (s > 0) trace_flat_z(col, 1, 2, 1, -1, s, 0); /* the cone has no cap: only the apex */
}

static void trace_tube(collector *col, double s, double t)
{
    const quad r0 = 1 - (quad)t;
    trace_wall(col, s, 1, 0, 0);
    trace_wall(col, s, r0, 3, 1);
    trace_flat_z(col, 0, 1, -1, -1, 1, r0);
    trace_flat_z(col, 1, 2, 1, -1, s, (quad)s - t);
}

/* The torus (ring radius 1 about z, tube radius `tube`): the textbook quartic
 * (|p|^2 + 1 - r^2)^2 - 4 (x^2 + y^2) along the line, formed in quad around
 * the point of the line nearest the centre and solved by quad_poly_roots
 * (Sturm sequences). Roots of even multiplicity (tangents) come back as a
 * pair with a zero margin. Near-tangent misses have no root to show it, so
 * the margin also learns, at each critical point of the quartic, the
 * distance-like |f| / |grad f| (near the tube f ~ 8 r delta and
 * |grad f| ~ 8 r, delta the distance to the surface). */
static quad torus_gradient(qvec p, quad r, qvec *n)
{
    const quad G = qdot(p, p) - 1 - r * r;
    n->x = 4 * G * p.x;
    n->y = 4 * G * p.y;
    n->z = 4 * G * p.z + 8 * p.z;
    return G;
}

static void trace_torus(collector *col, double tube)
{
    const quad r = tube;
    const qvec d = col->d;
    const quad a = qdot(d, d);
    const quad tc = -qdot(col->o, d) / a;
    const qvec o = qat(col->o, d, tc);
    const quad b = qdot(o, d), c = qdot(o, o) + 1 - r * r;
    const quad ax = d.x * d.x + d.y * d.y, bx = o.x * d.x + o.y * d.y, cx = o.x * o.x + o.y * o.y;
    const quad poly[5] = {c * c - 4 * cx, 4 * b * c - 8 * bx, 4 * b * b + 2 * a * c - 4 * ax,
                          4 * a * b, a * a};
    const quad reach = (1 + r) * 1.01Q / sqrtq(a) + qabs(b) / a;
    quad roots[4];
    int even[4];
    const int n = quad_poly_roots(poly, 4, -reach, reach, roots, even);
    for (int i = 0; i < n; i++) {
        const quad t = tc + roots[i];
        const qvec p = qat(col->o, d, t);
        qvec grad;
        const quad G = torus_gradient(p, r, &grad);
        const quad slope = qabs(qdot(grad, d));
        const quad spread = qabs(grad.x) * (qabs(col->o.x) + qabs(t * d.x)) +
                            qabs(grad.y) * (qabs(col->o.y) + qabs(t * d.y)) +
                            qabs(grad.z) * (qabs(col->o.z) + qabs(t * d.z)) +
                            qabs(4 * r * (G + 2)) * r;
        const quad condition = qabs(t) + (slope > 0 ? spread / slope : (quad)INFINITY);
        if (even[i]) {
            note_margin(col, 0);
            if (col->out->count + 2 > 8) continue;
            ref_hit *h = &col->out->hits[col->out->count];
            h[0].t = h[1].t = t;
            h[0].surface = h[1].surface = 0;
            h[0].entering = 1, h[1].entering = 0;
            h[0].condition = h[1].condition = condition;
            col->out->count += 2;
            continue;
        }
        add_crossing(col, t, 0, grad, 1, 1, condition);
    }
    const quad dpoly[4] = {poly[1], 2 * poly[2], 3 * poly[3], 4 * poly[4]};
    quad crit[3];
    const int nc = quad_poly_roots(dpoly, 3, -reach, reach, crit, NULL);
    for (int i = 0; i < nc; i++) {
        const qvec p = qat(o, d, crit[i]);
        qvec grad;
        torus_gradient(p, r, &grad);
        const quad length = sqrtq(qdot(grad, grad));
        if (length > 0) note_margin(col, quad_poly_eval(poly, 4, crit[i]) / length);
    }
}

static void sort_hits(ref_trace *out)
{
    for (int i = 1; i < out->count; i++) {
        ref_hit h = out->hits[i];
        int j = i;
        while (j > 0 && out->hits[j - 1].t > h.t) {
            out->hits[j] = out->hits[j - 1];
            j--;
        }
        out->hits[j] = h;
    }
}

static void trace_line(ref_shape shape, qvec origin, qvec dir, ref_trace *out);

void ref_trace_ray(ref_shape shape, hr_ray ray, ref_trace *out)
{
    trace_line(shape, qv(ray.origin), qv(ray.dir), out);
}

void ref_trace_quad_ray(ref_shape shape, const quad origin[3], const quad dir[3], ref_trace *out)
{
    const qvec o = {origin[0], origin[1], origin[2]}, d = {dir[0], dir[1], dir[2]};
    trace_line(shape, o, d, out);
}

static void trace_line(ref_shape shape, qvec origin, qvec dir, ref_trace *out)
{
    memset(out, 0, sizeof *out);
    collector col = {out, origin, dir, (quad)INFINITY};
    switch (shape.kind) {
    case REF_SPHERE: trace_sphere(&col); break;
    case REF_PLANE: trace_flat_z(&col, 0, 0, 1, -1, -1, 0); break;
    case REF_SQUARE: trace_flat_z(&col, 0, 0, 1, 1, -1, 0); break;
    case REF_TUBE: trace_tube(&col, shape.s, shape.t); break;
    case REF_CUBE: trace_cube(&col); break;
    case REF_TORUS: trace_torus(&col, shape.s); break;
    default: trace_tapered(&col, shape.s); break;
    }
    sort_hits(out);
    const quad dlen = sqrtq(qdot(col.d, col.d));
    for (int i = 1; i < out->count; i++)
        note_margin(&col, (out->hits[i].t - out->hits[i - 1].t) * dlen);
    out->margin = (double)col.margin;
}

/* Distance from (rho, z) to the segment from (r0, 0) to (r0 + s - 1, 1) in a
 * meridian half-plane: the distance to the tapered wall (a surface of
 * revolution). */
static quad wall_distance(quad rho, quad z, quad s, quad r0)
{
    const quad ax = r0, az = 0, bx = r0 + s - 1, bz = 1;
    const quad vx = bx - ax, vz = bz - az;
    quad f = ((rho - ax) * vx + (z - az) * vz) / (vx * vx + vz * vz);
    f = qmin(qmax(f, 0), 1);
    const quad dx = rho - (ax + f * vx), dz = z - (az + f * vz);
    return sqrtq(dx * dx + dz * dz);
}

static quad outside(quad value, quad limit)
{
    return qmax(qabs(value) - limit, 0);
}

double ref_surface_distance(ref_shape shape, int surface, hr_vec3 point)
{
    const qvec p = qv(point);
    switch (shape.kind) {
    case REF_SPHERE: return (double)qabs(sqrtq(qdot(p, p)) - 1);
    case REF_PLANE: return (double)qabs(p.z);
    case REF_SQUARE: {
        const quad ex = outside(p.x, 1), ey = outside(p.y, 1);
        return (double)sqrtq(p.z * p.z + ex * ex + ey * ey);
    }
    case REF_CUBE: {
        const int axis = surface / 2;
        const quad face = surface % 2 == 0 ? 1 : -1;
        quad sum = 0;
        for (int j = 0; j < 3; j++) {
            const quad e = j == axis ? qcomp(p, j) - face : outside(qcomp(p, j), 1);
            sum += e * e;
        }
        return (double)sqrtq(sum);
    }
    case REF_TORUS: {
        const quad rho = sqrtq(p.x * p.x + p.y * p.y);
        return (double)qabs(sqrtq((rho - 1) * (rho - 1) + p.z * p.z) - (quad)shape.s);
    }
    default: {
        const quad rho = sqrtq(p.x * p.x + p.y * p.y);
        const quad r0 = shape.kind == REF_TUBE ? 1 - (quad)shape.t : 0;
        if (surface == 0) return (double)wall_distance(rho, p.z, (quad)shape.s, 1);
        if (surface == 3) return (double)wall_distance(rho, p.z, (quad)shape.s, r0);
        const quad h = surface == 1 ? 0 : 1, radius = surface == 1 ? 1 : (quad)shape.s;
        const quad hole = shape.kind != REF_TUBE ? 0 : surface == 1 ? r0 : qmax(r0 + (quad)shape.s - 1, 0);
        const quad e = qmax(rho - radius, 0) + qmax(hole - rho, 0);
        return (double)sqrtq((p.z - h) * (p.z - h) + e * e);
    }
    }
}
