/* The scene's camera, lights and render settings: reading and checking, with errors that name the
 * file and the JSON path. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/settings_table.h"
#include "scene/internal.h"

/* ---- small readers ---- */

lucent_status scene_read_vec3(const lucent_json_node *n, const char *key, const double def[3], double dest[3])
{
    if (!lucent_json_has(n, key)) {
        memcpy(dest, def, 3 * sizeof *dest);
        return LUCENT_OK;
    }
    return lucent_json_numbers(n, key, 3, false, dest);
}

lucent_status scene_read_range(const lucent_json_node *n, const char *key, double def, double lo, double hi,
                               double *dest)
{
    lucent_status s = lucent_json_number_or(n, key, def, dest);
    if (s == LUCENT_OK && !(*dest >= lo && *dest <= hi))
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be in [%g, %g], got %g", lo, hi, *dest);
    return s;
}

lucent_status scene_read_int(const lucent_json_node *n, const char *key, int def, int lo, int hi, int *dest)
{
    double v;
    lucent_status s = scene_read_range(n, key, def, lo, hi, &v);
    if (s == LUCENT_OK && v != (double)(int)v)
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be a whole number, got %g", v);
    if (s == LUCENT_OK) *dest = (int)v;
    return s;
}

/* Reads an optional colour: 3 non-negative numbers (or one, repeated). */
static lucent_status read_color(const lucent_json_node *n, const char *key, double def, double dest[3])
{
    if (!lucent_json_has(n, key)) {
        dest[0] = dest[1] = dest[2] = def;
        return LUCENT_OK;
    }
    lucent_status s = lucent_json_numbers(n, key, 3, true, dest);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++)
        if (dest[c] < 0) s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be >= 0, got %g", dest[c]);
    return s;
}

/* Reads an optional name out of a NULL-terminated list; *dest is its index. */
static lucent_status read_choice(const lucent_json_node *n, const char *key, const char *const *names, int def,
                                 int *dest)
{
    const char *text;
    lucent_status s = lucent_json_string_or(n, key, names[def], &text);
    if (s != LUCENT_OK) return s;
    char list[256] = "";
    for (int i = 0; names[i]; i++) {
        if (!strcasecmp(text, names[i])) {
            *dest = i;
            return LUCENT_OK;
        }
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", i ? ", " : "", names[i]);
    }
    return lucent_json_fail(n, key, LUCENT_ERR_PARSE, "unknown value \"%s\" (%s)", text, list);
}

/* ---- camera ---- */

static const char *const k_camera_keys[] = {"position", "target", "up", "fov_y", "near", "far", NULL};

lucent_status scene_read_camera(const lucent_json_node *root, lucent_camera *dest)
{
    lucent_json_node n;
    static const double up[3] = {0, 1, 0};
    memset(dest, 0, sizeof *dest);
    lucent_status s = lucent_json_object(root, "camera", true, &n);
    if (s == LUCENT_OK) s = lucent_json_check_keys(&n, k_camera_keys);
    if (s == LUCENT_OK) s = lucent_json_numbers(&n, "position", 3, false, dest->position);
    if (s == LUCENT_OK) s = lucent_json_numbers(&n, "target", 3, false, dest->target);
    if (s == LUCENT_OK) s = scene_read_vec3(&n, "up", up, dest->up);
    if (s == LUCENT_OK) s = scene_read_range(&n, "fov_y", 30, 0.01, 179, &dest->fov_y);
    if (s == LUCENT_OK) s = scene_read_range(&n, "near", 0, 0, 1e12, &dest->near_plane);
    if (s == LUCENT_OK) s = scene_read_range(&n, "far", 0, 0, 1e12, &dest->far_plane);
    v3 d = v3_normalize(v3_sub(v3_load(dest->target), v3_load(dest->position)));
    v3 up_n = v3_normalize(v3_load(dest->up));
    if (s == LUCENT_OK && v3_dot(d, d) == 0)
        s = lucent_json_fail(&n, "target", LUCENT_ERR_PARSE, "must differ from the position");
    if (s == LUCENT_OK && v3_dot(up_n, up_n) == 0) s = lucent_json_fail(&n, "up", LUCENT_ERR_PARSE, "must not be zero");
    if (s == LUCENT_OK && dest->far_plane > 0 && dest->far_plane <= dest->near_plane)
        s = lucent_json_fail(&n, "far", LUCENT_ERR_PARSE, "must be greater than near");
    return s;
}

/* ---- lights ---- */

