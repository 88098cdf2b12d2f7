/* Material files: reading (with errors naming file and JSON path) and writing.
 * The format is described in docs/materials.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "lucent/spectral.h"
#include "material/internal.h"

/* A closed or open numeric interval, with the rule as users read it. */
typedef struct range {
    double lo, hi;
    bool lo_open, hi_open;
    const char *rule;
} range;

static const range k_nonneg = {0.0, INFINITY, false, true, ">= 0"};
static const range k_positive = {0.0, INFINITY, true, true, "> 0"};
static const range k_unit = {0.0, 1.0, false, false, "in [0, 1]"};
static const range k_unit_open = {0.0, 1.0, false, true, "in [0, 1)"};
static const range k_g = {-1.0, 1.0, true, true, "in (-1, 1)"};
static const range k_eta = {LUCENT_MATERIAL_ETA_MIN, LUCENT_MATERIAL_ETA_MAX, false, false, "in [1, 3]"};

static bool in_range(double v, const range *r)
{
    bool lo_ok = r->lo_open ? v > r->lo : v >= r->lo;
    bool hi_ok = r->hi_open ? v < r->hi : v <= r->hi;
    return lo_ok && hi_ok;
}

/* Reads key as 3 numbers (or one, repeated) within r; out-of-range values are named
 * with their index: "sigma_a[1]: must be >= 0, got -0.1". */
static lucent_status read_channels(const lucent_json_node *n, const char *key, const range *r, double dest[3])
{
    lucent_status s = lucent_json_numbers(n, key, 3, true, dest);
    if (s != LUCENT_OK) return s;
    bool scalar = cJSON_IsNumber(cJSON_GetObjectItemCaseSensitive(n->json, key));
    for (int c = 0; c < 3; c++) {
        if (in_range(dest[c], r)) continue;
        char where[64];
        snprintf(where, sizeof where, scalar ? "%s" : "%s[%d]", key, c);
        return lucent_json_fail(n, where, LUCENT_ERR_PARSE, "must be %s, got %g", r->rule, dest[c]);
    }
    return LUCENT_OK;
}

/* ---- units ---- */

typedef struct unit {
    const char *names[2];
    double scale; /* multiplies a value in this unit to give mm^-1 (coefficients) or mm (lengths) */
} unit;

static const unit k_coefficient_units[] = {
    {{"mm^-1", "1/mm"}, 1.0}, {{"cm^-1", "1/cm"}, 0.1}, {{"m^-1", "1/m"}, 0.001}};
static const unit k_length_units[] = {{{"mm", NULL}, 1.0}, {{"cm", NULL}, 10.0}, {{"m", NULL}, 1000.0}};

static lucent_status read_units(const lucent_json_node *n, bool length, const char *with, double *scale)
{
    const char *text;
    lucent_status s = lucent_json_string(n, "units", &text);
    if (s != LUCENT_OK) return s;
    const unit *units = length ? k_length_units : k_coefficient_units;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 2; j++)
            if (units[i].names[j] && strcmp(text, units[i].names[j]) == 0) {
                *scale = units[i].scale;
                return LUCENT_OK;
            }
    return lucent_json_fail(n, "units", LUCENT_ERR_PARSE, "expected %s with %s, got \"%s\"",
                            length ? "\"mm\", \"cm\" or \"m\"" : "\"mm^-1\", \"cm^-1\" or \"m^-1\"", with, text);
}

static void scale3(double v[3], double k)
{
    for (int c = 0; c < 3; c++) v[c] *= k;
}

/* ---- the four ways to give a medium ---- */

typedef enum form { FORM_COEFFICIENTS, FORM_ALBEDO, FORM_REDUCED_ALBEDO, FORM_DIFFUSE, FORM_COUNT } form;

/* The keys of each form; the first one selects it. */
static const char *const k_form_keys[FORM_COUNT][3] = {
    {"sigma_a", "sigma_s", "sigma_s_prime"},
    {"albedo", "mean_free_path", NULL},
    {"reduced_albedo", "reduced_mean_free_path", NULL},
    {"diffuse_reflectance", "diffuse_mean_free_path", NULL},
};

