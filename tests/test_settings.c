/* Tests of the settings table (lucent/settings.h): every setting's default read back through the
 * scene reader and the sidecar writer, values other than the defaults likewise, text in and out,
 * range checks, and the table's own consistency (unique keys, defaults inside their ranges, every
 * key documented in docs/scenes.md). The expected values are the table's own defaults and the
 * values written: what is checked is that reader and writers agree with the table, not a number. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/settings_table.h"
#include "lucent/scene.h"
#include "test.h"

static const char *k_scene_fmt =
    "{\"camera\": {\"position\": [0, 0, 50], \"target\": [0, 0, 0]},\n"
    " \"lights\": [{\"type\": \"directional\", \"direction\": [0, 0, -1]}],\n"
    " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1}, \"material\": \"skin1\"}],\n"
    " \"render\": %s}";

/* Writes s as the sidecar does and reads it back as a scene's "render" object. */
static lucent_status round_trip(const lucent_render_settings *s, lucent_render_settings *dest)
{
    cJSON *o = cJSON_CreateObject();
    if (!o || !lucent_settings_write_json(s, o)) return cJSON_Delete(o), LUCENT_ERR_OUT_OF_MEMORY;
    char *json = cJSON_PrintUnformatted(o), *text = NULL;
    cJSON_Delete(o);
    size_t n = strlen(json) + strlen(k_scene_fmt) + 1;
    text = malloc(n);
    snprintf(text, n, k_scene_fmt, json);
    lucent_scene *sc = NULL;
    lucent_status st =
        lucent_scene_parse(text, "round.json", NULL, &(lucent_scene_load_desc){.skip_meshes = true}, &sc);
    if (sc) *dest = sc->render;
    lucent_scene_destroy(sc);
    free(json), free(text);
    return st;
}

/* The bytes of setting k in a and b are equal (TEXT: the strings). */
static bool same(const lucent_render_settings *a, const lucent_render_settings *b, const lucent_setting *k)
{
    const char *x = (const char *)a + k->offset, *y = (const char *)b + k->offset;
    return k->type == LUCENT_SETTING_TEXT ? !strcmp(x, y) : !memcmp(x, y, k->size);
}

#define FOR_EACH_SETTING(k)                                                                                            \
    for (int g_ = 0; g_ < lucent_settings_group_count(); g_++)                                                         \
        for (const lucent_setting *k = lucent_settings_group_get(g_)->settings;                                        \
             k < lucent_settings_group_get(g_)->settings + lucent_settings_group_get(g_)->count; k++)

TEST(defaults_read_back_through_the_sidecar_and_the_scene_reader)
{
    lucent_render_settings d = lucent_render_settings_defaults(), back;
    CHECK_OK(round_trip(&d, &back));
    int count = 0;
    FOR_EACH_SETTING(k)
    {
        if (!same(&d, &back, k)) TEST_FAIL_("setting %s did not read back", k->key);
        count++;
    }
    CHECK(count >= 25); /* every setting of the five groups of lucent/settings.h */
    /* A scene without a "render" object gets the same defaults. */
    lucent_scene *sc = NULL;
    char text[1024];
    snprintf(text, sizeof text, k_scene_fmt, "{}");
    CHECK_OK(lucent_scene_parse(text, "t.json", NULL, &(lucent_scene_load_desc){.skip_meshes = true}, &sc));
    FOR_EACH_SETTING(k) CHECK(sc && same(&d, &sc->render, k));
    lucent_scene_destroy(sc);
}

/* A value other than the default for each setting: the upper end of a range, the last name. */
static void change(lucent_render_settings *s, const lucent_setting *k)
{
    char text[64];
    int last = 0;
    switch (k->type) {
    case LUCENT_SETTING_BOOL: snprintf(text, sizeof text, "%s", k->def ? "false" : "true"); break;
    case LUCENT_SETTING_INT:
    case LUCENT_SETTING_SEED:
        snprintf(text, sizeof text, "%.0f", (k->flags & LUCENT_SETTING_ODD) && fmod(k->hi, 2) == 0 ? k->hi - 1 : k->hi);
        break;
    case LUCENT_SETTING_REAL: snprintf(text, sizeof text, "%.17g", k->lo + 0.375 * (k->hi - k->lo)); break;
    case LUCENT_SETTING_COLOR: snprintf(text, sizeof text, "0.25,0.5,2"); break;
    case LUCENT_SETTING_CHOICE:
    case LUCENT_SETTING_TEXT:
        while (k->choice(last + 1)) last++;
        if (k->def_text && !strcmp(k->choice(last), k->def_text)) last = 0; /* not the default */
        snprintf(text, sizeof text, "%s", k->choice(last));
        break;
    }
    if (!strcmp(k->key, "method")) snprintf(text, sizeof text, "lambert"); /* "ssss:..." would reset the kernel */
    if (!strcmp(k->key, "kernel")) snprintf(text, sizeof text, "svd");     /* a rank-taking model keeps "rank" */
    CHECK_OK(lucent_setting_set(s, k, text));
}

