/* Data files compiled into the binary at build time (see cmake/embed.c). */
#ifndef LUCENT_SRC_BASE_EMBEDDED_H
#define LUCENT_SRC_BASE_EMBEDDED_H

#include <stddef.h>

typedef struct lucent_embedded_file {
    const char *name;          /* path relative to the source tree: "data/materials.json" */
    const unsigned char *data; /* NUL-terminated */
    size_t size;               /* without the terminating NUL */
} lucent_embedded_file;

extern const lucent_embedded_file lucent_embedded_files[]; /* ends with a NULL name */

/* Returns the embedded file of that name, or NULL. */
const lucent_embedded_file *lucent_embedded(const char *name);

#endif
