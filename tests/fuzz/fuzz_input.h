/* What every fuzz harness shares: the libFuzzer entry points it defines,
 * a reader that turns the input bytes into choices and numbers, and the
 * rule that a broken check ends the run.
 *
 * Numbers come in several kinds, chosen by a byte, so the fuzzer reaches
 * both ordinary geometry (small integers and fractions, where the shapes'
 * own tests live) and the values that break naive code (raw bit patterns:
 * subnormals, huge magnitudes, negative zero, infinities and NaN). An input
 * that runs out reads as zeros, so every prefix of an input is an input. */
#ifndef HR_FUZZ_INPUT_H
#define HR_FUZZ_INPUT_H

#include <stddef.h>
#include <stdint.h>

/* libFuzzer's entry points; the replay main (replay_main.c) calls them
 * too, so a corpus replays in builds without libFuzzer. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
int LLVMFuzzerInitialize(int *argc, char ***argv);

typedef struct fuzz_input {
    const uint8_t *data;
    size_t size, used;
} fuzz_input;

fuzz_input fuzz_input_make(const uint8_t *data, size_t size);
/* The next byte (0 past the end). */
uint8_t fuzz_byte(fuzz_input *in);
/* A choice in [0, n) from the next byte (n <= 256). */
unsigned fuzz_choice(fuzz_input *in, unsigned n);
/* Any double, NaN and infinities included (kind from the next byte). */
double fuzz_double(fuzz_input *in);
/* A finite double in [lo, hi]: the ordinary values a scene uses. */
double fuzz_double_in(fuzz_input *in, double lo, double hi);
/* Whether any input is left. */
int fuzz_more(const fuzz_input *in);

/* Aborts, after saying so, if any check of hr_test.h (used by the module
 * harness) has failed: libFuzzer keeps the input as a crash. `what` names
 * the harness. */
void fuzz_require_no_failures(const char *what);

/* abort() with a message saying what broke (printf format). */
void fuzz_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2), noreturn));

#endif
