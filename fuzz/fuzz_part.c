/* libFuzzer target: the part files of `lucent ... --part K/N` as `lucent merge` reads them
 * (lucent_dist_merge_load: header, the recorded command line, the tallies, the CRC-32 of format v2), through a
 * file since the reader takes paths. The first byte picks: odd, the rest is the file as it is (the checksum
 * refuses nearly every mutation); even, the rest's last 4 bytes are first replaced by the CRC-32 of the others,
 * so that mutations reach the header and tally checks behind the checksum. lucent_dist_finish frees what a
 * successful load kept. */
#include <stdio.h>
#include <unistd.h>
#include <zlib.h>

#include <stdint.h>

#include "fuzz.h"
#include "lucent/dist.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/lucent-fuzz-part-%d", (int)getpid());
    FILE *fp = fopen(path, "wb");
    if (!fp) return 0;
    if (size < 1) return (void)fclose(fp), 0;
    unsigned char *body = malloc(size - 1 + 1);
    if (!body) return (void)fclose(fp), 0;
    memcpy(body, data + 1, size - 1);
    size_t n = size - 1;
    if (!(data[0] & 1) && n >= 4) {
        uint32_t crc = (uint32_t)crc32_z(crc32_z(0, NULL, 0), body, n - 4);
        memcpy(body + n - 4, &crc, 4); /* the part's byte order: the machine's */
    }
    size_t put = fwrite(body, 1, n, fp);
    free(body);
    if (fclose(fp) != 0 || put != n) return 0;
    const char *paths[1] = {path};
    int argc = 0;
    char **argv = NULL;
    if (lucent_dist_merge_load(paths, 1, &argc, &argv) == LUCENT_OK) lucent_dist_merge_check_used();
    lucent_dist_finish(0);
    unlink(path);
    return 0;
}
