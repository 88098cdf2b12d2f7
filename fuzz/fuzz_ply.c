/* libFuzzer target: the PLY property API (lucent_ply_open_memory, lucent_ply_read) with optional faces,
 * a property that may be missing, and float or double output, as a point-cloud reader calls it. */
#include "fuzz.h"
#include "lucent/mesh.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    lucent_ply *ply;
    if (lucent_ply_open_memory(data, size, "fuzz.ply", &ply) != LUCENT_OK) return 0;
    int n = lucent_ply_property_count(ply);
    for (int i = 0; i < n; i++)
        if (lucent_ply_property_index(ply, lucent_ply_property_name(ply, i)) < 0) __builtin_trap();
    static const char *const names[] = {"x", "y", "z", "red", "opacity", "f_dc_0"};
    lucent_ply_data d;
    lucent_ply_read_desc desc = {
        .names = names, .count = 6, .allow_missing = 1, .single = (int)(size & 1), .faces = LUCENT_PLY_FACES_OPTIONAL};
    if (lucent_ply_read(ply, &desc, &d) == LUCENT_OK) {
        for (size_t t = 0; t < 3 * d.triangle_count; t++)
            if (d.triangles[t] >= d.vertex_count) __builtin_trap();
        lucent_ply_data_free(&d);
    }
    lucent_ply_close(ply);
    return 0;
}
