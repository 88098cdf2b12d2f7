/* libFuzzer target: scene JSON (lucent_scene_parse, meshes not loaded), then the same input as one
 * --set override ("key=value") of a valid scene. */
#include "fuzz.h"
#include "lucent/scene.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    lucent_scene *sc = NULL;
    lucent_scene_load_desc d = {.skip_meshes = true};
    if (lucent_scene_parse(text, "fuzz.json", NULL, &d, &sc) == LUCENT_OK) lucent_scene_destroy(sc);
    /* The same text as one override of a valid scene: "key=value". */
    const char *base = "{\"camera\": {\"position\": [0, 0, 50], \"target\": [0, 0, 0]},"
                       " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1]}],"
                       " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 1},"
                       " \"material\": \"skin1\"}]}";
    const char *ov[] = {text};
    lucent_scene_load_desc od = {.skip_meshes = true, .overrides = ov, .override_count = 1};
    sc = NULL;
    if (lucent_scene_parse(base, "base.json", NULL, &od, &sc) == LUCENT_OK) lucent_scene_destroy(sc);
    free(text);
    return 0;
}
