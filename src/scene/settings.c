/* The scene's camera, lights and render settings: reading and checking, with errors that name the
 * file and the JSON path. */
#include <stdlib.h>
#include <string.h>
#include <strings.h>

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
    if (s == LUCENT_OK && v3_dot(up_n, up_n) == 0)
        s = lucent_json_fail(&n, "up", LUCENT_ERR_PARSE, "must not be zero");
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

/* ---- render settings ---- */

static const char *const k_method_names[] = {"lambert", "cdrf", "cdrf+translucency", "ssss", NULL};
static const char *const k_depth_filters[] = {"follow", "gaussian", "none", NULL};
static const char *const k_sigma0_sources[] = {"fit", "diffuse", NULL};
static const char *const k_transmittances[] = {"slab", "profile", NULL};
static const char *const k_cdrf_variants[] = {"kubo", "collomb", NULL};
static const char *const k_tonemaps[] = {"none", "clamp", "reinhard", "filmic", NULL};
static const char *const k_render_keys[] = {
    "width",       "height",      "method",         "kernel",   "rank",     "taps",       "profile",
    "strength",    "width_scale", "depth_filter",   "translucency", "transmittance", "translucency_curvature", "cdrf_variant", "cdrf_lut", "sigma0",
    "curvature_smooth", "shadow_map_size", "background", "tonemap", "exposure", "spp", "seed",
    "max_bounces", "max_scatter", "time_limit", NULL};

lucent_render_settings lucent_render_settings_defaults(void)
{
    return (lucent_render_settings){.width = 512,
                                    .height = 512,
                                    .method = LUCENT_METHOD_SSSS,
                                    .kernel_model = LUCENT_KERNEL_PREINT,
                                    .kernel_rank = 1,
                                    .taps = 17,
                                    .profile = "dipole",
                                    .strength = 1,
                                    .width_scale = 1,
                                    .depth_filter = LUCENT_DEPTH_FOLLOW,
                                    .translucency = true,
                                    .translucency_curvature = 1,
                                    .cdrf_variant = LUCENT_CDRF_KUBO,
                                    .cdrf_lut = true,
                                    .sigma0_source = LUCENT_SIGMA0_FIT,
                                    .curvature_smooth = 1,
                                    .shadow_map_size = 2048,
                                    .tonemap = LUCENT_TONEMAP_FILMIC,
                                    .spp = 64,
                                    .seed = 1,
                                    .max_bounces = 64,
                                    .max_scatter = 100000};
}

const char *lucent_render_method_name(lucent_render_method method)
{
    return method >= 0 && method < LUCENT_METHOD_COUNT ? k_method_names[method] : "unknown";
}

const char *lucent_depth_filter_name(lucent_depth_filter filter)
{
    return filter >= 0 && filter <= LUCENT_DEPTH_NONE ? k_depth_filters[filter] : "unknown";
}

const char *lucent_transmittance_name(lucent_transmittance_model model)
{
    return model >= 0 && model <= LUCENT_TRANSMIT_PROFILE ? k_transmittances[model] : "unknown";
}

const char *lucent_sigma0_source_name(lucent_sigma0_source source)
{
    return source >= 0 && source <= LUCENT_SIGMA0_DIFFUSE ? k_sigma0_sources[source] : "unknown";
}

/* "svd3" -> model svd, rank 3; "preint" -> rank 1. Only svd and sog take a rank. */
static lucent_status parse_model_rank(const char *text, lucent_kernel_model *model, int *rank)
{
    char name[32];
    size_t len = strcspn(text, "0123456789");
    if (len == 0 || len >= sizeof name) return lucent_kernel_model_find(text, model);
    memcpy(name, text, len);
    name[len] = '\0';
    int r = 1;
    if (text[len]) {
        char *end;
        long v = strtol(text + len, &end, 10);
        if (*end || v < 1 || v > LUCENT_KERNEL_MAX_RANK) return lucent_kernel_model_find(text, model);
        r = (int)v;
    }
    lucent_status s = lucent_kernel_model_find(name, model);
    if (s == LUCENT_OK && r > 1 && *model != LUCENT_KERNEL_SVD && *model != LUCENT_KERNEL_SOG)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel model '%s' has rank 1 only (svd and sog take a rank)",
                            name);
    if (s == LUCENT_OK) *rank = r;
    return s;
}

lucent_status lucent_render_method_parse(const char *text, lucent_render_method *method,
                                         lucent_kernel_model *model, int *rank)
{
    const char *colon = strchr(text, ':');
    size_t len = colon ? (size_t)(colon - text) : strlen(text);
    for (int m = 0; m < LUCENT_METHOD_COUNT; m++) {
        if (strlen(k_method_names[m]) != len || strncasecmp(text, k_method_names[m], len)) continue;
        if (colon && m != LUCENT_METHOD_SSSS)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "method '%s': only ssss takes a kernel model", text);
        lucent_kernel_model km = LUCENT_KERNEL_PREINT;
        int r = 1;
        if (colon && parse_model_rank(colon + 1, &km, &r) != LUCENT_OK)
            return lucent_error_context(LUCENT_ERR_INVALID_ARGUMENT, "method '%s'", text);
        *method = (lucent_render_method)m;
        if (colon && model) *model = km;
        if (colon && rank) *rank = r;
        return LUCENT_OK;
    }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "unknown method '%s' (lambert, cdrf, cdrf+translucency, ssss, ssss:<model>[rank] "
                        "with model svd, preint, guided, manual, sog, jimenez)",
                        text);
}

