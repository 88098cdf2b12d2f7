/* Shared by the libFuzzer targets (fuzz/build.sh). */
#ifndef LUCENT_FUZZ_H
#define LUCENT_FUZZ_H

#include <stdlib.h>
#include <string.h>

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size);

/* The input as a NUL-terminated string for the text parsers (free it); NULL when out of memory. */
static inline char *fuzz_text(const unsigned char *data, size_t size)
{
    char *text = malloc(size + 1);
    if (text) memcpy(text, data, size), text[size] = '\0';
    return text;
}

#endif
