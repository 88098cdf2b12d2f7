/* libFuzzer target: `lucent view --script` files, checked whole as the viewer does before running
 * one (viewer/script_parse.c: no window, no renderer). Material names are looked up among the
 * presets only (no file is read): the context's resolve_materials is off. */
#include "../viewer/script.h"
#include "fuzz.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    viewer_script s;
    viewer_script_context ctx = {.light_count = 2, .object_count = 3, .window = size % 2};
    if (viewer_script_parse((const char *)data, size, "fuzz.txt", &ctx, &s) == LUCENT_OK) viewer_script_free(&s);
    return 0;
}
