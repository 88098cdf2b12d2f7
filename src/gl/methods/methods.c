/* The table of the renderer's methods, indexed by lucent_render_method, and the method names and
 * variants of lucent/settings.h, read from it. */
#include <string.h>
#include <strings.h>

#include "gl/methods/method.h"

extern const gl_method gl_method_lambert, gl_method_cdrf, gl_method_cdrf_translucency, gl_method_ssss;

const gl_method *const gl_methods[LUCENT_METHOD_COUNT] = {
    [LUCENT_METHOD_LAMBERT] = &gl_method_lambert,
    [LUCENT_METHOD_CDRF] = &gl_method_cdrf,
    [LUCENT_METHOD_CDRF_TRANSLUCENCY] = &gl_method_cdrf_translucency,
    [LUCENT_METHOD_SSSS] = &gl_method_ssss,
};

const char *lucent_render_method_name(lucent_render_method method)
{
    return method >= 0 && method < LUCENT_METHOD_COUNT ? gl_methods[method]->name : "unknown";
}

/* "lambert, cdrf, ..., ssss:<model>[rank]": the names and the variants' forms. */
static void method_list(char *dest, size_t size, bool variants_only)
{
    dest[0] = '\0';
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        if (!variants_only) snprintf(dest + strlen(dest), size - strlen(dest), "%s%s", m ? ", " : "", gl_methods[m]->name);
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        if (gl_methods[m]->variant)
            snprintf(dest + strlen(dest), size - strlen(dest), "%s%s:%s", dest[0] ? ", " : "", gl_methods[m]->name,
                     gl_methods[m]->variant_doc);
}

const char *lucent_render_method_setting(lucent_render_method method, int index)
{
    if (method < 0 || method >= LUCENT_METHOD_COUNT || index < 0) return NULL;
    const char *const *k = gl_methods[method]->settings;
    for (int i = 0; k[i]; i++)
        if (i == index) return k[i];
    return NULL;
}

void lucent_render_method_describe(const lucent_render_settings *s, char *dest, size_t size)
{
    dest[0] = '\0';
    const char *key;
    for (int i = 0; (key = lucent_render_method_setting(s->view.method, i)); i++) {
        char value[128];
        lucent_setting_format(s, lucent_setting_find(key, NULL), value, sizeof value);
        snprintf(dest + strlen(dest), size - strlen(dest), "%s%s %s", i ? ", " : "", key, value);
    }
    if (!dest[0]) snprintf(dest, size, "no settings");
}

lucent_status lucent_render_method_parse(const char *text, lucent_render_method *method, lucent_render_settings *s)
{
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++) {
        const gl_method *g = gl_methods[m];
        if (strlen(g->name) != len || strncasecmp(text, g->name, len)) continue;
        if (colon && !g->variant) {
            char list[512];
            method_list(list, sizeof list, true);
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "method '%s': %s takes no variant (only %s)", text, g->name,
                                list);
        }
        lucent_render_settings scratch;
        if (colon && g->variant(colon + 1, s ? s : &scratch) != LUCENT_OK)
            return lucent_error_context(LUCENT_ERR_INVALID_ARGUMENT, "method '%s'", text);
        *method = (lucent_render_method)m;
        return LUCENT_OK;
    }
    char list[512];
    method_list(list, sizeof list, false);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown method '%s' (%s)", text, list);
}