static lucent_status read_method(const lucent_json_node *n, lucent_render_settings *r)
{
    const char *text;
    lucent_status s = lucent_json_string_or(n, "method", "ssss", &text);
    if (s == LUCENT_OK && lucent_render_method_parse(text, &r->method, &r->kernel_model, &r->kernel_rank))
        s = lucent_json_fail(n, "method", LUCENT_ERR_PARSE, "%s", lucent_last_error());
    if (s == LUCENT_OK && lucent_json_has(n, "kernel")) {
        s = lucent_json_string(n, "kernel", &text);
        if (s == LUCENT_OK && parse_model_rank(text, &r->kernel_model, &r->kernel_rank))
            s = lucent_json_fail(n, "kernel", LUCENT_ERR_PARSE, "%s", lucent_last_error());
    }
    if (s == LUCENT_OK && lucent_json_has(n, "rank"))
        s = scene_read_int(n, "rank", 1, 1, LUCENT_KERNEL_MAX_RANK, &r->kernel_rank);
    return s;
}

static lucent_status read_profile(const lucent_json_node *n, lucent_render_settings *r)
{
    const char *text;
    lucent_status s = lucent_json_string_or(n, "profile", "dipole", &text);
    if (s == LUCENT_OK && (!lucent_profile_source_known(text) || strlen(text) >= sizeof r->profile))
        s = lucent_json_fail(n, "profile", LUCENT_ERR_PARSE,
                             "unknown profile \"%s\" (dipole, better-dipole, burley, mc)", text);
    if (s == LUCENT_OK) snprintf(r->profile, sizeof r->profile, "%s", text);
    return s;
}

static lucent_status read_choices(const lucent_json_node *n, lucent_render_settings *r)
{
    int v[5] = {r->depth_filter, r->sigma0_source, r->cdrf_variant, r->tonemap, r->transmittance};
    lucent_status s = read_choice(n, "depth_filter", k_depth_filters, v[0], &v[0]);
    if (s == LUCENT_OK) s = read_choice(n, "sigma0", k_sigma0_sources, v[1], &v[1]);
    if (s == LUCENT_OK) s = read_choice(n, "cdrf_variant", k_cdrf_variants, v[2], &v[2]);
    if (s == LUCENT_OK) s = read_choice(n, "tonemap", k_tonemaps, v[3], &v[3]);
    if (s == LUCENT_OK) s = read_choice(n, "transmittance", k_transmittances, v[4], &v[4]);
    r->depth_filter = (lucent_depth_filter)v[0], r->sigma0_source = (lucent_sigma0_source)v[1];
    r->cdrf_variant = (lucent_cdrf_variant)v[2], r->tonemap = (lucent_tonemap_op)v[3];
    r->transmittance = (lucent_transmittance_model)v[4];
    return s;
}

static lucent_status read_numbers(const lucent_json_node *n, lucent_render_settings *r)
{
    double seed = 1;
    lucent_status s = scene_read_int(n, "width", r->width, 1, 16384, &r->width);
    if (s == LUCENT_OK) s = scene_read_int(n, "height", r->height, 1, 16384, &r->height);
    if (s == LUCENT_OK) s = scene_read_int(n, "taps", r->taps, 1, 255, &r->taps);
    if (s == LUCENT_OK && r->taps % 2 == 0)
        s = lucent_json_fail(n, "taps", LUCENT_ERR_PARSE, "must be odd (a centre tap and pairs), got %d", r->taps);
    if (s == LUCENT_OK) s = scene_read_range(n, "strength", 1, 0, 1, &r->strength);
    if (s == LUCENT_OK) s = scene_read_range(n, "width_scale", 1, 1e-6, 1e6, &r->width_scale);
    if (s == LUCENT_OK) s = scene_read_range(n, "translucency_curvature", 1, -100, 100, &r->translucency_curvature);
    if (s == LUCENT_OK) s = scene_read_int(n, "curvature_smooth", 1, 0, 16, &r->curvature_smooth);
    if (s == LUCENT_OK) s = scene_read_int(n, "shadow_map_size", 2048, 16, 16384, &r->shadow_map_size);
    if (s == LUCENT_OK) s = read_color(n, "background", 0, r->background);
    if (s == LUCENT_OK) s = scene_read_range(n, "exposure", 0, -64, 64, &r->exposure);
    if (s == LUCENT_OK) s = scene_read_int(n, "spp", r->spp, 1, 1 << 24, &r->spp);
    if (s == LUCENT_OK) s = scene_read_range(n, "seed", 1, 0, 9007199254740992.0, &seed);
    r->seed = (uint64_t)seed;
    if (s == LUCENT_OK) s = scene_read_int(n, "max_bounces", r->max_bounces, 1, 100000, &r->max_bounces);
    if (s == LUCENT_OK) s = scene_read_int(n, "max_scatter", r->max_scatter, 1, 1 << 30, &r->max_scatter);
    if (s == LUCENT_OK) s = scene_read_range(n, "time_limit", 0, 0, 1e9, &r->time_limit);
    return s;
}

lucent_status scene_read_render(const lucent_json_node *root, lucent_render_settings *dest)
{
    lucent_json_node n;
    *dest = lucent_render_settings_defaults();
    lucent_status s = lucent_json_object(root, "render", false, &n);
    if (s != LUCENT_OK || !n.json) return s;
    s = lucent_json_check_keys(&n, k_render_keys);
    if (s == LUCENT_OK) s = read_method(&n, dest);
    if (s == LUCENT_OK) s = read_profile(&n, dest);
    if (s == LUCENT_OK) s = read_choices(&n, dest);
    if (s == LUCENT_OK) s = read_numbers(&n, dest);
    if (s == LUCENT_OK) s = lucent_json_bool_or(&n, "translucency", true, &dest->translucency);
    if (s == LUCENT_OK) s = lucent_json_bool_or(&n, "cdrf_lut", true, &dest->cdrf_lut);
    return s;
}
