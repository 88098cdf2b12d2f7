/* Status codes and the per-thread error message. */
#include <stdio.h>
#include <string.h>

#include "lucent/base.h"

enum { ERROR_MESSAGE_MAX = 2048 };

static _Thread_local char t_message[ERROR_MESSAGE_MAX];
static _Thread_local lucent_status t_status;

static const char *const k_status_text[] = {
#define LUCENT_X_TEXT(code, text) text,
    LUCENT_STATUS_TABLE(LUCENT_X_TEXT)
#undef LUCENT_X_TEXT
};

const char *lucent_status_string(lucent_status status)
{
    if ((unsigned)status >= LUCENT_STATUS_COUNT) return "unknown status";
    return k_status_text[status];
}

lucent_status lucent_error_v(lucent_status status, const char *fmt, va_list ap)
{
    t_status = status;
    vsnprintf(t_message, sizeof t_message, fmt, ap);
    return status;
}

lucent_status lucent_error(lucent_status status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    lucent_error_v(status, fmt, ap);
    va_end(ap);
    return status;
}

lucent_status lucent_error_context(lucent_status status, const char *fmt, ...)
{
    char prefix[ERROR_MESSAGE_MAX];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(prefix, sizeof prefix, fmt, ap);
    va_end(ap);
    if (n < 0) n = 0;
    char old[ERROR_MESSAGE_MAX];
    memcpy(old, t_message, sizeof old);
    if (snprintf(t_message, sizeof t_message, "%s: %s", prefix, old[0] ? old : lucent_status_string(status)) >=
        (int)sizeof t_message)
        strcpy(t_message + sizeof t_message - 4, "..."); /* truncated: say so */
    t_status = status;
    return status;
}

const char *lucent_last_error(void) { return t_message; }

lucent_status lucent_last_status(void) { return t_status; }

void lucent_clear_error(void)
{
    t_message[0] = '\0';
    t_status = LUCENT_OK;
}
