/* Internal: the Phong term's cut-off. Below it, pow(phong, exponent) is
 * exactly 0 in double, so shade can skip the call and get the same bits:
 * the exact power is below 2^-1100 there, 25 binades under half the
 * smallest subnormal (2^-1075), where pow's result, off from the exact
 * power by a few units in the last place at most, can only round to 0. The
 * SPD's materials use exponent 100000, where the cut-off is 0.99240: most of
 * a highlight's pow calls go. exp2's own rounding is immaterial against
 * that margin. */
#ifndef HITRAY_LIB_SPECULAR_H
#define HITRAY_LIB_SPECULAR_H

#include <math.h>

static inline double hr_specular_cutoff(double exponent)
{
    /* exponent 0 (pow is 1 everywhere) and non-positive ones cut nothing. */
    return exponent > 0 ? exp2(-1100.0 / exponent) : 0.0;
}

#endif
