/* shade skips pow(phong, exponent) at or below hri_specular_cutoff
 * (lib/scene/material_analysis.h), which is only right if pow is exactly 0 there: checked
 * for the exponents the SPD and Hill's scenes use and the extremes, on
 * 200,000 values each up to the cut-off (the cut-off itself among them),
 * and the cut-off is no more than a few percent below where pow really
 * reaches 0 for the large exponents, so the saving is real. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "hr_test.h"
#include "scene/material_analysis.h"

int main(void)
{
    const double exponents[] = {0.5, 1.0, 3.0827, 4.81884, 50.0, 101.148, 200.0, 1e5, 1e6, 1e9};
    uint64_t state = 12345;
    for (size_t e = 0; e < sizeof exponents / sizeof *exponents; e++) {
        const double n = exponents[e], cut = hri_specular_cutoff(n);
        CHECK(cut >= 0 && cut < 1); /* 0 where 2^(-1100/n) underflows: no cut */
        long nonzero = 0;
        for (int i = 0; i < 200000; i++) {
            state ^= state << 13, state ^= state >> 7, state ^= state << 17;
            double u = (double)(state >> 11) * 0x1p-53;
            double x = i == 0 ? cut : i == 1 ? nextafter(cut, 0) : cut * (1.0 - u * u * u);
            nonzero += pow(x, n) != 0.0;
        }
        CHECK_MSG(nonzero == 0, "exponent %g: pow is not 0 for %ld values below the cut-off %.17g", n,
                  nonzero, cut);
        /* Where pow first gives a nonzero result: just above 2^(-1075/n). */
        const double first_nonzero = exp2(-1075.0 / n);
        fprintf(stderr, "exponent %g: cut-off %.9g, pow nonzero from about %.9g\n", n, cut, first_nonzero);
        if (n >= 1e5) CHECK(cut > 0.99 * first_nonzero);
    }
    CHECK(hri_specular_cutoff(0.0) == 0.0);
    return hr_test_end();
}
