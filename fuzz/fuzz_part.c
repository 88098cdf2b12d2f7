/* libFuzzer target: the part files of `lucent ... --part K/N` as `lucent merge` reads them
 * (lucent_dist_merge_load: header, the recorded command line, the tallies), through a file since
 * the reader takes paths. lucent_dist_finish frees what a successful load kept. */
#include <stdio.h>
#include <unistd.h>

#include "fuzz.h"
#include "lucent/dist.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/lucent-fuzz-part-%d", (int)getpid());
    FILE *fp = fopen(path, "wb");
    if (!fp) return 0;
    size_t put = fwrite(data, 1, size, fp);
    if (fclose(fp) != 0 || put != size) return 0;
    const char *paths[1] = {path};
    int argc = 0;
    char **argv = NULL;
    if (lucent_dist_merge_load(paths, 1, &argc, &argv) == LUCENT_OK) lucent_dist_merge_check_used();
    lucent_dist_finish(0);
    unlink(path);
    return 0;
}
