/* libFuzzer target: compare's reference.json (what --reference DIR reads back), parsed against the
 * test sphere's scene (meshes not loaded): the identity check and the numbers, no images. */
#include "eval/internal.h"
#include "fuzz.h"
#include "lucent/scene.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    static lucent_scene *scene;
    if (!scene) {
        const char *base =
            "{\"name\": \"test-sphere\", \"camera\": {\"position\": [0, 0, 60], \"target\": [0, 0, 0],"
            " \"fov_y\": 30}, \"lights\": [{\"type\": \"directional\", \"direction\": [0.6, -0.3, -0.7],"
            " \"intensity\": 3}, {\"type\": \"environment\", \"intensity\": 0.05}], \"objects\": [{\"mesh\":"
            " {\"primitive\": \"icosphere\", \"radius\": 10, \"subdivisions\": 3}, \"material\": \"skin1\","
            " \"sigma0\": [3.5, 2.3, 1.5]}], \"render\": {\"width\": 48, \"height\": 40}}";
        lucent_scene_load_desc d = {.skip_meshes = true};
        if (lucent_scene_parse(base, "base.json", NULL, &d, &scene) != LUCENT_OK) return 0;
    }
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    eval_reference r;
    if (eval_reference_parse(text, "reference.json", scene, &r) == LUCENT_OK) eval_reference_free(&r);
    free(text);
    return 0;
}
