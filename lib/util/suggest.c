/* "Did you mean" (lib/util/suggest.h and hr_suggest): the candidate nearest a
 * misspelt word by edit distance, if it is near enough to be what was
 * meant.
 *
 * The distance is the optimal string alignment distance (Levenshtein's
 * insertions, deletions and substitutions, plus swaps of two neighbours:
 * "specualr" is one step from "specular"), with letters compared without
 * regard to case, so "SpecularExponet" still finds "specularExponent".
 * Near enough means at most one step per four letters of the word (at least
 * one): "--sp" suggests "--spp", while "cube" does not suggest "tube". Words
 * past SUGGEST_MAX_LENGTH get no suggestion: no keyword is that long, and
 * the table stays on the stack. */
#include "util/suggest.h"

#include <string.h>

#include <hitray/hitray.h>

#define SUGGEST_MAX_LENGTH 64

static char fold(char c) { return c >= 'A' && c <= 'Z' ? (char)(c - 'A' + 'a') : c; }

static int32_t min3(int32_t a, int32_t b, int32_t c)
{
    int32_t m = a < b ? a : b;
    return m < c ? m : c;
}

/* The distance, or limit + 1 once it is certain to exceed limit. */
static int32_t distance(const char *a, size_t n, const char *b, size_t m, int32_t limit)
{
    if ((n > m ? n - m : m - n) > (size_t)limit) return limit + 1;
    /* Three rows of the (n + 1) x (m + 1) table: two back for the swap. */
    int32_t rows[3][SUGGEST_MAX_LENGTH + 1];
    int32_t *before = rows[0], *prev = rows[1], *cur = rows[2];
    for (size_t j = 0; j <= m; j++) prev[j] = (int32_t)j;
    for (size_t i = 1; i <= n; i++) {
        cur[0] = (int32_t)i;
        int32_t row_min = cur[0];
        for (size_t j = 1; j <= m; j++) {
            int32_t cost = fold(a[i - 1]) == fold(b[j - 1]) ? 0 : 1;
            int32_t d = min3(prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + cost);
            if (i > 1 && j > 1 && fold(a[i - 1]) == fold(b[j - 2]) && fold(a[i - 2]) == fold(b[j - 1]) &&
                before[j - 2] + 1 < d)
                d = before[j - 2] + 1;
            cur[j] = d;
            if (d < row_min) row_min = d;
        }
        if (row_min > limit) return limit + 1;
        int32_t *t = before;
        before = prev;
        prev = cur;
        cur = t;
    }
    return prev[m];
}

void hri_suggester_init(hr_suggester *s, const char *word)
{
    s->word = word ? word : "";
    s->length = strlen(s->word);
    s->best = NULL;
    s->best_distance = 0;
}

void hri_suggester_offer(hr_suggester *s, const char *candidate)
{
    if (!candidate || s->length == 0 || s->length > SUGGEST_MAX_LENGTH) return;
    size_t m = strlen(candidate);
    if (m > SUGGEST_MAX_LENGTH || strcmp(candidate, s->word) == 0) return;
    int32_t limit = (int32_t)(s->length / 4);
    if (limit < 1) limit = 1;
    if (s->best && s->best_distance - 1 < limit) limit = s->best_distance - 1;
    int32_t d = distance(s->word, s->length, candidate, m, limit);
    if (d <= limit) {
        s->best = candidate;
        s->best_distance = d;
    }
}

HR_API const char *hr_suggest(const char *word, const char *const *candidates, int32_t count)
{
    if (!word || !candidates) return NULL;
    hr_suggester s;
    hri_suggester_init(&s, word);
    for (int32_t i = 0; i < count; i++) hri_suggester_offer(&s, candidates[i]);
    return s.best;
}
