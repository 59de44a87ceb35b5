/* Inputs too big for every run of the suite (gigabytes of memory, seconds to
 * minutes): run only when HITRAY_HUGE_TESTS is set, else reported skipped. */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sdl_test_support.h"

#define SKIPPED 77

/* A line longer than INT32_MAX columns: the column stops at INT32_MAX (as
 * for a long word) instead of overflowing, for blanks too. */
static void long_line(hr_context *ctx)
{
    size_t blanks = (size_t)INT32_MAX + 1;
    char *text = malloc(blanks + 16);
    if (!text) {
        fprintf(stderr, "note: no memory for %zu blanks; long_line not run\n", blanks);
        return;
    }
    memset(text, ' ', blanks);
    strcpy(text + blanks, "spere");
    EXPECT_ERROR(ctx, text, HR_ERROR_SDL, 1, INT32_MAX, "unknown keyword 'spere'");
    free(text);
}

int main(void)
{
    if (!getenv("HITRAY_HUGE_TESTS")) {
        fprintf(stderr, "skipped: set HITRAY_HUGE_TESTS=1 to run (needs about 7 GiB)\n");
        return SKIPPED;
    }
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    long_line(ctx);
    hr_context_destroy(ctx);
    return hr_test_end();
}
