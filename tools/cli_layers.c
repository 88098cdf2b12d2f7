/* --layers MATERIAL:THICKNESS,...: the layered slab of `lucent profile` and `lucent fit`. */
#include <math.h>
#include <string.h>

#include "cli.h"

/* One layer "MATERIAL:THICKNESS" (mm, or "inf"); the material may itself contain ':'. */
static lucent_status parse_layer(const char *text, lucent_layer *dest)
{
    const char *colon = strrchr(text, ':');
    char spec[512];
    double d;
    if (!colon || colon == text || (size_t)(colon - text) >= sizeof spec)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--layers: '%s': expected MATERIAL:THICKNESS", text);
    memcpy(spec, text, (size_t)(colon - text));
    spec[colon - text] = '\0';
    if (strcmp(colon + 1, "inf") == 0)
        d = INFINITY;
    else if (!cli_parse_double(colon + 1, &d) || !(d > 0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--layers: '%s': thickness must be > 0 mm or 'inf'", text);
    *dest = (lucent_layer){.slab = {.thickness = d}};
    lucent_status s = lucent_material_resolve(spec, &dest->material);
    return s == LUCENT_OK ? s : lucent_error_context(s, "--layers");
}

lucent_status cli_parse_layers(const char *list, lucent_layer *dest, int max, int *count)
{
    char buf[2048];
    snprintf(buf, sizeof buf, "%s", list);
    *count = 0;
    for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (*count == max) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--layers: at most %d layers", max);
        lucent_status s = parse_layer(t, &dest[(*count)++]);
        if (s != LUCENT_OK) return s;
    }
    if (*count == 0) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--layers: no layer given");
    for (int i = 0; i + 1 < *count; i++)
        if (isinf(dest[i].slab.thickness))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--layers: only the last layer may be 'inf'");
    return LUCENT_OK;
}
