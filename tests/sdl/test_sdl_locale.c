/* Numbers do not depend on the C locale: not on the program's, nor on a
 * thread's own (uselocale), nor on what other threads do meanwhile. Needs a
 * locale whose decimal point is not '.'; without one it is reported skipped
 * (LOCPATH may point at one made by `localedef -i de_DE -f UTF-8`; glibc then
 * leaks 30 bytes in newlocale, so a sanitizer build needs
 * ASAN_OPTIONS=detect_leaks=0). */
#define _GNU_SOURCE
#include <locale.h>
#include <pthread.h>
#include <stdio.h>
#include <string.h>

#include "sdl_test_support.h"

#define SKIPPED 77

static const char *const comma_locales[] = {"de_DE.UTF-8", "de_DE.utf8", "fr_FR.UTF-8",
                                            "fr_FR.utf8",  "ru_RU.UTF-8", "nl_NL.UTF-8",
                                            "de_DE",       "fr_FR"};

static locale_t comma_locale(void)
{
    for (size_t i = 0; i < sizeof comma_locales / sizeof comma_locales[0]; i++) {
        locale_t loc = newlocale(LC_ALL_MASK, comma_locales[i], (locale_t)0);
        if (!loc) continue;
        locale_t old = uselocale(loc);
        int comma = strcmp(localeconv()->decimal_point, ".") != 0;
        uselocale(old);
        if (comma) return loc;
        freelocale(loc);
    }
    return (locale_t)0;
}

static void check_numbers(hr_context *ctx)
{
    hr_sdl_result r;
    if (LOAD_OK(ctx, "translate 0.5 1.25e1 -.5 sphere", &r)) {
        hr_object_info o = sdl_test_object(r.scene, 0);
        CHECK(o.transform[3] == 0.5 && o.transform[7] == 12.5 && o.transform[11] == -0.5);
        hr_scene_destroy(r.scene);
    }
    EXPECT_ERROR(ctx, "translate 0,5 0 0", HR_ERROR_SDL, 1, 11, "found '0,5'");
}

typedef struct shared {
    hr_context *ctx;
    locale_t locale;
    volatile int done;
    int failures;
} shared;

#define LOADS 2000
#define NUMBERS 2000

/* Loads numbers with a decimal point, in the comma locale. */
static void *loader(void *arg)
{
    shared *s = arg;
    static char text[32 + 5 * NUMBERS];
    size_t len = (size_t)sprintf(text, "parameters %d", NUMBERS);
    for (int i = 0; i < NUMBERS; i++) len += (size_t)sprintf(text + len, " 0.5");
    uselocale(s->locale);
    for (int i = 0; i < LOADS; i++) {
        hr_sdl_result r;
        memset(&r, 0, sizeof r);
        r.struct_size = sizeof r;
        if (hr_sdl_load_string(s->ctx, text, "t.dat", NULL, &r) != HR_OK)
            s->failures++;
        else
            hr_scene_destroy(r.scene);
    }
    s->done = 1;
    return NULL;
}

/* Another thread of the program, in the "C" locale, asks for its own
 * conventions meanwhile: localeconv() keeps them in one static struct. */
static void *asker(void *arg)
{
    shared *s = arg;
    locale_t c = newlocale(LC_ALL_MASK, "C", (locale_t)0);
    uselocale(c);
    volatile const char *sink;
    while (!s->done) sink = localeconv()->decimal_point;
    (void)sink;
    uselocale(LC_GLOBAL_LOCALE);
    freelocale(c);
    return NULL;
}

int main(void)
{
    locale_t comma = comma_locale();
    if (!comma) {
        fprintf(stderr, "skipped: no locale with a decimal comma is installed\n");
        return SKIPPED;
    }
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);

    /* The thread's own locale. */
    locale_t old = uselocale(comma);
    check_numbers(ctx);
    uselocale(old);

    /* Two threads in different locales. */
    shared s = {ctx, comma, 0, 0};
    pthread_t a, b;
    CHECK(pthread_create(&b, NULL, asker, &s) == 0);
    CHECK(pthread_create(&a, NULL, loader, &s) == 0);
    pthread_join(a, NULL);
    pthread_join(b, NULL);
    CHECK_MSG(s.failures == 0, "%d of %d loads in the comma locale failed while another "
              "thread called localeconv()", s.failures, LOADS);

    hr_context_destroy(ctx);
    freelocale(comma);
    return hr_test_end();
}