static const char *const k_light_types[] = {"directional", "point", "sphere", "environment", NULL};
static const char *const k_light_keys[] = {"type",   "color",          "intensity", "direction", "position",
                                           "radius", "angular_radius", "shadows",   "name",      NULL};

const char *lucent_light_type_name(lucent_light_type type)
{
    return type >= 0 && type <= LUCENT_LIGHT_ENVIRONMENT ? k_light_types[type] : "unknown";
}

/* The members each type needs: direction for the sun, position for point and sphere lights. */
static lucent_status read_light_geometry(const lucent_json_node *n, lucent_light *l)
{
    lucent_status s = LUCENT_OK;
    if (l->type == LUCENT_LIGHT_DIRECTIONAL) {
        s = lucent_json_numbers(n, "direction", 3, false, l->direction);
        if (s == LUCENT_OK) {
            v3 dir = v3_normalize(v3_load(l->direction));
            v3_store(dir, l->direction);
            if (v3_dot(dir, dir) == 0) s = lucent_json_fail(n, "direction", LUCENT_ERR_PARSE, "must not be zero");
        }
        double deg = 0;
        if (s == LUCENT_OK) s = scene_read_range(n, "angular_radius", 0, 0, 45, &deg);
        l->angular_radius = deg * M_PI / 180;
    } else if (l->type == LUCENT_LIGHT_POINT || l->type == LUCENT_LIGHT_SPHERE) {
        s = lucent_json_numbers(n, "position", 3, false, l->position);
        double lo = l->type == LUCENT_LIGHT_SPHERE ? 1e-9 : 0, hi = l->type == LUCENT_LIGHT_SPHERE ? 1e12 : 0;
        if (s == LUCENT_OK && (l->type == LUCENT_LIGHT_SPHERE || lucent_json_has(n, "radius")))
            s = l->type == LUCENT_LIGHT_SPHERE
                    ? lucent_json_number(n, "radius", &l->radius)
                    : lucent_json_fail(n, "radius", LUCENT_ERR_PARSE, "a point light has no radius (use \"sphere\")");
        if (s == LUCENT_OK && !(l->radius >= lo && l->radius <= hi))
            s = lucent_json_fail(n, "radius", LUCENT_ERR_PARSE, "must be > 0, got %g", l->radius);
    }
    return s;
}

static lucent_status read_light(const lucent_json_node *n, lucent_light *l)
{
    int type = 0;
    memset(l, 0, sizeof *l);
    lucent_status s = lucent_json_check_keys(n, k_light_keys);
    if (s == LUCENT_OK && !lucent_json_has(n, "type"))
        s = lucent_json_fail(n, "type", LUCENT_ERR_PARSE, "missing field (directional, point, sphere, environment)");
    if (s == LUCENT_OK) s = read_choice(n, "type", k_light_types, 0, &type);
    l->type = (lucent_light_type)type;
    if (s == LUCENT_OK) s = read_color(n, "color", 1, l->color);
    if (s == LUCENT_OK) s = scene_read_range(n, "intensity", 1, 0, 1e30, &l->intensity);
    if (s == LUCENT_OK) s = lucent_json_bool_or(n, "shadows", true, &l->shadows);
    if (s == LUCENT_OK) s = read_light_geometry(n, l);
    return s;
}

lucent_status scene_read_lights(const lucent_json_node *root, lucent_light **dest, int *count)
{
    lucent_json_node list, e;
    int n = 0;
    *dest = NULL;
    *count = 0;
    lucent_status s = lucent_json_array(root, "lights", true, &list, &n);
    if (s == LUCENT_OK && n == 0) s = lucent_json_fail(&list, NULL, LUCENT_ERR_PARSE, "expected at least one light");
    if (s != LUCENT_OK) return s;
    lucent_light *l = calloc((size_t)n, sizeof *l);
    if (!l) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < n && s == LUCENT_OK; i++) {
        s = lucent_json_element(&list, i, &e);
        if (s == LUCENT_OK) s = read_light(&e, &l[i]);
    }
    if (s != LUCENT_OK) {
        free(l);
        return s;
    }
    *dest = l;
    *count = n;
    return LUCENT_OK;
}

/* ---- render settings (lucent/settings.h) ----
 * The view group is read here; the other groups are declared beside the code that reads them. */

static const char *tonemap_name(int i)
{
    return i >= 0 && i <= LUCENT_TONEMAP_FILMIC ? lucent_tonemap_op_name((lucent_tonemap_op)i) : NULL;
}

static const char *method_name(int i)
{
    return i >= 0 && i < LUCENT_METHOD_COUNT ? lucent_render_method_name((lucent_render_method)i) : NULL;
}

