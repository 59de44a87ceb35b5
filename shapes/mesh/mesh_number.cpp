// mesh_decimal_to_double (mesh_number.h) over fast_float::from_chars.
#include "mesh_number.h"

#include <fast_float/fast_float.h>

extern "C" int mesh_decimal_to_double(const char *s, size_t n, double *out)
{
    const char *first = s, *last = s + n;
    // from_chars follows C++17's grammar, which has no leading '+'; a '+'
    // followed by another sign is refused here, as strtod refuses it.
    if (first < last && *first == '+') {
        first++;
        if (first < last && (*first == '+' || *first == '-')) return 0;
    }
    if (first == last) return 0;
    double value = 0.0;
    const fast_float::from_chars_result r =
        fast_float::from_chars(first, last, value, fast_float::chars_format::general);
    if (r.ec != std::errc() || r.ptr != last) return 0;
    *out = value;
    return 1;
}
