/* A growable text buffer for writers of text formats (SVG, HTML, CSV). Appending never
 * fails loudly: on out-of-memory the buffer remembers it, and lucent_strbuf_finish reports. */
#ifndef LUCENT_SRC_BASE_STRBUF_H
#define LUCENT_SRC_BASE_STRBUF_H

#include "lucent/base.h"

typedef struct lucent_strbuf {
    char *data;
    size_t len, cap;
    bool failed;
} lucent_strbuf;

/* Appends formatted text. */
void lucent_strbuf_printf(lucent_strbuf *b, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* Appends text with &, <, >, " and ' escaped for XML. */
void lucent_strbuf_xml(lucent_strbuf *b, const char *text);

/* Hands over the text (*dest, free with free()) or reports out-of-memory; resets b. */
lucent_status lucent_strbuf_finish(lucent_strbuf *b, char **dest);

#endif