static lucent_status foreign_key(const lucent_json_node *n, form f)
{
    for (int o = 0; o < FORM_COUNT; o++)
        for (int k = 0; k < 3; k++) {
            const char *key = k_form_keys[o][k];
            if (o == (int)f || !key || !lucent_json_has(n, key)) continue;
            return lucent_json_fail(n, key, LUCENT_ERR_PARSE, "cannot be combined with \"%s\"", k_form_keys[f][0]);
        }
    return LUCENT_OK;
}

static lucent_status pick_form(const lucent_json_node *n, form *dest)
{
    for (int f = 0; f < FORM_COUNT; f++)
        if (lucent_json_has(n, k_form_keys[f][0])) {
            *dest = (form)f;
            return foreign_key(n, (form)f);
        }
    return lucent_json_fail(n, "sigma_a", LUCENT_ERR_PARSE,
                            "missing field (give sigma_a with sigma_s or sigma_s_prime, or albedo, "
                            "reduced_albedo or diffuse_reflectance with its mean free path)");
}

static lucent_status read_coefficients(const lucent_json_node *n, lucent_material *m)
{
    double scale;
    lucent_status s = read_units(n, false, "sigma_a", &scale);
    if (s == LUCENT_OK) s = read_channels(n, "sigma_a", &k_nonneg, m->sigma_a);
    if (s != LUCENT_OK) return s;
    bool reduced = lucent_json_has(n, "sigma_s_prime");
    if (reduced && lucent_json_has(n, "sigma_s"))
        return lucent_json_fail(n, "sigma_s_prime", LUCENT_ERR_PARSE, "give either sigma_s or sigma_s_prime, not both");
    s = read_channels(n, reduced ? "sigma_s_prime" : "sigma_s", &k_nonneg, m->sigma_s);
    if (s != LUCENT_OK) return s;
    for (int c = 0; reduced && c < 3; c++) m->sigma_s[c] /= 1.0 - m->g[c]; /* sigma_s' = sigma_s (1-g) */
    scale3(m->sigma_a, scale);
    scale3(m->sigma_s, scale);
    return LUCENT_OK;
}

static lucent_status read_pair(const lucent_json_node *n, form f, const range *first, double a[3], double mfp[3])
{
    const char *const *keys = k_form_keys[f];
    double scale;
    lucent_status s = read_units(n, true, keys[1], &scale);
    if (s == LUCENT_OK) s = read_channels(n, keys[0], first, a);
    if (s == LUCENT_OK) s = read_channels(n, keys[1], &k_positive, mfp);
    if (s == LUCENT_OK) scale3(mfp, scale);
    return s;
}

static lucent_status read_medium(const lucent_json_node *n, form f, lucent_material *m)
{
    if (f == FORM_COEFFICIENTS) return read_coefficients(n, m);
    double a[3], mfp[3];
    const range *r = f == FORM_DIFFUSE ? &k_unit_open : &k_unit; /* Rd(alpha' = 1) = 1 */
    lucent_status s = read_pair(n, f, r, a, mfp);
    if (s != LUCENT_OK) return s;
    if (f == FORM_DIFFUSE)
        s = lucent_material_set_diffuse(a, mfp, m);
    else
        s = lucent_material_set_albedo(f == FORM_ALBEDO ? LUCENT_ALBEDO_SINGLE : LUCENT_ALBEDO_REDUCED, a, mfp, m);
    return s == LUCENT_OK ? s : lucent_json_fail(n, k_form_keys[f][0], s, "%s", lucent_last_error());
}

/* ---- a skin from its chromophores (docs/skin.md) ---- */