/* "ssss:svd3" also sets the method's own settings (the kernel and its rank). */
static lucent_status parse_method(const char *text, lucent_render_settings *dest)
{
    return lucent_render_method_parse(text, &dest->view.method, dest);
}

static const lucent_setting k_view[] = {
    SETTING_INT("width", view.width, 512, 1, 16384, 0, "image width, pixels"),
    SETTING_INT("height", view.height, 512, 1, 16384, 0, "image height, pixels"),
    {.key = "method",
     .type = LUCENT_SETTING_CHOICE,
     SETTING_AT_(view.method, sizeof(lucent_render_method) == sizeof(int)),
     .def_text = "ssss",
     .choice = method_name,
     .parse = parse_method,
     .doc = "the GL renderer's method; ssss:<kernel>[rank] chooses the kernel too (ssss:svd3)"},
    SETTING_INT("shadow_map_size", view.shadow_map_size, 2048, 16, 16384, 0, "texels per side of each shadow map"),
    SETTING_INT("samples", view.samples, 1, 1, 256, 0,
                "pixel samples: the image is the mean of this many frames, the camera jittered over the pixel "
                "(Halton 2, 3), as TAA and EEVEE's render samples converge; 1: the pixel's centre"),
    SETTING_INT("bounce", view.bounce, 32, 0, 64, 0,
                "light between surfaces: one bounce of each shadowed light, from a reflective shadow map of this "
                "many surfels per side (0: none; its cost is surfels x pixels)"),
    SETTING_COLOR("background", view.background, 0, 0, 1e30,
                  "linear RGB behind the objects (an environment light shows through)"),
    SETTING_CHOICE("tonemap", view.tonemap, "filmic", tonemap_name, "tone mapping of PNG outputs"),
    SETTING_REAL("exposure", view.exposure, 0, -64, 64, "exposure of PNG outputs, stops"),
};

static const lucent_settings_group k_view_group = SETTINGS_GROUP("view", "the image and how it is shown", k_view);

/* Declared beside the code that reads them: src/gl/methods/ssss.c, translucency.c, cdrf.c,
 * src/trace/settings.c. */
extern const lucent_settings_group gl_ssss_settings, gl_translucency_settings, gl_cdrf_settings, gl_points_settings,
    gl_tsd_settings, tr_trace_settings;
extern const lucent_settings_group gl_burley_settings;

/* The registry: every group, in reading order (the method "ssss:svd3" before the kernel and rank
 * that may refine it). The settings engine of src/base/settings.c walks the table it is given; this
 * is the one the library gives it. */
static const lucent_settings_group *const k_groups[] = {
    &k_view_group,       &gl_ssss_settings, &gl_translucency_settings, &gl_cdrf_settings,
    &gl_points_settings, &gl_tsd_settings,  &tr_trace_settings,        &gl_burley_settings};
static const settings_table k_table = {k_groups, (int)(sizeof k_groups / sizeof k_groups[0])};

int lucent_settings_group_count(void) { return k_table.count; }

const lucent_settings_group *lucent_settings_group_get(int index)
{
    return index >= 0 && index < k_table.count ? k_groups[index] : NULL;
}

lucent_render_settings lucent_render_settings_defaults(void) { return settings_table_defaults(&k_table); }

const lucent_setting *lucent_setting_find(const char *key, const lucent_settings_group **group)
{
    return settings_table_find(&k_table, key, group);
}

lucent_status lucent_render_settings_check(const lucent_render_settings *s)
{
    return settings_table_check(&k_table, s);
}

void lucent_settings_describe(const lucent_render_settings *s, const char *group, const char *const *skip, char *dest,
                              size_t size)
{
    settings_table_describe(&k_table, s, group, skip, dest, size);
}

lucent_status lucent_settings_help(bool markdown, char **dest) { return settings_table_help(&k_table, markdown, dest); }

lucent_status lucent_settings_read_json(const lucent_json_node *render, lucent_render_settings *dest)
{
    return settings_table_read_json(&k_table, render, dest);
}

bool lucent_settings_write_json(const lucent_render_settings *s, cJSON *object)
{
    return settings_table_write_json(&k_table, s, object);
}

lucent_status scene_read_render(const lucent_json_node *root, lucent_render_settings *dest)
{
    lucent_json_node n;
    *dest = lucent_render_settings_defaults();
    lucent_status s = lucent_json_object(root, "render", false, &n);
    return s == LUCENT_OK ? lucent_settings_read_json(&n, dest) : s;
}
