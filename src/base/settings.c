/* The settings table at work (lucent/settings.h): defaults, the scene reader with its range checks,
 * text in and out, the JSON sidecar, checks of a struct filled by hand, descriptions and listings.
 * Every function here walks the groups of the table it is given (the registry of src/scene/settings.c
 * passes its own); none names a setting, and nothing here knows which groups exist. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/settings_table.h"
#include "base/strbuf.h"

/* ---- members ---- */

static void *member(lucent_render_settings *s, const lucent_setting *k) { return (char *)s + k->offset; }

static const void *cmember(const lucent_render_settings *s, const lucent_setting *k)
{
    return (const char *)s + k->offset;
}

int lucent_settings_choice_index(const char *(*choice)(int), const char *name)
{
    for (int i = 0; choice && choice(i); i++)
        if (!strcasecmp(choice(i), name)) return i;
    return -1;
}

void lucent_settings_choice_list(const char *(*choice)(int), char *dest, size_t size)
{
    dest[0] = '\0';
    for (int i = 0; choice && choice(i); i++)
        snprintf(dest + strlen(dest), size - strlen(dest), "%s%s", i ? ", " : "", choice(i));
}

static void set_default(lucent_render_settings *s, const lucent_setting *k)
{
    void *m = member(s, k);
    switch (k->type) {
    case LUCENT_SETTING_BOOL: *(bool *)m = k->def != 0; break;
    case LUCENT_SETTING_INT: *(int *)m = (int)k->def; break;
    case LUCENT_SETTING_REAL: *(double *)m = k->def; break;
    case LUCENT_SETTING_COLOR:
        for (int c = 0; c < 3; c++) ((double *)m)[c] = k->def;
        break;
    case LUCENT_SETTING_SEED: *(uint64_t *)m = (uint64_t)k->def; break;
    case LUCENT_SETTING_CHOICE: *(int *)m = lucent_settings_choice_index(k->choice, k->def_text); break;
    case LUCENT_SETTING_TEXT: snprintf((char *)m, k->size, "%s", k->def_text); break;
    }
}

lucent_render_settings settings_table_defaults(const settings_table *t)
{
    lucent_render_settings s;
    memset(&s, 0, sizeof s);
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count; i++) set_default(&s, &grp->settings[i]);
    }
    return s;
}

const lucent_setting *settings_table_find(const settings_table *t, const char *key, const lucent_settings_group **group)
{
    if (!strncmp(key, "render.", 7)) key += 7;
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count; i++)
            if (!strcmp(grp->settings[i].key, key)) {
                if (group) *group = grp;
                return &grp->settings[i];
            }
    }
    return NULL;
}

/* ---- range checks: one wording for files, --set and structs filled by hand ---- */

static void range_text(const lucent_setting *k, char *dest, size_t size)
{
    if (isinf(k->hi))
        snprintf(dest, size, "must be >= %g", k->lo);
    else
        snprintf(dest, size, "must be in [%g, %g]", k->lo, k->hi);
}

/* Checks a number read for k; fills why (empty when fine). */
static void check_number(const lucent_setting *k, double v, char *why, size_t size)
{
    why[0] = '\0';
    bool whole = k->type == LUCENT_SETTING_INT || k->type == LUCENT_SETTING_SEED;
    if (!(v >= k->lo && v <= k->hi)) {
        range_text(k, why, size);
        snprintf(why + strlen(why), size - strlen(why), ", got %g", v);
    } else if (whole && v != floor(v)) {
        snprintf(why, size, "must be a whole number, got %g", v);
    } else if ((k->flags & LUCENT_SETTING_ODD) && fmod(v, 2) == 0) {
        snprintf(why, size, "must be odd (a centre tap and pairs), got %g", v);
    }
}

static void check_name(const lucent_setting *k, const char *text, char *why, size_t size)
{
    char list[256];
    why[0] = '\0';
    if (!k->choice || lucent_settings_choice_index(k->choice, text) >= 0) return;
    lucent_settings_choice_list(k->choice, list, sizeof list);
    snprintf(why, size, "unknown value \"%s\" (%s)", text, list);
}

/* ---- text in ---- */