TEST(other_values_read_back_and_format_back)
{
    lucent_render_settings s = lucent_render_settings_defaults(), back;
    FOR_EACH_SETTING(k) change(&s, k);
    CHECK_OK(lucent_render_settings_check(&s));
    CHECK_OK(round_trip(&s, &back));
    lucent_render_settings d = lucent_render_settings_defaults();
    FOR_EACH_SETTING(k)
    {
        if (!same(&s, &back, k)) TEST_FAIL_("changed %s did not read back", k->key);
        if (same(&s, &d, k)) TEST_FAIL_("%s: the test value is the default", k->key);
        /* text out, text in: the same value */
        char text[256];
        lucent_render_settings t = lucent_render_settings_defaults();
        lucent_setting_format(&s, k, text, sizeof text);
        CHECK_OK(lucent_setting_set(&t, k, text));
        if (!same(&s, &t, k)) TEST_FAIL_("%s: \"%s\" did not read back", k->key, text);
    }
}

TEST(the_table_is_consistent)
{
    lucent_render_settings d = lucent_render_settings_defaults();
    CHECK_OK(lucent_render_settings_check(&d)); /* defaults inside their ranges */
    FOR_EACH_SETTING(k)
    {
        const lucent_settings_group *g = NULL;
        CHECK(lucent_setting_find(k->key, &g) == k); /* keys are unique across groups */
        CHECK(k->doc && k->doc[0]);
        CHECK(k->offset + k->size <= sizeof(lucent_render_settings));
    }
    CHECK(lucent_setting_find("render.taps", NULL) == lucent_setting_find("taps", NULL));
    CHECK(lucent_setting_find("wobble", NULL) == NULL);
}

TEST(every_key_is_documented_in_docs_scenes)
{
    char *text = NULL;
    size_t size = 0;
    CHECK_OK(lucent_read_file(LUCENT_SOURCE_DIR "/docs/scenes.md", &text, &size));
    FOR_EACH_SETTING(k)
    {
        char quoted[64];
        snprintf(quoted, sizeof quoted, "`%s`", k->key);
        if (text && !strstr(text, quoted)) TEST_FAIL_("docs/scenes.md lacks %s", quoted);
    }
    free(text);
}

TEST(bad_values_name_the_key_and_the_range)
{
    lucent_render_settings s = lucent_render_settings_defaults();
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("taps", NULL), "16"), LUCENT_ERR_INVALID_ARGUMENT,
              "render.taps", "odd");
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("strength", NULL), "1.5"), LUCENT_ERR_INVALID_ARGUMENT,
              "render.strength", "[0, 1]");
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("depth_filter", NULL), "blurry"), LUCENT_ERR_INVALID_ARGUMENT,
              "follow, gaussian, none");
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("background", NULL), "1,2"), LUCENT_ERR_INVALID_ARGUMENT,
              "1 or 3 numbers");
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("translucency", NULL), "maybe"), LUCENT_ERR_INVALID_ARGUMENT,
              "true or false");
    CHECK_ERR(lucent_setting_set(&s, lucent_setting_find("width", NULL), "12.5"), LUCENT_ERR_INVALID_ARGUMENT,
              "whole number");
    CHECK(s.ssss.taps == 17 && s.view.width == 512); /* nothing changed */
    s.view.method = (lucent_render_method)LUCENT_METHOD_COUNT;
    CHECK_ERR(lucent_render_settings_check(&s), LUCENT_ERR_INVALID_ARGUMENT, "method");
    s = lucent_render_settings_defaults();
    snprintf(s.ssss.profile, sizeof s.ssss.profile, "gaussian");
    CHECK_ERR(lucent_render_settings_check(&s), LUCENT_ERR_INVALID_ARGUMENT, "profile", "dipole");
}

TEST(listings_and_descriptions_come_from_the_table)
{
    char *help = NULL, *md = NULL;
    CHECK_OK(lucent_settings_help(false, &help));
    CHECK_OK(lucent_settings_help(true, &md));
    FOR_EACH_SETTING(k) CHECK(help && md && strstr(help, k->key) && strstr(md, k->key) && strstr(help, k->doc));
    free(help), free(md);
    lucent_render_settings s = lucent_render_settings_defaults();
    char text[512];
    lucent_render_method_describe(&s, text, sizeof text);
    CHECK(strstr(text, "kernel preint") && strstr(text, "taps 17") && strstr(text, "depth_filter follow"));
    s.view.method = LUCENT_METHOD_CDRF;
    lucent_render_method_describe(&s, text, sizeof text);
    CHECK(strstr(text, "cdrf_variant kubo") && !strstr(text, "taps"));
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++)
        for (int i = 0; lucent_render_method_setting((lucent_render_method)m, i); i++)
            CHECK(lucent_setting_find(lucent_render_method_setting((lucent_render_method)m, i), NULL) != NULL);
}

TEST_MAIN(TEST_ENTRY(defaults_read_back_through_the_sidecar_and_the_scene_reader),
          TEST_ENTRY(other_values_read_back_and_format_back), TEST_ENTRY(the_table_is_consistent),
          TEST_ENTRY(every_key_is_documented_in_docs_scenes), TEST_ENTRY(bad_values_name_the_key_and_the_range),
          TEST_ENTRY(listings_and_descriptions_come_from_the_table))
