/* libFuzzer target: image readers (PNG, EXR, PFM) on bytes written to a temporary file;
 * the first byte picks the format. */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "fuzz.h"
#include "lucent/image.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static const char *const ext[] = {"png", "exr", "pfm"};
    if (size < 1) return 0;
    char path[64];
    snprintf(path, sizeof path, "/tmp/lucent-fuzz-%d.%s", (int)getpid(), ext[data[0] % 3]);
    FILE *f = fopen(path, "wb");
    if (!f) return 0;
    fwrite(data + 1, 1, size - 1, f);
    fclose(f);
    lucent_image *img = NULL;
    if (lucent_image_load(path, &img) == LUCENT_OK) lucent_image_destroy(img);
    unlink(path);
    return 0;
}
