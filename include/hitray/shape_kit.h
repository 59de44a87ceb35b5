/* hitray: the shape kit, what the built-in shape modules are made of, for
 * anyone writing a shape module (see examples/shape_plugin).
 *
 * Header-only and static inline: a module that uses it still links nothing
 * of libhitray (the ABI promise of shape_module.h) and needs only libm. The
 * names start with shape_ (functions, types) and SHAPE_ (macros). What each
 * part gives and guarantees:
 *
 * shape_kit_math.h, the numerics. u is the unit roundoff (2^-53):
 * - shape_gamma(n) = n u / (1 - n u), the bound on the relative error of n
 *   chained roundings (pbrt-v4, Higham ch. 3): state a hit's error with it;
 * - shape_ray_point_error(ray, t, m): a bound, per coordinate, on the
 *   rounding of origin + t dir when t came from m roundings (gamma(m + 3)
 *   of max |o_i| + |t d_i|), for hr_hit.error of a flat surface;
 * - shape_two_product, shape_two_sum (error-free: the result plus its error
 *   is exact), shape_sum (a sum of products as accurate as one in twice the
 *   precision), shape_difference_of_products (a b - c d within 1.5 ulp);
 * - shape_solve_half_quadratic: the real roots of a t^2 + 2 h t + c = 0,
 *   sorted, with no cancellation in either root (the discriminant is the
 *   caller's, in the form that stays accurate for its geometry);
 * - power-of-two rescaling: shape_vec3_scale_exponent, shape_ldexp,
 *   shape_vec3_rescaled, exact, so a length squared neither overflows nor
 *   underflows;
 * - SHAPE_FMA_CLONES: builds a hot function for CPUs with and without FMA
 *   (same bits either way), with GCC's target_clones; SHAPE_FMA_DISPATCH
 *   (shape_kit_cpu.h) does the same with any compiler.
 *
 * shape_kit_hits.h, from crossings to the hits the host gets:
 * - shape_span and shape_slab_span: a convex solid as the intersection of
 *   regions, each the span of t the ray is inside it; an edge or seam is
 *   entered exactly once whatever rounding does (the first region keeps a
 *   tie);
 * - shape_report: appends the crossings inside the open (tmin, tmax) in the
 *   mode asked, drops non-finite ones, so the contract (sorted, no NaN or
 *   infinity) holds;
 * - SHAPE_DEFINE_HIT_MODES(prefix, trace): the vtable's hit, first_hit and
 *   any_hit from one trace(args, mode) function.
 *
 * shape_kit_cpu.h, what the CPU runs: shape_cpu_has_avx2(),
 *   shape_cpu_has_fma() (CPUID and XGETBV read once, not the compiler
 *   runtime's CPU model, which some toolchains leave empty), for a module
 *   that keeps a faster path beside the baseline one; SHAPE_FMA_DISPATCH
 *   and SHAPE_FMA_DISPATCH_VOID, a hot function built for CPUs with and
 *   without FMA and picked per call (what the built-in shapes use).
 *
 * shape_kit_box.h, the slab test: shape_box_misses(box, ray, tmin, tmax)
 * never says "misses" for a ray that touches the box in (tmin, tmax); its
 * widening (2^-20 relative, 2^-1022 absolute) is far above pbrt's
 * 1 + 2 gamma(3), so it also covers a shape's rounding of t. The host culls
 * with the same test.
 *
 * shape_kit_instance.h, for a class without parameters: shape_plain_create,
 * shape_plain_destroy, and shape_set_bounds.
 *
 * shape_kit_z0.h, the plane z = 0: shape_z0_crossing (no infinity or NaN
 * for a parallel ray) and shape_z0_fill (point, normal, error bound).
 *
 * shape_kit_uv.h, for surface_uv: shape_turn (an angle as a fraction of a
 * turn, in [0, 1)) and SHAPE_UV_PROBE (the answer to "does this shape give
 * (u, v)?").
 *
 * shape_kit_module.h, the declaration of a module: shape_param(args, name)
 * for create, and SHAPE_CLASS with SHAPE_MODULE_OF (or SHAPE_MODULE for
 * several classes), the class table, module info and entry point. */
#ifndef HITRAY_SHAPE_KIT_H
#define HITRAY_SHAPE_KIT_H

#include "shape_kit_box.h"
#include "shape_kit_cpu.h"
#include "shape_kit_hits.h"
#include "shape_kit_instance.h"
#include "shape_kit_math.h"
#include "shape_kit_module.h"
#include "shape_kit_uv.h"
#include "shape_kit_z0.h"

#endif
