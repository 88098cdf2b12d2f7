/* libFuzzer target: MCML input files (lucent_mcml_parse). */
#include "fuzz.h"
#include "lucent/mc.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    lucent_mcml_file f;
    memset(&f, 0, sizeof f);
    if (lucent_mcml_parse(text, "fuzz.mci", &f) == LUCENT_OK) lucent_mcml_file_free(&f);
    free(text);
    return 0;
}