static const char *const k_skin_layers[] = {"epidermis", "dermis", "hypodermis", NULL};
static const char *const k_chromophores[] = {"melanin", "eumelanin", "blood", "oxygenation", NULL};
static const char *const k_layer_fields[] = {"thickness", "g", "scattering", NULL};
static const char *const k_scattering_keys[] = {"mus_prime_500", "f_rayleigh", "b_mie", NULL};

static bool in_list(const char *key, const char *const *list)
{
    for (; *list; list++)
        if (!strcmp(key, *list)) return true;
    return false;
}

/* Every member of a layer is a chromophore or one of the layer's fields. */
static lucent_status check_layer_keys(const lucent_json_node *n)
{
    if (!cJSON_IsObject(n->json)) return lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "expected an object");
    for (const cJSON *c = n->json->child; c; c = c->next) {
        if (in_list(c->string, k_chromophores) || in_list(c->string, k_layer_fields)) continue;
        return lucent_json_fail(n, c->string, LUCENT_ERR_PARSE,
                                "unknown chromophore or field (chromophores: melanin, eumelanin, blood, oxygenation; "
                                "fields: thickness, g, scattering)");
    }
    return lucent_json_check_keys(
        n, (const char *const[]){"melanin", "eumelanin", "blood", "oxygenation", "thickness", "g", "scattering", NULL});
}

/* An optional number within r (default: *dest as it is). */
static lucent_status read_ranged(const lucent_json_node *n, const char *key, const range *r, double *dest)
{
    if (!lucent_json_has(n, key)) return LUCENT_OK;
    lucent_status s = lucent_json_number(n, key, dest);
    if (s == LUCENT_OK && !in_range(*dest, r))
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be %s, got %g", r->rule, *dest);
    return s;
}

/* scale: mm per unit of the file, so a coefficient in unit^-1 is scale times the one in mm^-1. */
static lucent_status read_skin_scattering(const lucent_json_node *layer, double scale, lucent_skin_layer *l)
{
    static const range b_mie = {0.0, 4.0, false, false, "in [0, 4]"};
    lucent_json_node n;
    lucent_status s = lucent_json_object(layer, "scattering", false, &n);
    if (s != LUCENT_OK || !n.json) return s;
    s = lucent_json_check_keys(&n, k_scattering_keys);
    double mus = l->scatter * scale; /* in the file's units^-1 */
    if (s == LUCENT_OK) s = read_ranged(&n, "mus_prime_500", &k_positive, &mus);
    if (s == LUCENT_OK) s = read_ranged(&n, "f_rayleigh", &k_unit, &l->f_rayleigh);
    if (s == LUCENT_OK) s = read_ranged(&n, "b_mie", &b_mie, &l->b_mie);
    l->scatter = mus / scale;
    return s;
}

/* scale: mm per unit of the file. */
static lucent_status read_skin_layer(const lucent_json_node *n, int kind, bool last, double scale, lucent_skin_layer *l)
{
    lucent_skin_layer_defaults((lucent_skin_layer_kind)kind, l);
    if (!last && !isfinite(l->thickness)) l->thickness = 1.0; /* a dermis above a hypodermis: about 1 mm */
    lucent_status s = check_layer_keys(n);
    double thickness = l->thickness / scale;
    if (s == LUCENT_OK) s = read_ranged(n, "thickness", &k_positive, &thickness);
    if (s == LUCENT_OK && !isfinite(thickness * scale) && lucent_json_has(n, "thickness"))
        s = lucent_json_fail(n, "thickness", LUCENT_ERR_PARSE, "must be finite, got %g mm", thickness * scale);
    l->thickness = thickness * scale;
    for (int i = 0; s == LUCENT_OK && k_chromophores[i]; i++) {
        double *v[] = {&l->melanin, &l->eumelanin, &l->blood, &l->oxygenation};
        s = read_ranged(n, k_chromophores[i], &k_unit, v[i]);
    }
    if (s == LUCENT_OK && !(l->melanin + l->blood <= 1.0))
        s = lucent_json_fail(n, "blood", LUCENT_ERR_PARSE, "melanin + blood must be <= 1, got %g",
                             l->melanin + l->blood);
    if (s == LUCENT_OK) s = read_ranged(n, "g", &k_g, &l->g);
    if (s == LUCENT_OK) s = read_skin_scattering(n, scale, l);
    return s;
}

