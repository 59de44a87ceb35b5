/* The regular solids of Hill's chapter 6, built in code: tetrahedron,
 * octahedron, dodecahedron and icosahedron, and the buckyball (the
 * truncated icosahedron, which Hill's reader loaded from bucky.3vn),
 * centred at the origin with their vertices on the unit sphere (the generic
 * sphere's size).
 *
 * Only the vertices are written down (the usual coordinates, from the cube
 * and the golden ratio); the faces are found from them: a face is the set
 * of vertices on a plane through three of them that has every vertex on
 * its inner side. Its corners are then ordered by angle about the face's
 * centre, counter-clockwise seen from outside, and the polygon is fanned
 * like any other (a pentagon gives three triangles, a hexagon four). */
#include <math.h>
#include <string.h>

#include "mesh.h"

#define MAX_VERTICES 60
/* Vertices of one solid closer than this to a face plane lie on it: the
 * coordinates are accurate to a few ulps, and distinct planes of these
 * solids are far apart. */
#define ON_PLANE 1e-9

typedef struct vec {
    double x, y, z;
} vec;

static vec sub(vec a, vec b) { return (vec){a.x - b.x, a.y - b.y, a.z - b.z}; }
static double dot(vec a, vec b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static vec cross(vec a, vec b)
{
    return (vec){a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/* Every sign combination of (a, b, c) with a cyclic shift `shift` of the
 * axes; zero components give one sign only. */
static int add_signed(vec *out, int n, double a, double b, double c, int shift)
{
    for (int s = 0; s < 8; s++) {
        if (((s & 1) && a == 0) || ((s & 2) && b == 0) || ((s & 4) && c == 0)) continue;
        double v[3] = {(s & 1) ? -a : a, (s & 2) ? -b : b, (s & 4) ? -c : c};
        out[n++] = (vec){v[(3 - shift) % 3], v[(4 - shift) % 3], v[(5 - shift) % 3]};
    }
    return n;
}

static int solid_vertices(int solid, vec *v)
{
    const double phi = (1.0 + sqrt(5.0)) / 2.0;
    int n = 0;
    switch (solid) {
    case MESH_TETRAHEDRON: /* alternate corners of the cube */
        v[n++] = (vec){1, 1, 1};
        v[n++] = (vec){1, -1, -1};
        v[n++] = (vec){-1, 1, -1};
        v[n++] = (vec){-1, -1, 1};
        break;
    case MESH_OCTAHEDRON:
        for (int shift = 0; shift < 3; shift++) n = add_signed(v, n, 1, 0, 0, shift);
        break;
    case MESH_DODECAHEDRON:
        n = add_signed(v, n, 1, 1, 1, 0);
        for (int shift = 0; shift < 3; shift++) n = add_signed(v, n, 0, 1 / phi, phi, shift);
        break;
    case MESH_ICOSAHEDRON:
        for (int shift = 0; shift < 3; shift++) n = add_signed(v, n, 0, 1, phi, shift);
        break;
    case MESH_BUCKYBALL: /* the icosahedron's edges cut at a third: edge 2 here */
        for (int shift = 0; shift < 3; shift++) {
            n = add_signed(v, n, 0, 1, 3 * phi, shift);
            n = add_signed(v, n, 1, 2 + phi, 2 * phi, shift);
            n = add_signed(v, n, phi, 2, 2 * phi + 1, shift);
        }
        break;
    default:
        return 0;
    }
    for (int i = 0; i < n; i++) {
        double r = sqrt(dot(v[i], v[i]));
        v[i] = (vec){v[i].x / r, v[i].y / r, v[i].z / r};
    }
    return n;
}

/* The face on the plane through v[i], v[j], v[k] if that plane has every
 * vertex on its inner side and i, j, k are its three lowest-numbered
 * vertices (so each face is found once). Corners in `face`, ordered. */
static int find_face(const vec *v, int n, int i, int j, int k, uint32_t *face)
{
    vec normal = cross(sub(v[j], v[i]), sub(v[k], v[i]));
    double len = sqrt(dot(normal, normal));
    if (len < 1e-6) return 0;
    normal = (vec){normal.x / len, normal.y / len, normal.z / len};
    double offset = dot(normal, v[i]);
    if (offset < 0) normal = (vec){-normal.x, -normal.y, -normal.z}, offset = -offset;
    int count = 0;
    for (int m = 0; m < n; m++) {
        double d = dot(normal, v[m]) - offset;
        if (d > ON_PLANE) return 0;
        if (d > -ON_PLANE) {
            if (count < 3 && m != (count == 0 ? i : count == 1 ? j : k)) return 0;
            face[count++] = (uint32_t)m;
        }
    }
    /* Order by angle about the centre, seen from outside (along -normal). */
    vec centre = {0, 0, 0};
    for (int m = 0; m < count; m++) {
        centre.x += v[face[m]].x / count, centre.y += v[face[m]].y / count;
        centre.z += v[face[m]].z / count;
    }
    vec u = sub(v[face[0]], centre);
    vec w = cross(normal, u);
    double angle[MAX_VERTICES];
    for (int m = 0; m < count; m++) {
        vec p = sub(v[face[m]], centre);
        angle[m] = atan2(dot(p, w), dot(p, u));
    }
    for (int a = 1; a < count; a++)
        for (int b = a; b > 0 && angle[b] < angle[b - 1]; b--) {
            double ta = angle[b];
            angle[b] = angle[b - 1], angle[b - 1] = ta;
            uint32_t tf = face[b];
            face[b] = face[b - 1], face[b - 1] = tf;
        }
    return count;
}

int mesh_solid_build(mesh_builder *b, int solid)
{
    vec v[MAX_VERTICES];
    const int n = solid_vertices(solid, v);
    if (n == 0) return -1;
    for (int i = 0; i < n; i++)
        if (mesh_builder_add_vertex(b, (hr_vec3){v[i].x, v[i].y, v[i].z})) return -1;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++)
            for (int k = j + 1; k < n; k++) {
                uint32_t face[MAX_VERTICES];
                int count = find_face(v, n, i, j, k, face);
                if (count >= 3 && mesh_builder_add_polygon(b, face, NULL, (size_t)count))
                    return -1;
            }
    return 0;
}
