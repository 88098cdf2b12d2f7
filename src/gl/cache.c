/* The disk cache of the renderer's Monte Carlo results (sigma0 fits, slab transmittances): one JSON
 * file per result, DIR/PREFIX-<FNV-1a of the key>.json, holding the full key, so that a changed
 * material, setting or photon count misses. Written atomically; a file that cannot be read, or holds
 * another key, is a miss; failures to write are warnings, never errors. */
#include <string.h>

#include "base/json.h"
#include "gl/renderer_internal.h"

/* FNV-1a, 64 bits: the cache file's name. */
static uint64_t hash(const char *text)
{
    uint64_t h = 1469598103934665603ull;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) h = (h ^ *p) * 1099511628211ull;
    return h;
}

void gl_cache_path(const char *dir, const char *prefix, const char *key, char *dest, size_t size)
{
    snprintf(dest, size, "%s/%s-%016llx.json", dir, prefix, (unsigned long long)hash(key));
}

bool gl_cache_read(const char *path, const char *key, const char *field, int count, double *dest)
{
    cJSON *json = NULL;
    if (lucent_json_parse_file(path, &json) != LUCENT_OK) return lucent_clear_error(), false;
    lucent_json_node root = lucent_json_root(json, path, "");
    const char *stored = NULL;
    bool ok = lucent_json_string(&root, "key", &stored) == LUCENT_OK && !strcmp(stored, key) &&
              lucent_json_numbers(&root, field, count, false, dest) == LUCENT_OK;
    cJSON_Delete(json);
    lucent_clear_error();
    return ok;
}

void gl_cache_write(const char *dir, const char *path, const char *key, cJSON *json)
{
    if (!json) return;
    if (lucent_mkdir_p(dir) != LUCENT_OK) {
        lucent_log(LUCENT_LOG_WARN, "cache: %s", lucent_last_error());
        lucent_clear_error();
    } else {
        cJSON_AddStringToObject(json, "key", key);
        if (lucent_json_write_file(path, json) != LUCENT_OK) {
            lucent_log(LUCENT_LOG_WARN, "cache: %s", lucent_last_error());
            lucent_clear_error();
        }
    }
    cJSON_Delete(json);
}
