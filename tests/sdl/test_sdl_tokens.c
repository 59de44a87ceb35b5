/* SDL tokens: braces glued to words, '!' comments that end a word, the last
 * token without a final newline, number forms, line endings, columns. */
#include <string.h>

#include "sdl_test_support.h"

static int64_t count_objects(hr_context *ctx, const char *text)
{
    hr_sdl_result r;
    hr_scene *s = LOAD_OK(ctx, text, &r);
    int64_t n = s ? hr_scene_object_count(s) : -1;
    hr_scene_destroy(s);
    return n;
}

int main(void)
{
    hr_context *ctx = sdl_test_context(SDL_STUB_SHAPES);
    hr_sdl_result r;

    /* Braces are tokens of their own, even glued to words on both sides. */
    CHECK(count_objects(ctx, "def leg{push translate 1 0 0 sphere pop}use leg use leg") == 2);
    CHECK(count_objects(ctx, "def a{sphere}use a") == 1);
    CHECK(count_objects(ctx, "def a{}use a sphere") == 1);

    /* '!' ends the word it is glued to and comments out the rest of the line. */
    CHECK(count_objects(ctx, "def cube1 { cube }\nuse cube1!note sphere sphere\nuse cube1") == 2);
    CHECK(count_objects(ctx, "sphere!sphere\ncube") == 2);
    CHECK(count_objects(ctx, "! a whole line\n  ! another\nsphere ! trailing") == 1);
    /* A comment at the very end, with no newline after it. */
    CHECK(count_objects(ctx, "sphere\n! the end") == 1);
    CHECK(count_objects(ctx, "sphere !") == 1);
    /* '!' inside a def body comments the rest of that line only. */
    CHECK(count_objects(ctx, "def a { sphere ! cube }\n cube }\nuse a") == 2);

    /* The last token counts without a final newline (Hill's reader lost it). */
    CHECK(count_objects(ctx, "sphere") == 1);
    CHECK(count_objects(ctx, "cube\nsphere") == 2);
    if (LOAD_OK(ctx, "background 1 1 .5", &r)) {
        hr_scene_globals g;
        memset(&g, 0, sizeof g);
        g.struct_size = sizeof g;
        CHECK_OK(hr_scene_get_globals(r.scene, &g));
        CHECK_COLOR(g.background, 1, 1, 0.5, 0);
        hr_scene_destroy(r.scene);
    }
    /* Empty text and text of only comments make an empty scene. */
    CHECK(count_objects(ctx, "") == 0);
    CHECK(count_objects(ctx, "! nothing\n\n") == 0);

    /* Number forms: a leading point, a sign, an exponent, "+", "5.". */
    if (LOAD_OK(ctx, "diffuse .8 +.25 5.\nrotate -90 1 0 0 scale 1e-3 2E+1 1 sphere", &r)) {
        hr_object_info o = sdl_test_object(r.scene, 0);
        CHECK_COLOR(o.material.diffuse, 0.8, 0.25, 5.0, 0);
        /* rotate -90 about x maps y to -z: column 1 of M is (0, 0, -1) * 20. */
        CHECK_NEAR(o.transform[0], 1e-3, 0);
        CHECK_NEAR(o.transform[1], 0, 0);
        CHECK_NEAR(o.transform[5], 0, 0);
        CHECK_NEAR(o.transform[9], -20, 0);
        CHECK_NEAR(o.transform[6], 1, 0);
        hr_scene_destroy(r.scene);
    }

    /* Windows line endings and tabs: lines and columns still right. */
    CHECK(count_objects(ctx, "sphere\r\ncube\r\n") == 2);
    EXPECT_ERROR(ctx, "sphere\r\n\tscale x 1 1\r\n", HR_ERROR_SDL, 2, 8,
                 "expected a number after 'scale', found 'x'");
    /* A UTF-8 byte order mark is skipped and takes no column. */
    CHECK(count_objects(ctx, "\xEF\xBB\xBFsphere") == 1);
    EXPECT_ERROR(ctx, "\xEF\xBB\xBF" "spere", HR_ERROR_SDL, 1, 1, "unknown keyword 'spere'");

    /* Strict numbers: trailing junk, hex, inf, nan, a lone exponent. */
    EXPECT_ERROR(ctx, "translate 3x 0 0", HR_ERROR_SDL, 1, 11,
                 "expected a number after 'translate', found '3x'");
    EXPECT_ERROR(ctx, "translate 0x10 0 0", HR_ERROR_SDL, 1, 11, "found '0x10'");
    EXPECT_ERROR(ctx, "translate inf 0 0", HR_ERROR_SDL, 1, 11, "found 'inf'");
    EXPECT_ERROR(ctx, "translate 1 nan 0", HR_ERROR_SDL, 1, 13, "found 'nan'");
    EXPECT_ERROR(ctx, "translate 1 1e 0", HR_ERROR_SDL, 1, 13, "found '1e'");
    EXPECT_ERROR(ctx, "translate 1 . 0", HR_ERROR_SDL, 1, 13, "found '.'");
    EXPECT_ERROR(ctx, "translate 1 -.e1 0", HR_ERROR_SDL, 1, 13, "found '-.e1'");
    EXPECT_ERROR(ctx, "translate 1 1.5.2 0", HR_ERROR_SDL, 1, 13, "found '1.5.2'");
    EXPECT_ERROR(ctx, "translate 1e999 0 0", HR_ERROR_SDL, 1, 11, "'1e999'",
                 "beyond the range of a double");
    /* A number glued to a brace is two tokens: the brace is then unexpected. */
    EXPECT_ERROR(ctx, "translate 1 2 3{", HR_ERROR_SDL, 1, 16, "unexpected '{'");
    /* Tiny numbers underflow to a usable value, not an error. */
    CHECK(count_objects(ctx, "translate 1e-400 0 0 sphere") == 1);

    /* A long junk word is shortened in the message. */
    EXPECT_ERROR(ctx,
                 "scale 1 2 abcdefghijklmnopqrstuvwxyzabcdefghijklmnopqrstuvwxyzabcdefghijklmnop",
                 HR_ERROR_SDL, 1, 11, "found 'abcdefghijklmnopqrstuvwxyzabcdefghijklmn...'");

    hr_context_destroy(ctx);
    return hr_test_end();
}
