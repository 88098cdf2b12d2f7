/* libFuzzer target: glTF scenes (lucent_scene_parse_gltf: .gltf text or .glb bytes from memory, meshes
 * read from data URIs and the BIN chunk; external files refused), through the material mapping and the
 * JSON scene reader. */
#include "fuzz.h"
#include "lucent/scene.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    lucent_scene *sc = NULL;
    if (lucent_scene_parse_gltf(data, size, "fuzz.gltf", NULL, NULL, &sc) == LUCENT_OK) lucent_scene_destroy(sc);
    return 0;
}