static lucent_status set_number(lucent_render_settings *s, const lucent_setting *k, const double *v, int n, char *why,
                                size_t size)
{
    void *m = member(s, k);
    for (int i = 0; i < n && !why[0]; i++) check_number(k, v[i], why, size);
    if (why[0]) return LUCENT_ERR_PARSE;
    if (k->type == LUCENT_SETTING_INT)
        *(int *)m = (int)v[0];
    else if (k->type == LUCENT_SETTING_REAL)
        *(double *)m = v[0];
    else if (k->type == LUCENT_SETTING_SEED)
        *(uint64_t *)m = (uint64_t)v[0];
    else
        for (int c = 0; c < 3; c++) ((double *)m)[c] = v[n == 3 ? c : 0];
    return LUCENT_OK;
}

/* Sets k from text; on a bad value fills why and returns LUCENT_ERR_PARSE. */
static lucent_status set_text(lucent_render_settings *s, const lucent_setting *k, const char *text, char *why,
                              size_t size)
{
    why[0] = '\0';
    if (k->parse) {
        lucent_status st = k->parse(text, s);
        if (st != LUCENT_OK) snprintf(why, size, "%s", lucent_last_error());
        return st;
    }
    void *m = member(s, k);
    if (k->type == LUCENT_SETTING_CHOICE || k->type == LUCENT_SETTING_TEXT) {
        check_name(k, text, why, size);
        if (!why[0] && k->type == LUCENT_SETTING_TEXT && strlen(text) >= k->size)
            snprintf(why, size, "at most %zu characters", k->size - 1);
        if (why[0]) return LUCENT_ERR_PARSE;
        if (k->type == LUCENT_SETTING_CHOICE)
            *(int *)m = lucent_settings_choice_index(k->choice, text);
        else
            snprintf((char *)m, k->size, "%s", text);
        return LUCENT_OK;
    }
    if (k->type == LUCENT_SETTING_BOOL) {
        bool t = !strcasecmp(text, "true") || !strcmp(text, "1"), f = !strcasecmp(text, "false") || !strcmp(text, "0");
        if (!t && !f) return snprintf(why, size, "expected true or false, got \"%s\"", text), LUCENT_ERR_PARSE;
        *(bool *)m = t;
        return LUCENT_OK;
    }
    double v[3];
    int n = 0;
    for (const char *p = text; n < 3;) {
        char *end;
        v[n++] = strtod(p, &end);
        if (end == p || !isfinite(v[n - 1]))
            return snprintf(why, size, "expected a number, got \"%s\"", text), LUCENT_ERR_PARSE;
        p = end + strspn(end, " ");
        if (*p != ',') break;
        p++;
    }
    if (n != 1 && !(n == 3 && k->type == LUCENT_SETTING_COLOR))
        return snprintf(why, size, "expected %s, got \"%s\"",
                        k->type == LUCENT_SETTING_COLOR ? "1 or 3 numbers" : "a number", text),
               LUCENT_ERR_PARSE;
    return set_number(s, k, v, n, why, size);
}

lucent_status lucent_setting_set(lucent_render_settings *s, const lucent_setting *k, const char *text)
{
    char why[512];
    lucent_status st = set_text(s, k, text, why, sizeof why);
    return st == LUCENT_OK ? st : lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render.%s: %s", k->key, why);
}

/* ---- text out ---- */

/* The shortest of %.15g, %.17g that reads back exactly. */
static void format_real(double v, char *dest, size_t size)
{
    snprintf(dest, size, "%.15g", v);
    if (strtod(dest, NULL) != v) snprintf(dest, size, "%.17g", v);
}

void lucent_setting_format(const lucent_render_settings *s, const lucent_setting *k, char *dest, size_t size)
{
    const void *m = cmember(s, k);
    const char *name;
    switch (k->type) {
    case LUCENT_SETTING_BOOL: snprintf(dest, size, "%s", *(const bool *)m ? "true" : "false"); break;
    case LUCENT_SETTING_INT: snprintf(dest, size, "%d", *(const int *)m); break;
    case LUCENT_SETTING_REAL: format_real(*(const double *)m, dest, size); break;
    case LUCENT_SETTING_SEED: snprintf(dest, size, "%llu", (unsigned long long)*(const uint64_t *)m); break;
    case LUCENT_SETTING_COLOR: {
        const double *c = m;
        char v[3][32];
        for (int i = 0; i < 3; i++) format_real(c[i], v[i], sizeof v[i]);
        snprintf(dest, size, "%s,%s,%s", v[0], v[1], v[2]);
        break;
    }
    case LUCENT_SETTING_CHOICE:
        name = k->choice(*(const int *)m);
        snprintf(dest, size, "%s", name ? name : "unknown");
        break;
    case LUCENT_SETTING_TEXT: snprintf(dest, size, "%s", (const char *)m); break;
    }
}