static lucent_status read_skin(const lucent_json_node *n, lucent_material *m)
{
    double scale = 1.0;
    lucent_json_node skin = {0}, layer;
    lucent_status s = read_units(n, true, "skin", &scale);
    if (s == LUCENT_OK) s = lucent_json_object(n, "skin", true, &skin);
    if (s == LUCENT_OK && lucent_json_has(n, "g"))
        s = lucent_json_fail(n, "g", LUCENT_ERR_PARSE, "a skin gives g per layer (skin.<layer>.g)");
    if (s == LUCENT_OK && cJSON_IsObject(skin.json))
        for (const cJSON *c = skin.json->child; c && s == LUCENT_OK; c = c->next)
            if (!in_list(c->string, k_skin_layers))
                s = lucent_json_fail(&skin, c->string, LUCENT_ERR_PARSE,
                                     "unknown layer (known, top down: epidermis, dermis, hypodermis)");
    if (s == LUCENT_OK) s = lucent_json_check_keys(&skin, k_skin_layers);
    if (s != LUCENT_OK) return s;
    int last = -1;
    for (int k = 0; k < 3; k++)
        if (lucent_json_has(&skin, k_skin_layers[k])) last = k;
    if (s == LUCENT_OK && last < 0)
        s = lucent_json_fail(n, "skin", LUCENT_ERR_PARSE, "needs at least one layer (epidermis, dermis, hypodermis)");
    for (int k = 0; k <= last && s == LUCENT_OK; k++) {
        if (!lucent_json_has(&skin, k_skin_layers[k])) continue;
        s = lucent_json_object(&skin, k_skin_layers[k], true, &layer);
        if (s == LUCENT_OK) s = read_skin_layer(&layer, k, k == last, scale, &m->skin.layer[m->skin.layer_count++]);
    }
    if (s == LUCENT_OK && (s = lucent_skin_validate(&m->skin, m->name)) != LUCENT_OK)
        s = lucent_json_fail(n, "skin", LUCENT_ERR_PARSE, "%s", lucent_last_error());
    return s;
}

/* ---- one material ---- */

/* clang-format off */
static const char *const k_material_keys[] = {
    "name", "units", "g", "eta", "sigma_a", "sigma_s", "sigma_s_prime", "albedo", "mean_free_path",
    "reduced_albedo", "reduced_mean_free_path", "diffuse_reflectance", "diffuse_mean_free_path",
    "rd_published", "source", "derived", "skin", NULL};
/* clang-format on */

static lucent_status read_name(const lucent_json_node *n, const char *def, lucent_material *m)
{
    const char *name;
    lucent_status s = lucent_json_string_or(n, "name", def, &name);
    if (s != LUCENT_OK) return s;
    if (!name[0] || strlen(name) >= sizeof m->name)
        return lucent_json_fail(n, "name", LUCENT_ERR_PARSE, "must have 1 to %d characters", (int)sizeof m->name - 1);
    memcpy(m->name, name, strlen(name) + 1);
    return LUCENT_OK;
}

/* Informational members: checked for type, otherwise ignored. */
static lucent_status read_informational(const lucent_json_node *n)
{
    double rd[3];
    const char *text;
    lucent_json_node derived;
    lucent_status s = lucent_json_string_or(n, "source", "", &text);
    if (s == LUCENT_OK && lucent_json_has(n, "rd_published")) s = read_channels(n, "rd_published", &k_unit, rd);
    if (s == LUCENT_OK) s = lucent_json_object(n, "derived", false, &derived);
    return s;
}

