/* libFuzzer target: gzip-compressed PLY (.ply.gz) through the mesh readers' gzip source (issue 32). The first
 * byte picks how the rest is fed: even, the rest is compressed here into one gzip member (so the fuzzer explores
 * PLY text and binary bodies behind valid gzip framing, the inflate-ratio limit included); odd, the rest is fed
 * as it is, when it starts with the gzip magic (the framing itself: header flags, the deflate stream, the CRC
 * and length trailer, members that end early). Both as a mesh and through the property API. */
#include <zlib.h>

#include "fuzz.h"
#include "lucent/mesh.h"

static void read_ply(const unsigned char *data, size_t size)
{
    lucent_mesh *m = NULL;
    if (lucent_mesh_load_memory(data, size, "fuzz.ply.gz", &(lucent_mesh_load_desc){.format = "ply"}, &m) ==
        LUCENT_OK) {
        for (size_t t = 0; t < 3 * m->face_count; t++)
            if (m->faces[t] >= m->vertex_count) __builtin_trap();
        lucent_mesh_destroy(m);
    }
    lucent_ply *ply;
    if (lucent_ply_open_memory(data, size, "fuzz.ply.gz", &ply) != LUCENT_OK) return;
    static const char *const names[] = {"x", "y", "z", "nx", "radius"};
    lucent_ply_data d;
    lucent_ply_read_desc desc = {.names = names, .count = 5, .allow_missing = 1, .single = 1};
    if (lucent_ply_read(ply, &desc, &d) == LUCENT_OK) lucent_ply_data_free(&d);
    lucent_ply_close(ply);
}

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    if (size < 1) return 0;
    lucent_mesh_set_read_limit(1 << 16); /* the limit's own check, and bounded work per input */
    if (data[0] & 1) {
        if (size >= 3 && data[1] == 0x1f && data[2] == 0x8b) read_ply(data + 1, size - 1);
        return 0;
    }
    size_t cap = compressBound((uLong)(size - 1)) + 32;
    unsigned char *gz = malloc(cap);
    z_stream z = {0};
    if (!gz || deflateInit2(&z, 6, Z_DEFLATED, 16 + MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK) {
        free(gz);
        return 0;
    }
    z.next_in = (unsigned char *)data + 1, z.avail_in = (uInt)(size - 1);
    z.next_out = gz, z.avail_out = (uInt)cap;
    if (deflate(&z, Z_FINISH) == Z_STREAM_END) read_ply(gz, z.total_out);
    deflateEnd(&z);
    free(gz);
    return 0;
}