/* ---- checks of a struct ---- */

static void check_member(const lucent_render_settings *s, const lucent_setting *k, char *why, size_t size)
{
    const void *m = cmember(s, k);
    why[0] = '\0';
    if (k->type == LUCENT_SETTING_INT)
        check_number(k, *(const int *)m, why, size);
    else if (k->type == LUCENT_SETTING_REAL)
        check_number(k, *(const double *)m, why, size);
    else if (k->type == LUCENT_SETTING_SEED)
        check_number(k, (double)*(const uint64_t *)m, why, size);
    else if (k->type == LUCENT_SETTING_COLOR)
        for (int c = 0; c < 3 && !why[0]; c++) check_number(k, ((const double *)m)[c], why, size);
    else if (k->type == LUCENT_SETTING_CHOICE && !k->choice(*(const int *)m))
        snprintf(why, size, "unknown value %d", *(const int *)m);
    else if (k->type == LUCENT_SETTING_TEXT)
        check_name(k, memchr(m, '\0', k->size) ? (const char *)m : "(not terminated)", why, size);
}

lucent_status settings_table_check(const settings_table *t, const lucent_render_settings *s)
{
    char why[512];
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count; i++) {
            check_member(s, &grp->settings[i], why, sizeof why);
            if (why[0])
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "render settings: %s %s", grp->settings[i].key, why);
        }
    }
    return LUCENT_OK;
}

/* ---- scene files ---- */

static lucent_status read_member(const lucent_json_node *n, const lucent_setting *k, lucent_render_settings *dest)
{
    char why[512] = "";
    lucent_status st = LUCENT_OK;
    if (k->parse || k->type == LUCENT_SETTING_CHOICE || k->type == LUCENT_SETTING_TEXT) {
        const char *text;
        st = lucent_json_string(n, k->key, &text);
        if (st == LUCENT_OK) st = set_text(dest, k, text, why, sizeof why);
    } else if (k->type == LUCENT_SETTING_BOOL) {
        st = lucent_json_bool_or(n, k->key, false, (bool *)member(dest, k));
    } else {
        double v[3];
        int count = k->type == LUCENT_SETTING_COLOR ? 3 : 1;
        st = count == 3 ? lucent_json_numbers(n, k->key, 3, true, v) : lucent_json_number(n, k->key, v);
        if (st == LUCENT_OK) st = set_number(dest, k, v, count, why, sizeof why);
    }
    if (why[0]) {
        lucent_clear_error();
        return lucent_json_fail(n, k->key, LUCENT_ERR_PARSE, "%s", why);
    }
    return st;
}

static lucent_status check_keys(const settings_table *t, const lucent_json_node *n)
{
    const char *known[256];
    int count = 0;
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count && count < 255; i++) known[count++] = grp->settings[i].key;
    }
    known[count] = NULL;
    return lucent_json_check_keys(n, known);
}

lucent_status settings_table_read_json(const settings_table *t, const lucent_json_node *render,
                                       lucent_render_settings *dest)
{
    *dest = settings_table_defaults(t);
    if (!render->json) return LUCENT_OK;
    lucent_status st = check_keys(t, render);
    for (int g = 0; g < t->count && st == LUCENT_OK; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count && st == LUCENT_OK; i++)
            if (lucent_json_has(render, grp->settings[i].key)) st = read_member(render, &grp->settings[i], dest);
    }
    return st;
}

static bool write_member(const lucent_render_settings *s, const lucent_setting *k, cJSON *o)
{
    const void *m = cmember(s, k);
    char text[256];
    switch (k->type) {
    case LUCENT_SETTING_BOOL: return cJSON_AddBoolToObject(o, k->key, *(const bool *)m) != NULL;
    case LUCENT_SETTING_INT: return lucent_json_add_number(o, k->key, *(const int *)m) != NULL;
    case LUCENT_SETTING_REAL: return lucent_json_add_number(o, k->key, *(const double *)m) != NULL;
    case LUCENT_SETTING_SEED: return lucent_json_add_number(o, k->key, (double)*(const uint64_t *)m) != NULL;
    case LUCENT_SETTING_COLOR: return lucent_json_add_numbers(o, k->key, m, 3) != NULL;
    case LUCENT_SETTING_CHOICE:
    case LUCENT_SETTING_TEXT:
        lucent_setting_format(s, k, text, sizeof text);
        return cJSON_AddStringToObject(o, k->key, text) != NULL;
    }
    return false;
}

