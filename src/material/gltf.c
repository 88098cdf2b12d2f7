/* Lucent materials in glTF 2.0 (lucent/gltf.h): the mapping to KHR_materials_ior, _transmission,
 * _volume (absorption), _diffuse_transmission and the draft _volume_scatter, and back; the material
 * object's JSON both ways (src/material/gltf.h). docs/pack.md#gltf. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "material/gltf.h"

/* KHR_materials_volume_scatter (draft, Khronos glTF pull request 2453), "Multi-Scatter Albedo": the
 * single-scattering albedo from the multiple-scattering albedo m, after Kulla & Conty 2017. */
static double draft_s(double m) { return 4.09712 + 4.20863 * m - sqrt(9.59217 + 41.6808 * m + 17.7126 * m * m); }

double lucent_gltf_single_albedo(double multiscatter)
{
    double m = fmin(fmax(multiscatter, 0), 1), s = draft_s(m);
    return fmin(fmax(1 - s * s, 0), 1);
}

/* s(m) falls from 0.999997 at m = 0 through 0 just below m = 1: bisect s(m) = sqrt(1 - albedo). */
double lucent_gltf_multiscatter_albedo(double albedo)
{
    double want = sqrt(1 - fmin(fmax(albedo, 0), 1)), lo = 0, hi = 1;
    if (draft_s(0) <= want) return 0;
    for (int i = 0; i < 200 && hi - lo > 1e-15; i++) {
        double mid = 0.5 * (lo + hi);
        if (draft_s(mid) > want)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

lucent_status lucent_gltf_material_from_lucent(const lucent_material *m, double roughness_alpha, double thickness_m,
                                               lucent_gltf_material *dest)
{
    lucent_status s = lucent_material_validate(m);
    if (s != LUCENT_OK) return s;
    if (!(roughness_alpha >= 0 && roughness_alpha <= 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: roughness %g: must be in [0, 1]", m->name,
                            roughness_alpha);
    if (!(thickness_m > 0 && thickness_m < INFINITY))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: thickness %g m: must be > 0", m->name, thickness_m);
    lucent_gltf_material g = {.metallic = 0, .roughness = sqrt(roughness_alpha), .ior = m->eta};
    snprintf(g.name, sizeof g.name, "%s", m->name);
    g.has_transmission = g.has_volume = g.has_diffuse_transmission = g.has_scatter = true;
    g.transmission = 1, g.diffuse_transmission = 1, g.thickness = thickness_m;
    double most = fmax(m->sigma_a[0], fmax(m->sigma_a[1], m->sigma_a[2])), dist_mm = 0.1 / most;
    g.attenuation_distance = most > 0 ? dist_mm / 1000 : INFINITY;
    double g_sum = 0;
    for (int c = 0; c < 3; c++) {
        g.base_color[c] = 1, g.diffuse_transmission_color[c] = 1;
        /* light through x keeps exp(-sigma_a x) = colour^(x / distance) */
        g.attenuation_color[c] = most > 0 ? exp(-m->sigma_a[c] * dist_mm) : 1;
        g.multiscatter_color[c] = lucent_gltf_multiscatter_albedo(m->sigma_s[c] / (m->sigma_a[c] + m->sigma_s[c]));
        g_sum += m->g[c];
    }
    g.scatter_anisotropy = g_sum / 3;
    *dest = g;
    return LUCENT_OK;
}

/* The medium of a volume: sigma_a from the attenuation (ratified KHR_materials_volume), sigma_s from
 * the draft's albedo when it is there. */
static lucent_status volume_medium(const lucent_gltf_material *g, lucent_material *d)
{
    for (int c = 0; c < 3; c++) {
        double col = g->attenuation_color[c], dist_mm = g->attenuation_distance * 1000;
        if (!(col > 0))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s: attenuationColor[%d] is 0: an infinite absorption Lucent cannot render", d->name,
                                c);
        d->sigma_a[c] = isinf(dist_mm) || col >= 1 ? 0 : -log(col) / dist_mm;
        d->g[c] = g->has_scatter ? g->scatter_anisotropy : 0;
        if (!g->has_scatter) continue;
        double a = lucent_gltf_single_albedo(g->multiscatter_color[c]);
        if (g->multiscatter_color[c] >= 1 && d->sigma_a[c] > 0)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s: multiscatterColor[%d] = %g means no absorption, but the attenuation absorbs: the "
                                "scattering would be infinite",
                                d->name, c, g->multiscatter_color[c]);
        d->sigma_s[c] = g->multiscatter_color[c] >= 1 ? 0 : d->sigma_a[c] * a / (1 - a);
    }
    return LUCENT_OK;
}

lucent_status lucent_gltf_material_to_lucent(const lucent_gltf_material *g, lucent_material *dest,
                                             double *roughness_alpha)
{
    lucent_material d = {.eta = g->ior};
    snprintf(d.name, sizeof d.name, "%s", g->name[0] ? g->name : "gltf");
    if (!(g->ior >= LUCENT_MATERIAL_ETA_MIN && g->ior <= LUCENT_MATERIAL_ETA_MAX))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: ior %g: Lucent's eta must be in [1, 3]", d.name, g->ior);
    if (!(g->roughness >= 0 && g->roughness <= 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: roughness %g: must be in [0, 1]", d.name, g->roughness);
    lucent_status s = LUCENT_OK;
    if (g->has_volume && g->thickness > 0) {
        s = volume_medium(g, &d);
    } else {
        for (int c = 0; c < 3; c++) { /* a surface: the look of a dense medium of the base colour */
            double m = fmin(g->base_color[c], LUCENT_GLTF_SURFACE_MAX_ALBEDO), sigma_t = 1 / LUCENT_GLTF_SURFACE_MFP_MM;
            double a = lucent_gltf_single_albedo(m);
            d.sigma_s[c] = a * sigma_t, d.sigma_a[c] = (1 - a) * sigma_t, d.g[c] = 0;
        }
    }
    for (int c = 0; s == LUCENT_OK && c < 3; c++)
        if (!(d.sigma_a[c] + d.sigma_s[c] > 0))
            s = lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                             "%s: channel %d neither absorbs nor scatters (no attenuation%s): not a medium", d.name, c,
                             g->has_scatter ? "; the draft's scattering follows from the absorption" : "");
    if (s == LUCENT_OK) s = lucent_material_validate(&d);
    if (s != LUCENT_OK) return s;
    *dest = d;
    if (roughness_alpha) *roughness_alpha = g->roughness * g->roughness;
    return LUCENT_OK;
}

/* ---- JSON ---- */

static cJSON *add_object(cJSON *parent, const char *key)
{
    return parent ? cJSON_AddObjectToObject(parent, key) : NULL;
}

static bool add_color(cJSON *o, const char *key, const double c[3]) { return lucent_json_add_numbers(o, key, c, 3); }

static bool add_extras(cJSON *o, const lucent_material *m, double roughness_alpha)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    cJSON *lu = add_object(add_object(o, "extras"), "lucent");
    return lu && cJSON_AddStringToObject(lu, "units", "mm^-1") &&
           lucent_json_add_numbers(lu, "sigma_a", m->sigma_a, 3) &&
           lucent_json_add_numbers(lu, "sigma_s", m->sigma_s, 3) && lucent_json_add_numbers(lu, "g", m->g, 3) &&
           lucent_json_add_number(lu, "eta", m->eta) && lucent_json_add_number(lu, "roughness", roughness_alpha) &&
           lucent_json_add_numbers(lu, "rd", d.rd, 3) &&
           cJSON_AddStringToObject(
               lu, "note",
               "Lucent's exact medium (sigma_a, sigma_s per RGB channel in mm^-1, Henyey-Greenstein "
               "g, eta) and the boundary's microfacet alpha (roughness); rd: the dipole's total "
               "diffuse reflectance, the colour for a renderer without volume scattering");
}

static bool add_extensions(cJSON *o, const lucent_gltf_material *g)
{
    cJSON *ext = add_object(o, "extensions"), *e;
    bool ok = (e = add_object(ext, LUCENT_GLTF_EXT_IOR)) && lucent_json_add_number(e, "ior", g->ior);
    ok = ok && (e = add_object(ext, LUCENT_GLTF_EXT_TRANSMISSION)) &&
         lucent_json_add_number(e, "transmissionFactor", g->transmission);
    ok = ok && (e = add_object(ext, LUCENT_GLTF_EXT_VOLUME)) &&
         lucent_json_add_number(e, "thicknessFactor", g->thickness);
    if (ok && isfinite(g->attenuation_distance))
        ok = lucent_json_add_number(e, "attenuationDistance", g->attenuation_distance) &&
             add_color(e, "attenuationColor", g->attenuation_color);
    ok = ok && (e = add_object(ext, LUCENT_GLTF_EXT_DIFFUSE_TRANSMISSION)) &&
         lucent_json_add_number(e, "diffuseTransmissionFactor", g->diffuse_transmission) &&
         add_color(e, "diffuseTransmissionColorFactor", g->diffuse_transmission_color);
    ok = ok && (e = add_object(ext, LUCENT_GLTF_EXT_VOLUME_SCATTER)) &&
         add_color(e, "multiscatterColor", g->multiscatter_color) &&
         lucent_json_add_number(e, "scatterAnisotropy", g->scatter_anisotropy);
    cJSON *x = ok ? add_object(e, "extras") : NULL;
    return x && cJSON_AddStringToObject(x, "status",
                                        "draft (Khronos glTF pull request 2453): it reads attenuationColor and "
                                        "attenuationDistance as the extinction, ratified KHR_materials_volume as "
                                        "the absorption, which is what they hold here");
}

cJSON *material_gltf_object(const lucent_gltf_material *g, const lucent_material *exact, double roughness_alpha)
{
    cJSON *o = cJSON_CreateObject(), *pbr;
    double base[4] = {g->base_color[0], g->base_color[1], g->base_color[2], 1};
    bool ok = o && cJSON_AddStringToObject(o, "name", g->name) && (pbr = add_object(o, "pbrMetallicRoughness")) &&
              lucent_json_add_numbers(pbr, "baseColorFactor", base, 4) &&
              lucent_json_add_number(pbr, "metallicFactor", g->metallic) &&
              lucent_json_add_number(pbr, "roughnessFactor", g->roughness) && add_extensions(o, g) &&
              (!exact || add_extras(o, exact, roughness_alpha));
    if (!ok) cJSON_Delete(o);
    return ok ? o : NULL;
}

lucent_status lucent_gltf_material_json(const lucent_material *m, double roughness_alpha, double thickness_m,
                                        char **dest)
{
    *dest = NULL;
    lucent_gltf_material g;
    lucent_status s = lucent_gltf_material_from_lucent(m, roughness_alpha, thickness_m, &g);
    if (s != LUCENT_OK) return s;
    cJSON *o = material_gltf_object(&g, m, roughness_alpha);
    *dest = o ? cJSON_Print(o) : NULL;
    cJSON_Delete(o);
    return *dest ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
}

/* -- reading -- */

/* An optional number in [lo, hi] (open ends where said). */
static lucent_status number_in(const lucent_json_node *n, const char *key, double def, double lo, double hi, bool open,
                               double *dest)
{
    lucent_status s = lucent_json_number_or(n, key, def, dest);
    if (s == LUCENT_OK && !(open ? *dest > lo && *dest < hi : *dest >= lo && *dest <= hi))
        s = lucent_json_fail(n, key, LUCENT_ERR_PARSE, "must be in %c%g, %g%c, got %g", open ? '(' : '[', lo, hi,
                             open ? ')' : ']', *dest);
    return s;
}

/* An optional colour of `count` numbers in [0, 1]. */
static lucent_status color_in(const lucent_json_node *n, const char *key, int count, double def, double *dest)
{
    for (int c = 0; c < count; c++) dest[c] = def;
    if (!lucent_json_has(n, key)) return LUCENT_OK;
    lucent_status s = lucent_json_numbers(n, key, count, false, dest);
    for (int c = 0; s == LUCENT_OK && c < count; c++)
        if (!(dest[c] >= 0 && dest[c] <= 1)) {
            char where[80];
            snprintf(where, sizeof where, "%s[%d]", key, c);
            s = lucent_json_fail(n, where, LUCENT_ERR_PARSE, "must be in [0, 1], got %g", dest[c]);
        }
    return s;
}

static lucent_status read_pbr(const lucent_json_node *n, lucent_gltf_material *g)
{
    lucent_json_node p;
    double base[4];
    lucent_status s = lucent_json_object(n, "pbrMetallicRoughness", false, &p);
    if (s == LUCENT_OK && !p.json) { /* absent: glTF's defaults */
        g->base_color[0] = g->base_color[1] = g->base_color[2] = 1;
        g->metallic = g->roughness = 1;
        return LUCENT_OK;
    }
    if (s == LUCENT_OK) s = color_in(&p, "baseColorFactor", 4, 1, base);
    if (s == LUCENT_OK) s = number_in(&p, "metallicFactor", 1, 0, 1, false, &g->metallic);
    if (s == LUCENT_OK) s = number_in(&p, "roughnessFactor", 1, 0, 1, false, &g->roughness);
    if (s == LUCENT_OK) memcpy(g->base_color, base, sizeof g->base_color);
    return s;
}

static lucent_status read_volume(const lucent_json_node *e, lucent_gltf_material *g)
{
    lucent_status s = number_in(e, "thicknessFactor", 0, 0, INFINITY, false, &g->thickness);
    if (s == LUCENT_OK) s = lucent_json_number_or(e, "attenuationDistance", INFINITY, &g->attenuation_distance);
    if (s == LUCENT_OK && !(g->attenuation_distance > 0))
        s = lucent_json_fail(e, "attenuationDistance", LUCENT_ERR_PARSE, "must be > 0, got %g",
                             g->attenuation_distance);
    if (s == LUCENT_OK) s = color_in(e, "attenuationColor", 3, 1, g->attenuation_color);
    return s;
}

static lucent_status read_extensions(const lucent_json_node *n, lucent_gltf_material *g)
{
    lucent_json_node ext, e;
    lucent_status s = lucent_json_object(n, "extensions", false, &ext);
    if (s == LUCENT_OK && ext.json && (s = lucent_json_object(&ext, LUCENT_GLTF_EXT_IOR, false, &e)) == LUCENT_OK &&
        e.json)
        s = lucent_json_number_or(&e, "ior", 1.5, &g->ior);
    if (s == LUCENT_OK && ext.json &&
        (s = lucent_json_object(&ext, LUCENT_GLTF_EXT_TRANSMISSION, false, &e)) == LUCENT_OK &&
        (g->has_transmission = e.json != NULL))
        s = number_in(&e, "transmissionFactor", 0, 0, 1, false, &g->transmission);
    if (s == LUCENT_OK && ext.json && (s = lucent_json_object(&ext, LUCENT_GLTF_EXT_VOLUME, false, &e)) == LUCENT_OK &&
        (g->has_volume = e.json != NULL))
        s = read_volume(&e, g);
    if (s == LUCENT_OK && ext.json &&
        (s = lucent_json_object(&ext, LUCENT_GLTF_EXT_DIFFUSE_TRANSMISSION, false, &e)) == LUCENT_OK &&
        (g->has_diffuse_transmission = e.json != NULL)) {
        s = number_in(&e, "diffuseTransmissionFactor", 0, 0, 1, false, &g->diffuse_transmission);
        if (s == LUCENT_OK) s = color_in(&e, "diffuseTransmissionColorFactor", 3, 1, g->diffuse_transmission_color);
    }
    if (s == LUCENT_OK && ext.json &&
        (s = lucent_json_object(&ext, LUCENT_GLTF_EXT_VOLUME_SCATTER, false, &e)) == LUCENT_OK &&
        (g->has_scatter = e.json != NULL)) {
        s = color_in(&e, "multiscatterColor", 3, 0, g->multiscatter_color);
        if (s == LUCENT_OK) s = number_in(&e, "scatterAnisotropy", 0, -1, 1, true, &g->scatter_anisotropy);
    }
    return s;
}

/* extras.lucent: the exact medium, read as strictly as a material file (material_read_json). */
static lucent_status read_exact(const lucent_json_node *n, const lucent_gltf_material *g, bool *has, lucent_material *m,
                                double *roughness)
{
    lucent_json_node x, lu;
    lucent_status s = lucent_json_object(n, "extras", false, &x);
    if (s == LUCENT_OK && x.json && cJSON_IsObject(x.json))
        s = lucent_json_object(&x, "lucent", false, &lu);
    else
        lu.json = NULL;
    if (s != LUCENT_OK || !lu.json) return s;
    lucent_material d = {0};
    snprintf(d.name, sizeof d.name, "%s", g->name[0] ? g->name : "gltf");
    const char *units;
    s = lucent_json_string(&lu, "units", &units);
    if (s == LUCENT_OK && strcmp(units, "mm^-1") != 0)
        s = lucent_json_fail(&lu, "units", LUCENT_ERR_PARSE, "expected \"mm^-1\", got \"%s\"", units);
    if (s == LUCENT_OK) s = lucent_json_numbers(&lu, "sigma_a", 3, false, d.sigma_a);
    if (s == LUCENT_OK) s = lucent_json_numbers(&lu, "sigma_s", 3, false, d.sigma_s);
    if (s == LUCENT_OK) s = lucent_json_numbers(&lu, "g", 3, true, d.g);
    if (s == LUCENT_OK) s = lucent_json_number(&lu, "eta", &d.eta);
    if (s == LUCENT_OK) s = number_in(&lu, "roughness", g->roughness * g->roughness, 0, 1, false, roughness);
    if (s == LUCENT_OK && lucent_material_validate(&d) != LUCENT_OK)
        s = lucent_json_fail(&lu, NULL, LUCENT_ERR_PARSE, "%s", lucent_last_error());
    if (s == LUCENT_OK) *m = d, *has = true;
    return s;
}

/* The name, cut to fit at a UTF-8 character's start. */
static void copy_name(const char *src, char *dest, size_t size)
{
    size_t n = strlen(src);
    if (n >= size) {
        n = size - 1;
        while (n > 0 && ((unsigned char)src[n] & 0xC0) == 0x80) n--;
    }
    memcpy(dest, src, n);
    dest[n] = '\0';
}

lucent_status material_gltf_read(const lucent_json_node *n, lucent_gltf_material *g, bool *has_exact,
                                 lucent_material *exact, double *exact_roughness)
{
    memset(g, 0, sizeof *g);
    g->ior = 1.5, g->attenuation_distance = INFINITY;
    for (int c = 0; c < 3; c++) g->attenuation_color[c] = g->diffuse_transmission_color[c] = 1;
    *has_exact = false;
    const char *name;
    lucent_status s = lucent_json_string_or(n, "name", "", &name);
    if (s == LUCENT_OK) copy_name(name, g->name, sizeof g->name);
    if (s == LUCENT_OK) s = read_pbr(n, g);
    if (s == LUCENT_OK) s = read_extensions(n, g);
    if (s == LUCENT_OK) s = read_exact(n, g, has_exact, exact, exact_roughness);
    return s;
}
