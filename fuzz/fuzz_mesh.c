/* libFuzzer target: mesh import through lucent_mesh_load_memory, the first byte picking the format
 * (PLY and OBJ through Lucent's readers; STL, OFF, glTF and GLB through assimp in its child process),
 * the rest the file's bytes (gzip included: the readers inflate what starts with the gzip magic). */
#include "fuzz.h"
#include "lucent/mesh.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static const char *const formats[] = {"ply", "obj", "ply", "obj", "stl", "off", "gltf", "glb"};
    if (size < 2) return 0;
    /* The assimp formats fork a child per input: 2 of 8 choices only, to keep the executions fast. */
    const char *format = formats[data[0] % 8];
    lucent_mesh *m = NULL;
    if (lucent_mesh_load_memory(data + 1, size - 1, "fuzz", &(lucent_mesh_load_desc){.format = format}, &m) ==
        LUCENT_OK)
        lucent_mesh_destroy(m);
    return 0;
}
