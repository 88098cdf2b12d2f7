/* Logging: formatted lines to an application-installed sink (the library never prints). */
#include <pthread.h>
#include <stdio.h>

#include "lucent/base.h"

static pthread_mutex_t g_log_lock = PTHREAD_MUTEX_INITIALIZER;
static lucent_log_fn g_log_fn;
static void *g_log_user;
static lucent_log_level g_log_min = LUCENT_LOG_OFF;

void lucent_log_set_sink(lucent_log_fn fn, void *user, lucent_log_level min_level)
{
    pthread_mutex_lock(&g_log_lock);
    g_log_fn = fn;
    g_log_user = user;
    g_log_min = min_level;
    pthread_mutex_unlock(&g_log_lock);
}

void lucent_log(lucent_log_level level, const char *fmt, ...)
{
    char line[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    pthread_mutex_lock(&g_log_lock);
    if (g_log_fn && level >= g_log_min && level < LUCENT_LOG_OFF) g_log_fn(level, line, g_log_user);
    pthread_mutex_unlock(&g_log_lock);
}

void lucent_log_stderr_sink(lucent_log_level level, const char *message, void *user)
{
    static const char *const names[] = {"debug", "info", "warning", "error"};
    FILE *out = user ? (FILE *)user : stderr;
    if (level == LUCENT_LOG_INFO)
        fprintf(out, "lucent: %s\n", message);
    else
        fprintf(out, "lucent: %s: %s\n", names[level], message);
}