/* Reads one material object; def_name is used when it has no "name" (NULL: required). */
lucent_status material_read_json(const lucent_json_node *n, const char *def_name, lucent_material *m)
{
    form f = FORM_COEFFICIENTS;
    memset(m, 0, sizeof *m);
    lucent_status s = lucent_json_check_keys(n, k_material_keys);
    if (s == LUCENT_OK) s = read_name(n, def_name, m);
    if (s == LUCENT_OK) s = lucent_json_number(n, "eta", &m->eta);
    if (s == LUCENT_OK && !in_range(m->eta, &k_eta))
        s = lucent_json_fail(n, "eta", LUCENT_ERR_PARSE, "must be %s, got %g", k_eta.rule, m->eta);
    if (s == LUCENT_OK && lucent_json_has(n, "skin")) {
        for (int o = 0; o < FORM_COUNT && s == LUCENT_OK; o++)
            for (int k = 0; k < 3 && s == LUCENT_OK; k++)
                if (k_form_keys[o][k] && lucent_json_has(n, k_form_keys[o][k]))
                    s = lucent_json_fail(n, k_form_keys[o][k], LUCENT_ERR_PARSE, "cannot be combined with \"skin\"");
        if (s == LUCENT_OK) s = read_skin(n, m);
        if (s == LUCENT_OK) s = read_informational(n);
        return s;
    }
    if (s == LUCENT_OK && lucent_json_has(n, "g")) s = read_channels(n, "g", &k_g, m->g);
    if (s == LUCENT_OK) s = pick_form(n, &f);
    if (s == LUCENT_OK) s = read_medium(n, f, m);
    if (s == LUCENT_OK) s = read_informational(n);
    if (s == LUCENT_OK && (s = lucent_material_validate(m)) != LUCENT_OK)
        s = lucent_json_fail(n, NULL, LUCENT_ERR_PARSE, "%s", lucent_last_error());
    return s;
}

/* ---- files ---- */

static lucent_status check_unique(const lucent_json_node *list, const lucent_material *m, int count)
{
    for (int i = 0; i < count; i++)
        for (int j = 0; j < i; j++)
            if (strcasecmp(m[i].name, m[j].name) == 0) {
                lucent_json_node e;
                lucent_json_element(list, i, &e);
                return lucent_json_fail(&e, "name", LUCENT_ERR_PARSE, "\"%s\" is also the name of materials[%d]",
                                        m[i].name, j);
            }
    return LUCENT_OK;
}

static const char *const k_file_keys[] = {"materials", "source", NULL};

static lucent_status read_list(const lucent_json_node *root, lucent_material **dest, int *count)
{
    lucent_json_node list, e;
    int n;
    const char *source;
    lucent_status s = lucent_json_check_keys(root, k_file_keys);
    if (s == LUCENT_OK) s = lucent_json_string_or(root, "source", "", &source);
    if (s == LUCENT_OK) s = lucent_json_array(root, "materials", true, &list, &n);
    if (s == LUCENT_OK && n == 0) s = lucent_json_fail(&list, NULL, LUCENT_ERR_PARSE, "expected at least one material");
    if (s != LUCENT_OK) return s;
    lucent_material *m = calloc((size_t)n, sizeof *m);
    if (!m) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", root->file);
    for (int i = 0; i < n && s == LUCENT_OK; i++) {
        s = lucent_json_element(&list, i, &e);
        if (s == LUCENT_OK) s = material_read_json(&e, NULL, &m[i]);
    }
    if (s == LUCENT_OK) s = check_unique(&list, m, n);
    if (s != LUCENT_OK) {
        free(m);
        return s;
    }
    *dest = m;
    *count = n;
    return LUCENT_OK;
}

/* The file's base name without extension: the default name of a lone material. */
static void stem(const char *file, char *dest, size_t size)
{
    const char *base = strrchr(file, '/');
    base = base ? base + 1 : file;
    size_t len = strcspn(base, ".");
    if (len == 0) len = strlen(base);
    if (len >= size) len = size - 1;
    memcpy(dest, base, len);
    dest[len] = '\0';
}

