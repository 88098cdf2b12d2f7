/* Progress bars on a stream (stderr in the CLI): label, bar, percentage, rate and ETA.
 * Redrawn at most ten times per second by whichever thread reports progress. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/base.h"

struct lucent_progress {
    char label[48];
    char unit[16]; /* "frame": the bar also says "frame k of n" */
    uint64_t total;
    _Atomic uint64_t done;
    double start, limit; /* limit: seconds from start (0: none) */
    _Atomic long long next_draw_ns;
    pthread_mutex_t draw_lock;
};

static FILE *_Atomic g_progress_out;

void lucent_progress_set_output(FILE *out) { atomic_store(&g_progress_out, out); }

lucent_progress *lucent_progress_begin(const char *label, uint64_t total)
{
    lucent_progress *p = calloc(1, sizeof *p);
    if (!p) return NULL;
    snprintf(p->label, sizeof p->label, "%s", label ? label : "");
    p->total = total;
    p->start = lucent_clock_seconds();
    pthread_mutex_init(&p->draw_lock, NULL);
    return p;
}

/* Formats a count with an SI suffix: 950, 12.3k, 4.56M. */
static void format_rate(double v, char *dest, size_t n)
{
    int len = v >= 1e9   ? snprintf(dest, n, "%.3gG", v / 1e9)
              : v >= 1e6 ? snprintf(dest, n, "%.3gM", v / 1e6)
              : v >= 1e3 ? snprintf(dest, n, "%.3gk", v / 1e3)
                         : snprintf(dest, n, "%.3g", v);
    (void)len;
}

static void format_duration(double s, char *dest, size_t n)
{
    if (!(s >= 0) || s > 360000) {
        snprintf(dest, n, "--:--");
        return;
    }
    long t = (long)(s + 0.5);
    int len = t >= 3600 ? snprintf(dest, n, "%ld:%02ld:%02ld", t / 3600, t / 60 % 60, t % 60)
                        : snprintf(dest, n, "%ld:%02ld", t / 60, t % 60);
    (void)len; /* t is at most 100 hours: always fits */
}

void lucent_progress_set_unit(lucent_progress *p, const char *unit)
{
    if (p) snprintf(p->unit, sizeof p->unit, "%s", unit ? unit : "");
}

void lucent_progress_set_deadline(lucent_progress *p, double seconds)
{
    if (p) p->limit = seconds > 0 ? seconds : 0;
}

static void draw(lucent_progress *p, FILE *out, bool final)
{
    uint64_t done = atomic_load(&p->done);
    double frac = p->total ? (double)done / (double)p->total : 1.0;
    double elapsed = lucent_clock_seconds() - p->start;
    double rate = elapsed > 0 ? (double)done / elapsed : 0;
    double eta = rate > 0 ? (double)(p->total - (done < p->total ? done : p->total)) / rate : -1;
    if (p->limit > 0) { /* the time limit ends the task first when its share is ahead */
        frac = fmax(frac, elapsed / p->limit);
        eta = eta < 0 ? fmax(p->limit - elapsed, 0) : fmin(eta, fmax(p->limit - elapsed, 0));
    }
    if (frac > 1) frac = 1;
    char bar[31], rate_s[32], time_s[32], elapsed_s[32], count[64] = "";
    int fill = (int)(frac * 30);
    for (int i = 0; i < 30; i++) bar[i] = i < fill ? '#' : '.';
    bar[30] = '\0';
    format_rate(rate, rate_s, sizeof rate_s);
    format_duration(final ? elapsed : eta, time_s, sizeof time_s);
    format_duration(elapsed, elapsed_s, sizeof elapsed_s);
    if (p->unit[0]) /* the unit in progress: the next one unless all are done */
        snprintf(count, sizeof count, " %s %llu of %llu", p->unit,
                 (unsigned long long)(done < p->total ? done + 1 : p->total), (unsigned long long)p->total);
    if (final)
        fprintf(out, "\r%-20s [%s] %5.1f%%%s %8s/s took %s\n", p->label, bar, 100 * frac, count, rate_s, time_s);
    else
        fprintf(out, "\r%-20s [%s] %5.1f%%%s %8s/s %s elapsed, ETA %s   ", p->label, bar, 100 * frac, count, rate_s,
                elapsed_s, time_s);
    fflush(out);
}

void lucent_progress_add(lucent_progress *p, uint64_t n)
{
    if (!p) return;
    atomic_fetch_add(&p->done, n);
    FILE *out = atomic_load(&g_progress_out);
    if (!out) return;
    long long t = (long long)(lucent_clock_seconds() * 1e9);
    long long next = atomic_load(&p->next_draw_ns);
    if (t < next || !atomic_compare_exchange_strong(&p->next_draw_ns, &next, t + 100000000LL)) return;
    if (pthread_mutex_trylock(&p->draw_lock) != 0) return;
    draw(p, out, false);
    pthread_mutex_unlock(&p->draw_lock);
}

uint64_t lucent_progress_done(const lucent_progress *p) { return p ? atomic_load(&((lucent_progress *)p)->done) : 0; }

void lucent_progress_end(lucent_progress *p)
{
    if (!p) return;
    FILE *out = atomic_load(&g_progress_out);
    if (out) {
        pthread_mutex_lock(&p->draw_lock);
        draw(p, out, true);
        pthread_mutex_unlock(&p->draw_lock);
    }
    pthread_mutex_destroy(&p->draw_lock);
    free(p);
}
