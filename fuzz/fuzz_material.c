/* libFuzzer target: material JSON (lucent_material_parse). */
#include "fuzz.h"
#include "lucent/material.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    lucent_material *m = NULL;
    int n = 0;
    if (lucent_material_parse(text, "fuzz.json", &m, &n) == LUCENT_OK) {
        lucent_material_derived d;
        for (int i = 0; i < n; i++) lucent_material_derive(&m[i], &d);
    }
    free(m);
    free(text);
    return 0;
}
