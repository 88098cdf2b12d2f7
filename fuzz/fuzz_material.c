/* libFuzzer target: material JSON (lucent_material_parse), a spectral skin's fields included: what
 * parses is derived, written back and read again, and a skin is resolved (lucent/skin.h). */
#include "fuzz.h"
#include "lucent/material.h"
#include "lucent/skin.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    lucent_material *m = NULL;
    int n = 0;
    if (lucent_material_parse(text, "fuzz.json", &m, &n) == LUCENT_OK) {
        lucent_material_derived d;
        for (int i = 0; i < n; i++) {
            if (lucent_skin_resolve(&m[i]) == LUCENT_OK) lucent_material_derive(&m[i], &d);
        }
        char *json = NULL;
        lucent_material *back = NULL;
        int count = 0;
        if (lucent_material_to_json(m, n, true, &json) == LUCENT_OK &&
            (lucent_material_parse(json, "back.json", &back, &count) != LUCENT_OK || count != n))
            abort(); /* what Lucent writes, it reads back */
        free(back);
        free(json);
    }
    free(m);
    free(text);
    return 0;
}
