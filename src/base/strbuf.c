/* Growable text buffer. */
#include <stdlib.h>
#include <string.h>

#include "base/strbuf.h"

static bool reserve(lucent_strbuf *b, size_t extra)
{
    if (b->failed) return false;
    if (b->len + extra + 1 <= b->cap) return true;
    size_t cap = b->cap ? b->cap : 4096;
    while (cap < b->len + extra + 1) cap *= 2;
    char *grown = realloc(b->data, cap);
    if (!grown) {
        b->failed = true;
        return false;
    }
    b->data = grown;
    b->cap = cap;
    return true;
}

void lucent_strbuf_printf(lucent_strbuf *b, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n < 0 || !reserve(b, (size_t)n)) return;
    va_start(ap, fmt);
    vsnprintf(b->data + b->len, (size_t)n + 1, fmt, ap);
    va_end(ap);
    b->len += (size_t)n;
}

void lucent_strbuf_xml(lucent_strbuf *b, const char *text)
{
    for (const char *p = text ? text : ""; *p; p++) {
        switch (*p) {
        case '&': lucent_strbuf_printf(b, "&amp;"); break;
        case '<': lucent_strbuf_printf(b, "&lt;"); break;
        case '>': lucent_strbuf_printf(b, "&gt;"); break;
        case '"': lucent_strbuf_printf(b, "&quot;"); break;
        case '\'': lucent_strbuf_printf(b, "&apos;"); break;
        default: lucent_strbuf_printf(b, "%c", *p);
        }
    }
}

lucent_status lucent_strbuf_finish(lucent_strbuf *b, char **dest)
{
    *dest = NULL;
    if (b->failed || !reserve(b, 0)) {
        free(b->data);
        *b = (lucent_strbuf){0};
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory building text");
    }
    b->data[b->len] = '\0';
    *dest = b->data;
    *b = (lucent_strbuf){0};
    return LUCENT_OK;
}
