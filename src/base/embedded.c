/* Look-up of the data files compiled into the binary. */
#include <string.h>

#include "base/embedded.h"

const lucent_embedded_file *lucent_embedded(const char *name)
{
    for (const lucent_embedded_file *f = lucent_embedded_files; f->name; f++)
        if (strcmp(f->name, name) == 0) return f;
    return NULL;
}
