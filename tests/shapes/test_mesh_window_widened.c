/* A closed mesh's first hit is the first of its all-hits list where a
 * best hit of the first-hit search is replaced by one with a wider window
 * (see leaf_loop in shapes/mesh/mesh_trace.c). A fuzz input: twelve
 * triangles on a cube's vertices, two of them pulled out to x = -6.7e15,
 * and the ray from (-8.3e15, -1, -1.5) along (1.0e16, 0, 1.5) over
 * (0, inf), aimed at vertex 1 and lying in the plane y = -1 of the
 * faces (1, 4, 3) and (4, 7, 3). In rational arithmetic on the doubles the
 * line meets vertex 1 at t = 1, runs inside the face (1, 4, 3) and leaves
 * the plane across the edge 3-7 at t = 1 + 4.65e-10, through the face
 * (2, 3, 7); then it crosses the face (5, 6, 7) at t = 5/3. The winding
 * number is 0 before t = 1, -1 on (1 + 4.65e-10, 5/3) and 0 after: the line
 * leaves first (the surface passes through itself). The triangle test
 * sees the faces (1, 3, 2) and (1, 5, 8) leaving at t = 1 (t errors 4.8e-5
 * and 1.4e-13) and (2, 3, 7) entering at t = 1 + 4.65e-10. The all-hits
 * list's repair moves the entering one up onto t = 1 (the slack of the
 * leaving (1, 3, 2) holds twice its t error) and lists it first. The
 * first-hit search met (1, 5, 8) first, which narrowed its end to
 * 1 + 2.9e-13, refused (2, 3, 7) there, and then took (1, 3, 2) as its best
 * (the same t, a lower index), whose window reaches 1 + 9.6e-5 and holds
 * the entering crossing it never saw: it gave the leaving hit. Checked:
 * first_hit's t and entering flag are those of all hits' first. */
#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static const char mesh_text[] = "v -6666666666633330 -1 -0\n"
                                "v -0 1 1\n"
                                "v -6666666663533342 -1 -0\n"
                                "v 1 -1 1\n"
                                "v -1 19 -6\n"
                                "v -1 -21 1\n"
                                "v 1 -1 3\n"
                                "v 1 1 1\n"
                                "v -1 1 1\n"
                                "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

int main(void)
{
    const hr_ray ray = harness_ray(-0x1.d9b1f5d20329p+53, -1.0, -1.5, 0x1.1c37937e01e57p+53, 0.0, 1.5);
    mesh_check_first_is_all_first("window_widened.obj", mesh_text, ray);
    return hr_test_end();
}
