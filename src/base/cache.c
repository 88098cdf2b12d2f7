/* The disk cache of computed results (lucent/base.h): one JSON file per result,
 * DIR/PREFIX-<FNV-1a of the key>.json, holding the full key, so that a changed material, setting or
 * photon count misses. Written atomically; a file that cannot be read, or holds another key, is a
 * miss; failures to write are warnings, never errors. */
#include <stdlib.h>
#include <string.h>

#include "base/json.h"

struct lucent_cache {
    char dir[1024];
};

lucent_status lucent_cache_create(const char *dir, lucent_cache **dest)
{
    *dest = NULL;
    if (!dir || !dir[0] || strlen(dir) >= sizeof((lucent_cache *)0)->dir)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "cache: the folder name is empty or too long");
    lucent_cache *c = calloc(1, sizeof *c);
    if (!c) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    snprintf(c->dir, sizeof c->dir, "%s", dir);
    *dest = c;
    return LUCENT_OK;
}

void lucent_cache_destroy(lucent_cache *cache) { free(cache); }

/* FNV-1a, 64 bits: the cache file's name. */
static uint64_t hash(const char *text)
{
    uint64_t h = 1469598103934665603ull;
    for (const unsigned char *p = (const unsigned char *)text; *p; p++) h = (h ^ *p) * 1099511628211ull;
    return h;
}

static void entry_path(const lucent_cache *c, const char *prefix, const char *key, char *dest, size_t size)
{
    snprintf(dest, size, "%s/%s-%016llx.json", c->dir, prefix, (unsigned long long)hash(key));
}

bool lucent_cache_get(const lucent_cache *cache, const char *prefix, const char *key, const char *field, int count,
                      double *dest)
{
    char path[1200];
    cJSON *json = NULL;
    if (!cache) return false;
    entry_path(cache, prefix, key, path, sizeof path);
    if (lucent_json_parse_file(path, &json) != LUCENT_OK) return lucent_clear_error(), false;
    lucent_json_node root = lucent_json_root(json, path, "");
    const char *stored = NULL;
    bool ok = lucent_json_string(&root, "key", &stored) == LUCENT_OK && !strcmp(stored, key) &&
              lucent_json_numbers(&root, field, count, false, dest) == LUCENT_OK;
    cJSON_Delete(json);
    lucent_clear_error();
    return ok;
}

static void write_entry(const lucent_cache *c, const char *path, cJSON *json)
{
    if (lucent_mkdir_p(c->dir) != LUCENT_OK) {
        lucent_log(LUCENT_LOG_WARN, "cache: %s", lucent_last_error());
        lucent_clear_error();
    } else if (lucent_json_write_file_direct(path, json) != LUCENT_OK) {
        lucent_log(LUCENT_LOG_WARN, "cache: %s", lucent_last_error());
        lucent_clear_error();
    }
}

void lucent_cache_put(lucent_cache *cache, const char *prefix, const char *key, const lucent_cache_field *fields,
                      int count)
{
    char path[1200];
    if (!cache) return;
    cJSON *json = cJSON_CreateObject();
    bool ok = json != NULL;
    for (int i = 0; ok && i < count; i++)
        ok = lucent_json_add_numbers(json, fields[i].name, fields[i].values, fields[i].count);
    ok = ok && cJSON_AddStringToObject(json, "key", key);
    entry_path(cache, prefix, key, path, sizeof path);
    if (ok)
        write_entry(cache, path, json);
    else
        lucent_log(LUCENT_LOG_WARN, "cache: out of memory writing %s", path);
    cJSON_Delete(json);
}