static lucent_status read_root(const cJSON *json, const char *file, lucent_material **dest, int *count)
{
    lucent_json_node root = lucent_json_root(json, file, "");
    if (!cJSON_IsObject(json))
        return lucent_json_fail(&root, NULL, LUCENT_ERR_PARSE,
                                "expected an object (a material, or {\"materials\": [...]})");
    if (lucent_json_has(&root, "materials")) return read_list(&root, dest, count);
    lucent_material *m = malloc(sizeof *m);
    if (!m) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", file);
    char def[LUCENT_MATERIAL_NAME_SIZE];
    stem(file, def, sizeof def);
    lucent_status s = material_read_json(&root, def[0] ? def : "material", m);
    if (s != LUCENT_OK) {
        free(m);
        return s;
    }
    *dest = m;
    *count = 1;
    return LUCENT_OK;
}

lucent_status lucent_material_parse(const char *text, const char *name, lucent_material **dest, int *count)
{
    cJSON *json;
    *dest = NULL;
    *count = 0;
    if (!name) name = "<json>";
    lucent_status s = lucent_json_parse_text(text, name, &json);
    if (s != LUCENT_OK) return s;
    s = read_root(json, name, dest, count);
    cJSON_Delete(json);
    return s;
}

lucent_status lucent_material_load(const char *path, lucent_material **dest, int *count)
{
    cJSON *json;
    *dest = NULL;
    *count = 0;
    lucent_status s = lucent_json_parse_file(path, &json);
    if (s != LUCENT_OK) return s;
    s = read_root(json, path, dest, count);
    cJSON_Delete(json);
    return s;
}

/* ---- one material from a preset name or a file ---- */

static lucent_status pick_from_file(const char *file, const char *name, lucent_material *dest)
{
    lucent_material *m;
    int n;
    lucent_status s = lucent_material_load(file, &m, &n);
    if (s != LUCENT_OK) return s;
    int found = -1;
    for (int i = 0; i < n && found < 0; i++)
        if (name ? strcasecmp(m[i].name, name) == 0 : n == 1) found = i;
    if (found >= 0)
        *dest = m[found];
    else if (name)
        s = lucent_error(LUCENT_ERR_NOT_FOUND, "%s: no material named \"%s\"", file, name);
    else
        s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: holds %d materials; name one as %s#NAME", file, n, file);
    free(m);
    return s;
}

static bool looks_like_file(const char *spec)
{
    size_t len = strlen(spec);
    return strchr(spec, '/') || (len > 5 && strcasecmp(spec + len - 5, ".json") == 0);
}

lucent_status lucent_material_resolve(const char *spec, lucent_material *dest)
{
    if (!spec) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "material: no name or file given (NULL)");
    const char *hash = strrchr(spec, '#');
    if (hash) {
        char *file = strndup(spec, (size_t)(hash - spec));
        if (!file) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        lucent_status s = pick_from_file(file, hash[1] ? hash + 1 : NULL, dest);
        free(file);
        return s;
    }
    if (looks_like_file(spec)) return pick_from_file(spec, NULL, dest);
    return lucent_material_preset_find(spec, dest);
}

/* ---- writing ---- */

static bool add_derived(cJSON *obj, const lucent_material *m)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    cJSON *o = cJSON_AddObjectToObject(obj, "derived");
    if (!o || !cJSON_AddStringToObject(o, "units", "coefficients in mm^-1, lengths in mm")) return false;
    bool ok = lucent_json_add_numbers(o, "sigma_s_prime", d.sigma_s_prime, 3) &&
              lucent_json_add_numbers(o, "sigma_t", d.sigma_t, 3) &&
              lucent_json_add_numbers(o, "sigma_t_prime", d.sigma_t_prime, 3) &&
              lucent_json_add_numbers(o, "albedo", d.albedo, 3) &&
              lucent_json_add_numbers(o, "albedo_prime", d.albedo_prime, 3) &&
              lucent_json_add_numbers(o, "sigma_tr", d.sigma_tr, 3) &&
              lucent_json_add_numbers(o, "diffusion", d.diffusion, 3) &&
              lucent_json_add_numbers(o, "mean_free_path", d.mfp, 3) &&
              lucent_json_add_numbers(o, "reduced_mean_free_path", d.mfp_prime, 3) &&
              lucent_json_add_numbers(o, "diffuse_mean_free_path", d.mfp_diffuse, 3) &&
              lucent_json_add_numbers(o, "rd_dipole", d.rd, 3);
    return ok && cJSON_AddNumberToObject(o, "fdr", d.fdr) && cJSON_AddNumberToObject(o, "a", d.a);
}

