/* The render progress bar and Ctrl-C (cli.h).
 *
 * hr_render calls the progress callback from one thread at a time as tiles
 * finish. The bar goes to stderr, and only when stderr is a terminal, so
 * logs and pipes get the summary line alone. The same callback turns a
 * first Ctrl-C into a clean cancel (hr_render returns HR_ERROR_CANCELLED and
 * no file is written); a second Ctrl-C kills the process as usual. A
 * Ctrl-C that comes after the render, while the files are being written, is
 * held until they are complete (cli_interrupt_release): killing the process
 * there would leave a temporary file behind. */
#include <signal.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli.h"

#define BAR_WIDTH 32
#define BAR_LINE_WIDTH 96 /* the longest label and time left fit */

static volatile sig_atomic_t interrupted;
static int quiet;

void cli_set_quiet(int on) { quiet = on; }

/* The bar and the status line are drawn on a terminal only, and not under
 * --quiet. */
static int draws(void) { return !quiet && isatty(STDERR_FILENO); }
static struct sigaction previous_sigint;
static int handler_installed;

static void on_sigint(int signo)
{
    (void)signo;
    interrupted = 1;
}

int cli_interrupted(void) { return interrupted != 0; }

double cli_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_begin(cli_progress *p, const char *label)
{
    memset(p, 0, sizeof *p);
    p->draw = draws();
    p->last_shown = -1;
    p->started = cli_now();
    p->label = label;
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sa.sa_flags = SA_RESETHAND; /* the second Ctrl-C is not caught */
    sigemptyset(&sa.sa_mask);
    interrupted = 0;
    sigaction(SIGINT, &sa, &previous_sigint);
    handler_installed = 1;
    /* Ignored when we started (a shell's background job): stay ignored. */
    if (!(previous_sigint.sa_flags & SA_SIGINFO) && previous_sigint.sa_handler == SIG_IGN) cli_interrupt_release();
}

/* One line of the bar: label, bar, per cent, the time so far and, from 1%
 * on, the time left at the rate so far. */
static void format_bar(char *out, size_t size, const char *label, double fraction, double elapsed)
{
    int percent = (int)(fraction * 100.0 + 0.5);
    if (percent < 0) percent = 0;
    if (percent > 100) percent = 100;
    char bar[BAR_WIDTH + 1];
    int filled = percent * BAR_WIDTH / 100;
    for (int i = 0; i < BAR_WIDTH; i++) bar[i] = i < filled ? '#' : ' ';
    bar[BAR_WIDTH] = '\0';
    /* The time left, at the rate so far; not before 1% is done, when the
     * rate says little. */
    if (fraction >= 0.01 && fraction < 1.0)
        snprintf(out, size, "%s [%s] %3d%%  %.1f s, about %.0f s left", label, bar, percent, elapsed,
                 elapsed * (1.0 - fraction) / fraction + 0.5);
    else
        snprintf(out, size, "%s [%s] %3d%%  %.1f s", label, bar, percent, elapsed);
}

int32_t cli_progress_update(void *user, double fraction)
{
    cli_progress *p = user;
    if (p->draw) {
        int percent = (int)(fraction * 100.0 + 0.5);
        /* Redraw only when the number changes: a big render finishes
         * thousands of tiles, and the terminal need not see each. The
         * library reports fractions that never go backwards. */
        if (percent != p->last_shown) {
            /* Padded to a fixed width, so a shorter line covers a longer
             * one; erasing the line ("\033[K") is kept for the end, where
             * it says the render is over (tests watch for it). */
            char line[256];
            format_bar(line, sizeof line, p->label, fraction, cli_now() - p->started);
            fprintf(stderr, "\r%-*s", BAR_LINE_WIDTH, line);
            fflush(stderr);
            p->last_shown = percent;
        }
    }
    return interrupted ? 1 : 0;
}

void cli_progress_end(cli_progress *p)
{
    if (p->draw && p->last_shown >= 0) {
        fputs("\r\033[K", stderr); /* clear the bar's line */
        fflush(stderr);
    }
}

/* Characters of the status line on the terminal now (0: none). */
static int status_shown;

void cli_status(const char *what, const char *name)
{
    if (!draws()) return;
    /* Overwritten with blanks, not erased with "\033[K": see above. */
    if (status_shown) fprintf(stderr, "\r%*s\r", status_shown, "");
    status_shown = 0;
    if (what) {
        int n = fprintf(stderr, "%s %s ...", what, name);
        status_shown = n > 0 ? n : 0;
    }
    fflush(stderr);
}

void cli_interrupt_release(void)
{
    if (!handler_installed) return;
    sigaction(SIGINT, &previous_sigint, NULL);
    handler_installed = 0;
}

void cli_hold_signals(sigset_t *previous)
{
    sigset_t hold;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    sigaddset(&hold, SIGTERM);
    sigaddset(&hold, SIGHUP);
    sigaddset(&hold, SIGQUIT);
    /* The render's threads have ended: the process mask is this thread's. */
    sigprocmask(SIG_BLOCK, &hold, previous);
}

void cli_release_signals(const sigset_t *previous)
{
    /* A signal that came meanwhile is delivered here, after the rename. */
    sigprocmask(SIG_SETMASK, previous, NULL);
}
