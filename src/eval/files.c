/* Paths, folders and events for the evaluations' outputs. */
#include <stdarg.h>
#include <stdio.h>

#include "eval/internal.h"

lucent_status eval_path_printf(char *dest, size_t size, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(dest, size, fmt, ap);
    va_end(ap);
    if (n < 0 || (size_t)n >= size) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%.60s...: path too long", dest);
    return LUCENT_OK;
}

lucent_status eval_make_dirs(const char *path) { return lucent_mkdir_p(path); }

void eval_file_stem(const char *name, char *dest, size_t size)
{
    snprintf(dest, size, "%s", name);
    for (char *p = dest; *p; p++)
        if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || (*p >= '0' && *p <= '9') || *p == '-')) *p = '-';
}

lucent_status eval_wrote(lucent_eval_event_fn on_event, void *user, lucent_status s, const char *path)
{
    if (s == LUCENT_OK && on_event) on_event(&(lucent_eval_event){.kind = LUCENT_EVAL_WROTE, .path = path}, user);
    return s;
}