/* A skin's layers in mm (a semi-infinite layer has no thickness). */
static bool add_skin(cJSON *o, const lucent_skin *skin)
{
    cJSON *sk = cJSON_AddObjectToObject(o, "skin");
    bool ok = sk != NULL;
    for (int i = 0; ok && i < skin->layer_count; i++) {
        const lucent_skin_layer *l = &skin->layer[i];
        cJSON *j = cJSON_AddObjectToObject(sk, lucent_skin_layer_name(l->kind));
        cJSON *sc = j ? cJSON_CreateObject() : NULL;
        ok = j && sc && (!isfinite(l->thickness) || lucent_json_add_number(j, "thickness", l->thickness)) &&
             lucent_json_add_number(j, "melanin", l->melanin) && lucent_json_add_number(j, "eumelanin", l->eumelanin) &&
             lucent_json_add_number(j, "blood", l->blood) && lucent_json_add_number(j, "oxygenation", l->oxygenation) &&
             lucent_json_add_number(j, "g", l->g) && cJSON_AddItemToObject(j, "scattering", sc);
        if (j && sc && !ok) cJSON_Delete(sc);
        ok = ok && lucent_json_add_number(sc, "mus_prime_500", l->scatter) &&
             lucent_json_add_number(sc, "f_rayleigh", l->f_rayleigh) && lucent_json_add_number(sc, "b_mie", l->b_mie);
    }
    return ok;
}

static bool add_material(cJSON *list, const lucent_material *m, bool with_derived)
{
    cJSON *o = cJSON_CreateObject();
    if (!o || !cJSON_AddItemToArray(list, o)) {
        cJSON_Delete(o);
        return false;
    }
    if (m->skin.layer_count > 0) {
        bool ok = cJSON_AddStringToObject(o, "name", m->name) && cJSON_AddStringToObject(o, "units", "mm") &&
                  cJSON_AddNumberToObject(o, "eta", m->eta) && add_skin(o, &m->skin);
        return ok && (!with_derived || !m->skin.resolved || add_derived(o, m));
    }
    bool ok = cJSON_AddStringToObject(o, "name", m->name) && cJSON_AddStringToObject(o, "units", "mm^-1") &&
              lucent_json_add_numbers(o, "sigma_a", m->sigma_a, 3) &&
              lucent_json_add_numbers(o, "sigma_s", m->sigma_s, 3) && lucent_json_add_numbers(o, "g", m->g, 3) &&
              cJSON_AddNumberToObject(o, "eta", m->eta);
    return ok && (!with_derived || add_derived(o, m));
}

lucent_status lucent_material_to_json(const lucent_material *materials, int count, bool with_derived, char **dest)
{
    *dest = NULL;
    cJSON *root = cJSON_CreateObject();
    cJSON *list = root ? cJSON_AddArrayToObject(root, "materials") : NULL;
    bool ok = list != NULL;
    for (int i = 0; ok && i < count; i++) ok = add_material(list, &materials[i], with_derived);
    char *text = ok ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    size_t len = text ? strlen(text) : 0;
    *dest = text ? realloc(text, len + 2) : NULL;
    if (!*dest) {
        free(text);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory writing material JSON");
    }
    memcpy(*dest + len, "\n", 2);
    return LUCENT_OK;
}
