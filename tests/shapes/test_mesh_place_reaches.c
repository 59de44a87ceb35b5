/* A closed mesh's first hit is the first of its all-hits list where a
 * crossing before the first-hit search's best, outside the caller's
 * interval, has a t error bound wide enough for the list's repair to fill
 * its place from past the best (place_reaches in
 * shapes/mesh/mesh_trace.c). A fuzz input: twelve triangles on a cube's
 * vertices, vertices 1 and 3 pulled out to x = -6.7e15, and the ray from
 * (-8.3e15, -1, -1.5) along (1.0e16, 0, 1.5) over (0, inf), lying in the
 * plane y = -1 of the faces (1, 4, 3) and (4, 7, 3). In rational arithmetic
 * on the doubles the line first meets the surface at t = 1 + 5.0e-4, where
 * it crosses the edge 3-7: it enters through the face (2, 3, 7) and runs on
 * inside the face (4, 7, 3) until t = 5/3; it leaves through the face
 * (1, 2, 6) at t = 1 + 11/29 (the surface passes through itself), and
 * enters the face (5, 6, 7) at t = 5/3. The triangle test sees (1, 5, 8)
 * leaving at t = 1 (t error 1.4e-13; exactly, the line passes just outside
 * it), (1, 2, 6) leaving at t = 1 (t error 500, which the caller's
 * tmin = 0 refuses it for) and (2, 3, 7) entering at t = 1 + 5.0e-4. The
 * all-hits list's repair moves the entering crossing up onto the place of
 * (1, 2, 6), within twice its t error, and keeps both: it lists the
 * entering crossing first, at t = 1. The first-hit search took (1, 5, 8) as
 * its best, whose window ends at 1 + 2.9e-13, and (1, 2, 6), of the same
 * kind, formed no near tie with it: it gave the leaving hit. Checked:
 * first_hit's t and entering flag are those of all hits' first. */
#include "hr_test.h"
#include "mesh_support.h"
#include "module_harness.h"

static const char mesh_text[] = "v -6663333333316665 -1 -0\n"
                                "v -0 1 1\n"
                                "v -6660001197173880 -1 -0\n"
                                "v 1 -1 1\n"
                                "v -1 19 -6\n"
                                "v -1 -21 1\n"
                                "v 1 -1 3\n"
                                "v -1 1 1\n"
                                "f 1 4 3\nf 1 3 2\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
                                "f 4 8 7\nf 4 7 3\nf 1 5 8\nf 1 8 4\nf 2 3 7\nf 2 7 6\n";

int main(void)
{
    const hr_ray ray = harness_ray(-0x1.d97553c70c149p+53, -1.0, -1.5, 0x1.1c1332443a72cp+53, 0.0, 1.5);
    mesh_check_first_is_all_first("place_reaches.obj", mesh_text, ray);
    return hr_test_end();
}
