#include "numerics_cases.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hr_test.h"

double nc_gamma(int n)
{
    return n * NC_U / (1 - n * NC_U);
}

void nc_note(nc_result *r, double ratio)
{
    r->samples++;
    if (!(ratio <= r->worst)) r->worst = isnan(ratio) ? INFINITY : ratio;
}

/* CATALOG.md, read once: every case id must head a section ("### Q03 ..."). */
static char *read_catalog(void)
{
    FILE *f = fopen(HR_TEST_SOURCE_DIR "/tests/numerics/CATALOG.md", "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    const long size = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *text = size >= 0 ? malloc((size_t)size + 1) : NULL;
    if (text) text[fread(text, 1, (size_t)size, f)] = '\0';
    fclose(f);
    return text;
}

int nc_run_table(const char *program, const nc_case *cases, int count)
{
    char *catalog = read_catalog();
    CHECK_MSG(catalog != NULL, "tests/numerics/CATALOG.md cannot be read");
    for (int i = 0; i < count; i++) {
        const nc_case *c = &cases[i];
        if (catalog) {
            char heading[64];
            snprintf(heading, sizeof heading, "\n### %s ", c->id);
            CHECK_MSG(strstr(catalog, heading) != NULL, "%s: case %s is not in CATALOG.md",
                      program, c->id);
        }
        nc_result r;
        memset(&r, 0, sizeof r);
        const int failures_before = hr_test_failures;
        c->run(&r);
        printf("%s %-4s %-16s worst %8.3g of tolerance, %ld events, over %7ld samples%s%s%s\n",
               program, c->id, c->shape, r.worst, r.events, r.samples, r.note[0] ? " (" : "",
               r.note, r.note[0] ? ")" : "");
        CHECK_MSG(r.worst <= 1.0, "%s %s (%s): worst error %.3g of its tolerance (%s)", program,
                  c->id, c->setup, r.worst, c->tolerance);
        CHECK_MSG(r.events == 0, "%s %s (%s): %ld events (%s)", program, c->id, c->setup,
                  r.events, c->tolerance);
        CHECK_MSG(r.samples > 0, "%s %s: measured nothing", program, c->id);
        if (hr_test_failures != failures_before)
            printf("  %s failed: %s -- hard because %s\n", c->id, c->setup, c->why_hard);
    }
    free(catalog);
    return hr_test_end();
}
