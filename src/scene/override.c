/* `--set key=value`: overrides applied to a scene document before it is read, so that a changed
 * value is checked exactly like one written in the file. */
#include <ctype.h>
#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "scene/internal.h"

/* The value: JSON when the whole text parses as JSON, else the text as a string. */
static cJSON *override_value(const char *text)
{
    const char *end = NULL;
    cJSON *v = cJSON_ParseWithOpts(text, &end, true);
    if (v) return v;
    return cJSON_CreateString(text);
}

/* Reads one path segment "name" or "name[i][j]": copies name and returns the position after it. */
static const char *segment_name(const char *p, char *name, size_t size)
{
    size_t n = 0;
    while (*p && *p != '.' && *p != '[') {
        if (n + 1 < size) name[n++] = *p;
        p++;
    }
    name[n] = '\0';
    return p;
}

static lucent_status bad(const char *file, const char *ov, const char *why)
{
    char shown[1024];
    lucent_json_printable(ov, shown, sizeof shown);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: override '%s': %s", file, shown, why);
}

/* Walks the indices "[i]..." after a member; *node becomes the element. */
static lucent_status walk_indices(const char **pp, cJSON **node, const char *file, const char *ov)
{
    const char *p = *pp;
    while (*p == '[') {
        char *end;
        long i = strtol(p + 1, &end, 10);
        if (end == p + 1 || *end != ']' || i < 0) return bad(file, ov, "expected [index]");
        /* cJSON indexes with an int: a larger index must not wrap (4294967296 to 0). */
        if (i > INT_MAX) return bad(file, ov, "index beyond the end of the array");
        if (!cJSON_IsArray(*node)) return bad(file, ov, "indexes something that is not an array");
        cJSON *e = cJSON_GetArrayItem(*node, (int)i);
        if (!e) return bad(file, ov, "index beyond the end of the array");
        *node = e;
        p = end + 1;
    }
    *pp = p;
    return LUCENT_OK;
}

/* Sets member `name` of object parent to value (replacing or adding). */
static lucent_status set_member(cJSON *parent, const char *name, cJSON *value, const char *file, const char *ov)
{
    if (!cJSON_IsObject(parent)) return cJSON_Delete(value), bad(file, ov, "its parent is not an object");
    if (cJSON_GetObjectItemCaseSensitive(parent, name))
        cJSON_ReplaceItemInObjectCaseSensitive(parent, name, value);
    else
        cJSON_AddItemToObject(parent, name, value);
    return LUCENT_OK;
}

static lucent_status apply_one(cJSON *root, const char *file, const char *ov)
{
    const char *eq = strchr(ov, '=');
    if (!eq || eq == ov) return bad(file, ov, "expected key=value");
    char *key = strndup(ov, (size_t)(eq - ov));
    if (!key) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    cJSON *node = root;
    const char *p = key;
    lucent_status s = LUCENT_OK;
    char name[128];
    while (s == LUCENT_OK) {
        p = segment_name(p, name, sizeof name);
        if (!name[0]) {
            s = bad(file, ov, "empty name in the key");
            break;
        }
        cJSON *child = cJSON_IsObject(node) ? cJSON_GetObjectItemCaseSensitive(node, name) : NULL;
        if (*p == '\0') { /* the last segment: set it */
            cJSON *v = override_value(eq + 1);
            s = v ? set_member(node, name, v, file, ov) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
            break;
        }
        if (!child && *p == '.' && cJSON_IsObject(node)) /* "render.taps" without a render object */
            child = cJSON_AddObjectToObject(node, name);
        if (!child) {
            s = bad(file, ov, "no such member in the scene");
            break;
        }
        node = child;
        if ((s = walk_indices(&p, &node, file, ov)) != LUCENT_OK) break;
        if (*p == '\0') {
            s = bad(file, ov, "the key ends in an index; name a member");
            break;
        }
        if (*p++ != '.') s = bad(file, ov, "expected '.' after ']'");
    }
    free(key);
    return s;
}

lucent_status scene_apply_overrides(cJSON *root, const char *file, const char *const *overrides, int count)
{
    for (int i = 0; i < count; i++) {
        lucent_status s = apply_one(root, file, overrides[i]);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}
