/* Internal: "did you mean" (lib/util/suggest.c), for keywords, options and shape
 * class names. Candidates are offered one at a time, so a caller can walk
 * its own tables without gathering them into an array first. */
#ifndef HITRAY_LIB_UTIL_SUGGEST_H
#define HITRAY_LIB_UTIL_SUGGEST_H

#include <stddef.h>
#include <stdint.h>

typedef struct hr_suggester {
    const char *word; /* the misspelt word */
    size_t length;
    const char *best; /* NULL until a candidate is close enough */
    int32_t best_distance;
} hr_suggester;

void hri_suggester_init(hr_suggester *s, const char *word);
/* Offer one candidate; the closest close-enough one is kept (the first of
 * equals). A candidate equal to the word is not a suggestion. */
void hri_suggester_offer(hr_suggester *s, const char *candidate);

#endif
