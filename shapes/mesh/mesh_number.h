/* Decimal text to double for the mesh readers: the one C function over
 * fast_float (Lemire's exact decimal-to-binary conversion, a C++ header
 * library; mesh_number.cpp), several times faster than strtod on the
 * coordinates of a mesh file and as exact: the nearest double, ties to
 * even, as strtod gives in the default rounding mode. Unlike strtod it
 * reads '.' whatever the locale. */
#ifndef HITRAY_MESH_NUMBER_H
#define HITRAY_MESH_NUMBER_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Converts s[0, n): [+-] digits [. digits] [(e|E) [+-] digits], with at
 * least one digit before the exponent (the caller checks that grammar;
 * fast_float alone would also take "inf" and "nan"). Returns 1 and writes
 * *out when the whole text was read; a value past double's range is
 * +-infinity, one below it a subnormal or a signed zero, as from strtod.
 * Returns 0 when the text is not one such number. */
int mesh_decimal_to_double(const char *s, size_t n, double *out);

#ifdef __cplusplus
}
#endif

#endif
