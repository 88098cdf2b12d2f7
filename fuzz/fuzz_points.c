/* libFuzzer target: point clouds as a scene's "points" reads them (lucent_surfels_load: plain clouds with
 * normals, colour and radius, 3D Gaussian splatting files; each point checked as it is read), through a
 * temporary file since the loader takes paths; plain or gzip as the bytes say (issue 32). */
#include <stdio.h>
#include <unistd.h>

#include "fuzz.h"
#include "lucent/mesh.h"
#include "lucent/surfels.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char path[64];
    snprintf(path, sizeof path, "/tmp/lucent-fuzz-points-%d.ply", (int)getpid());
    FILE *fp = fopen(path, "wb");
    if (!fp) return 0;
    size_t put = fwrite(data, 1, size, fp);
    if (fclose(fp) != 0 || put != size) return 0;
    lucent_mesh_set_read_limit(1 << 16); /* bounded work per input: the neighbour search grows with the points */
    lucent_surfels *sf = NULL;
    if (lucent_surfels_load(path, &(lucent_surfels_desc){.max_levels = 2}, &sf) == LUCENT_OK) {
        for (size_t i = 0; i < sf->count; i++)
            if (!(sf->radii[i] > 0)) __builtin_trap(); /* every surfel drawable */
        lucent_surfels_destroy(sf);
    }
    unlink(path);
    return 0;
}
