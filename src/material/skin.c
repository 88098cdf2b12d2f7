/* A skin from its chromophores: layer defaults, validation, and each layer's absorption and reduced
 * scattering at a wavelength (lucent/spectral.h; docs/skin.md). The spectra are data/spectra.json's. */
#include <math.h>
#include <string.h>

#include "lucent/spectral.h"
#include "material/spectra.h"

static const char *const k_layer_names[3] = {"epidermis", "dermis", "hypodermis"};

const char *lucent_skin_layer_name(int kind) { return kind >= 0 && kind < 3 ? k_layer_names[kind] : NULL; }

/* Thicknesses: epidermis about 100 um, dermis about 1 mm ("Modeling optical properties of human skin
 * using Mie theory ...", Optics Express 19(15) 14549, 2011, section 1); the dermis and hypodermis are
 * semi-infinite unless given a thickness. The other defaults are choices, stated in docs/skin.md:
 * oxygenation 0.75, eumelanin share 0.7 (Donner & Jensen 2006 vary it over [0, 1]), g 0.8 (only the
 * Monte Carlo reads g; the diffusion models see sigma_s'). */
void lucent_skin_layer_defaults(lucent_skin_layer_kind kind, lucent_skin_layer *dest)
{
    const lucent_spectra *sp = lucent_spectra_get();
    int k = kind >= 0 && kind < 3 ? (int)kind : 1;
    memset(dest, 0, sizeof *dest);
    dest->kind = k;
    dest->thickness = k == LUCENT_SKIN_EPIDERMIS ? 0.1 : INFINITY;
    dest->eumelanin = 0.7;
    dest->oxygenation = 0.75;
    dest->g = 0.8;
    if (sp) {
        dest->scatter = sp->scatter[k][0];
        dest->f_rayleigh = sp->scatter[k][1];
        dest->b_mie = sp->scatter[k][2];
    }
}

static lucent_status bad(const char *name, const lucent_skin_layer *l, const char *field, double v, const char *rule)
{
    const char *layer = lucent_skin_layer_name(l->kind);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: skin.%s.%s: must be %s, got %g", name, layer ? layer : "?",
                        field, rule, v);
}

static bool unit(double v) { return v >= 0.0 && v <= 1.0; }

static lucent_status validate_layer(const lucent_skin_layer *l, bool last, const char *name)
{
    if (!l->thickness || !(l->thickness > 0.0) || (!isfinite(l->thickness) && !last))
        return bad(name, l, "thickness", l->thickness, last ? "> 0 (or absent: semi-infinite)" : "finite and > 0");
    if (!unit(l->melanin)) return bad(name, l, "melanin", l->melanin, "in [0, 1]");
    if (!unit(l->eumelanin)) return bad(name, l, "eumelanin", l->eumelanin, "in [0, 1]");
    if (!unit(l->blood)) return bad(name, l, "blood", l->blood, "in [0, 1]");
    if (!unit(l->oxygenation)) return bad(name, l, "oxygenation", l->oxygenation, "in [0, 1]");
    if (!(l->melanin + l->blood <= 1.0)) return bad(name, l, "melanin + blood", l->melanin + l->blood, "<= 1");
    if (!(l->scatter > 0.0) || !isfinite(l->scatter))
        return bad(name, l, "scattering.mus_prime_500", l->scatter, "finite and > 0");
    if (!unit(l->f_rayleigh)) return bad(name, l, "scattering.f_rayleigh", l->f_rayleigh, "in [0, 1]");
    if (!(l->b_mie >= 0.0 && l->b_mie <= 4.0)) return bad(name, l, "scattering.b_mie", l->b_mie, "in [0, 4]");
    if (!(l->g > -1.0 && l->g < 1.0)) return bad(name, l, "g", l->g, "in (-1, 1)");
    return LUCENT_OK;
}

lucent_status lucent_skin_validate(const lucent_skin *skin, const char *name)
{
    if (!name || !name[0]) name = "skin";
    lucent_status s = lucent_spectra_ready();
    if (s != LUCENT_OK) return s;
    if (skin->layer_count < 1 || skin->layer_count > LUCENT_SKIN_MAX_LAYERS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: skin: 1 to %d layers, got %d", name,
                            LUCENT_SKIN_MAX_LAYERS, skin->layer_count);
    for (int i = 0; i < skin->layer_count; i++) {
        const lucent_skin_layer *l = &skin->layer[i];
        if (!lucent_skin_layer_name(l->kind))
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: skin.layer[%d]: unknown layer kind %d", name, i,
                                l->kind);
        if (i > 0 && l->kind <= skin->layer[i - 1].kind)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s: skin.%s: layers go top down (epidermis, dermis, hypodermis), each at most once",
                                name, lucent_skin_layer_name(l->kind));
        if ((s = validate_layer(l, i + 1 == skin->layer_count, name)) != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

/* Jacques 1998 / Donner & Jensen 2006: sigma_a = M sigma_mel + B sigma_blood + (1 - M - B) sigma_base;
 * Jacques 2013, eq. 2: mu_s' = a' (f_ray (lambda/500)^-4 + (1 - f_ray) (lambda/500)^-b_mie). */
void lucent_skin_coefficients(const lucent_skin *skin, int layer, double nm, double *sigma_a, double *sigma_s_prime)
{
    const lucent_skin_layer *l = &skin->layer[layer];
    double x = nm / 500.0;
    double sa = (1.0 - l->melanin - l->blood) * lucent_baseline_absorption(nm);
    if (l->melanin > 0.0) sa += l->melanin * lucent_melanin_absorption(nm, l->eumelanin);
    if (l->blood > 0.0) sa += l->blood * lucent_blood_absorption(nm, l->oxygenation);
    *sigma_a = sa;
    *sigma_s_prime = l->scatter * (l->f_rayleigh * pow(x, -4.0) + (1.0 - l->f_rayleigh) * pow(x, -l->b_mie));
}
