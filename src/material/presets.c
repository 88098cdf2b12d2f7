/* The presets: the measured table of Jensen et al. 2001 (data/materials.json, compiled into
 * the binary). Parsed once, on first use, by whichever thread comes first. */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/embedded.h"
#include "lucent/material.h"

#define PRESETS_FILE "data/materials.json"

static pthread_once_t g_once = PTHREAD_ONCE_INIT;
static lucent_material *g_presets;
static int g_count;
static char g_failure[512]; /* why the table could not be read ("" when it could) */

static void load_presets(void)
{
    const lucent_embedded_file *f = lucent_embedded(PRESETS_FILE);
    if (!f) {
        snprintf(g_failure, sizeof g_failure, "%s is not built into this binary", PRESETS_FILE);
        return;
    }
    if (lucent_material_parse((const char *)f->data, PRESETS_FILE " (built in)", &g_presets, &g_count) != LUCENT_OK)
        snprintf(g_failure, sizeof g_failure, "%s", lucent_last_error());
    lucent_clear_error();
}

static lucent_status presets_ready(void)
{
    pthread_once(&g_once, load_presets);
    if (g_failure[0]) return lucent_error(LUCENT_ERR_INTERNAL, "%s", g_failure);
    return LUCENT_OK;
}

int lucent_material_preset_count(void) { return presets_ready() == LUCENT_OK ? g_count : 0; }

lucent_status lucent_material_preset(int index, lucent_material *dest)
{
    lucent_status s = presets_ready();
    if (s != LUCENT_OK) return s;
    if (index < 0 || index >= g_count)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "preset index %d out of range [0, %d)", index, g_count);
    *dest = g_presets[index];
    return LUCENT_OK;
}

lucent_status lucent_material_preset_find(const char *name, lucent_material *dest)
{
    if (!name) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "material: no preset name given (NULL)");
    lucent_status s = presets_ready();
    if (s != LUCENT_OK) return s;
    char list[512] = "";
    for (int i = 0; i < g_count; i++) {
        if (strcasecmp(g_presets[i].name, name) == 0) {
            *dest = g_presets[i];
            return LUCENT_OK;
        }
        size_t len = strlen(list);
        snprintf(list + len, sizeof list - len, "%s%s", i ? ", " : "", g_presets[i].name);
    }
    return lucent_error(LUCENT_ERR_NOT_FOUND, "unknown material \"%s\" (presets: %s)", name, list);
}
