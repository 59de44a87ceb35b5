/* The window title (view.h): which pass, how fast, which effects ran, and
 * when the full-quality pass will be (or was) done. */
#include <stdarg.h>
#include <stdio.h>

#include "view.h"

/* Camera rays a pass casts: one per block (the last block of a row or
 * column may be partial), times its samples. */
static double pass_rays(const view_pass *p, int32_t width, int32_t height)
{
    double bx = (double)((width + p->block_size - 1) / p->block_size);
    double by = (double)((height + p->block_size - 1) / p->block_size);
    return bx * by * (double)p->samples_per_pixel;
}

/* Seconds until the last pass ends, from the last finished pass's time per
 * camera ray (secondary rays grow with the camera rays, so the ratio
 * holds once the blocks are small against the scene's features), the pass
 * in flight counted by what is left of it. Needs a finished pass. */
static double seconds_left(const view_status *s)
{
    double per_ray = s->last.stats.seconds / pass_rays(&s->plan[s->last.pass], s->width, s->height);
    double left = 0.0;
    for (int i = s->last.pass + 1; i < s->passes; i++) {
        double t = per_ray * pass_rays(&s->plan[i], s->width, s->height);
        left += i == s->running_pass ? t * (1.0 - s->running_fraction) : t;
    }
    return left;
}

static void append(char *buf, size_t size, size_t *at, const char *fmt, ...) __attribute__((format(printf, 4, 5)));
static void append(char *buf, size_t size, size_t *at, const char *fmt, ...)
{
    if (*at >= size) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + *at, size - *at, fmt, ap);
    va_end(ap);
    if (n > 0) *at += (size_t)n < size - *at ? (size_t)n : size - *at - 1;
}

void view_status_text(const view_status *s, char *buf, size_t size)
{
    size_t at = 0;
    buf[0] = '\0';
    append(buf, size, &at, "hitray view: %s", s->scene_name);
    if (s->error) {
        append(buf, size, &at, " | render failed: %s", s->error);
        return;
    }
    int done = s->running_pass >= s->passes;
    if (done && s->has_frame) {
        append(buf, size, &at, " | final pass (%d of %d)", s->passes, s->passes);
    } else {
        int pass = s->running_pass < s->passes ? s->running_pass : s->passes - 1;
        const view_pass *p = &s->plan[pass];
        append(buf, size, &at, " | pass %d of %d: block %d", pass + 1, s->passes, (int)p->block_size);
        if (p->samples_per_pixel > 1) append(buf, size, &at, ", %d spp", (int)p->samples_per_pixel);
        append(buf, size, &at, " %.0f%%", 100.0 * s->running_fraction);
    }
    if (s->has_frame) {
        const hr_render_stats *st = &s->last.stats;
        double rays = (double)(st->primary + st->shadow + st->reflected + st->refracted);
        double rate = st->seconds > 0.0 ? rays / st->seconds : 0.0;
        if (rate >= 1e6) append(buf, size, &at, " | %.2f M rays/s", rate / 1e6);
        else append(buf, size, &at, " | %.0f k rays/s", rate / 1e3);
        append(buf, size, &at, " | effects:");
        int any = 0;
        for (int bit = 0; bit < 32; bit++) {
            const char *name = (st->effects >> bit) & 1u ? hr_effect_name(1u << bit) : NULL;
            if (!name) continue;
            append(buf, size, &at, "%s %s", any ? "," : "", name);
            any = 1;
        }
        if (!any) append(buf, size, &at, " none");
        if (done) append(buf, size, &at, " | final pass after %.2f s", s->last.since_restart);
        else append(buf, size, &at, " | final in ~%.1f s", seconds_left(s));
    }
    append(buf, size, &at, " | step %.3g, %.3g deg | H: keys", s->steps.slide, s->steps.degrees);
}
