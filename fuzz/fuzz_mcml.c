/* libFuzzer target: MCML input files (lucent_mcml_parse) and output files (lucent_mco_parse),
 * the same bytes through both. */
#include "fuzz.h"
#include "lucent/mc.h"
#include "lucent/mcml.h"

int LLVMFuzzerTestOneInput(const unsigned char *data, size_t size)
{
    char *text = fuzz_text(data, size);
    if (!text) return 0;
    lucent_mcml_file f;
    memset(&f, 0, sizeof f);
    if (lucent_mcml_parse(text, "fuzz.mci", &f) == LUCENT_OK) lucent_mcml_file_free(&f);
    lucent_mco m;
    if (lucent_mco_parse(text, "fuzz.mco", &m) == LUCENT_OK) lucent_mco_free(&m);
    free(text);
    return 0;
}