bool settings_table_write_json(const settings_table *t, const lucent_render_settings *s, cJSON *object)
{
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        for (int i = 0; i < grp->count; i++)
            if (!write_member(s, &grp->settings[i], object)) return false;
    }
    return true;
}

/* ---- descriptions and listings ---- */

static bool listed(const char *key, const char *const *skip)
{
    for (int i = 0; skip && skip[i]; i++)
        if (!strcmp(skip[i], key)) return true;
    return false;
}

void settings_table_describe(const settings_table *t, const lucent_render_settings *s, const char *group,
                             const char *const *skip, char *dest, size_t size)
{
    dest[0] = '\0';
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        if (strcmp(grp->name, group)) continue;
        for (int i = 0; i < grp->count; i++) {
            const lucent_setting *k = &grp->settings[i];
            if (listed(k->key, skip)) continue;
            char value[128];
            lucent_setting_format(s, k, value, sizeof value);
            snprintf(dest + strlen(dest), size - strlen(dest), "%s%s %s", dest[0] ? ", " : "", k->key, value);
        }
    }
}

/* "17 (odd, 1..255)", "follow (follow, gaussian, none)". */
static void default_and_range(const settings_table *t, const lucent_setting *k, char *dest, size_t size)
{
    lucent_render_settings d = settings_table_defaults(t);
    char value[128], names[256];
    lucent_setting_format(&d, k, value, sizeof value);
    if (k->type == LUCENT_SETTING_REAL || k->type == LUCENT_SETTING_COLOR)
        snprintf(value, sizeof value, k->type == LUCENT_SETTING_COLOR ? "%g (each)" : "%g", k->def);
    if (k->type == LUCENT_SETTING_CHOICE || (k->type == LUCENT_SETTING_TEXT && k->choice)) {
        lucent_settings_choice_list(k->choice, names, sizeof names);
        snprintf(dest, size, "%s | %s", value, names);
    } else if (k->type == LUCENT_SETTING_BOOL || k->type == LUCENT_SETTING_TEXT) {
        snprintf(dest, size, "%s | true, false", value);
        if (k->type == LUCENT_SETTING_TEXT) snprintf(dest, size, "%s | text", value);
    } else {
        char range[96];
        isinf(k->hi) ? snprintf(range, sizeof range, ">= %g", k->lo)
                     : snprintf(range, sizeof range, "%g .. %g", k->lo, k->hi);
        snprintf(dest, size, "%s | %s%s", value, range, (k->flags & LUCENT_SETTING_ODD) ? ", odd" : "");
    }
}

lucent_status settings_table_help(const settings_table *t, bool markdown, char **dest)
{
    lucent_strbuf b = {0};
    for (int g = 0; g < t->count; g++) {
        const lucent_settings_group *grp = t->groups[g];
        if (markdown)
            lucent_strbuf_printf(&b, "%s**%s**: %s\n\n| key | default | values | meaning |\n|---|---|---|---|\n",
                                 g ? "\n" : "", grp->name, grp->doc);
        else
            lucent_strbuf_printf(&b, "%s%s: %s\n", g ? "\n" : "", grp->name, grp->doc);
        for (int i = 0; i < grp->count; i++) {
            const lucent_setting *k = &grp->settings[i];
            char dr[400];
            default_and_range(t, k, dr, sizeof dr);
            char *bar = strstr(dr, " | ");
            *bar = '\0';
            if (markdown)
                lucent_strbuf_printf(&b, "| `%s` | %s | %s | %s |\n", k->key, dr, bar + 3, k->doc);
            else
                lucent_strbuf_printf(&b, "  %-24s %s\n  %-24s default %s; %s\n", k->key, k->doc, "", dr, bar + 3);
        }
    }
    return lucent_strbuf_finish(&b, dest);
}
