/* glTF 2.0's material extensions as an engine of the fit (lucent/engine.h): KHR_materials_ior,
 * _transmission, _volume, _diffuse_transmission and the draft KHR_materials_volume_scatter. There is
 * nothing to fit: the values are lucent/gltf.h's mapping of the material (src/material/gltf.c, the one
 * the pack writes), and the model is the medium a reader that honours the draft builds from them
 * (lucent_gltf_material_to_lucent: sigma_a from the attenuation, sigma_s from multiscatterColor by
 * Kulla & Conty's inversion, g = scatterAnisotropy, eta = ior) traced by Lucent's Monte Carlo under
 * that boundary (lucent/mc.h), on the truth's grid with a seed of its own, so that its error is the
 * mapping's (one g, no layers, the inversion's round trip) plus the two runs' noise. A reader of the
 * ratified extensions only sees a clear absorbing volume: no light comes back from below the surface,
 * e_p 100% and T 0, which the result states rather than computes. */
#include <stdlib.h>

#include "engine/internal.h"
#include "lucent/gltf.h"
#include "lucent/mc.h"

/* The glTF material's parameters, in the extensions' own names (lengths in metres). */
static void gltf_params(const lucent_gltf_material *g, lucent_engine_fit_result *r)
{
    eng_param(r, "baseColorFactor", "", 3, g->base_color);
    eng_param1(r, "KHR_materials_ior.ior", "", g->ior);
    eng_param1(r, "KHR_materials_transmission.transmissionFactor", "", g->transmission);
    eng_param1(r, "KHR_materials_volume.attenuationDistance", "m", g->attenuation_distance);
    eng_param(r, "KHR_materials_volume.attenuationColor", "", 3, g->attenuation_color);
    eng_param1(r, "KHR_materials_diffuse_transmission.diffuseTransmissionFactor", "", g->diffuse_transmission);
    eng_param(r, "KHR_materials_diffuse_transmission.diffuseTransmissionColorFactor", "", 3,
              g->diffuse_transmission_color);
    eng_param(r, "KHR_materials_volume_scatter.multiscatterColor (draft)", "", 3, g->multiscatter_color);
    eng_param1(r, "KHR_materials_volume_scatter.scatterAnisotropy (draft)", "", g->scatter_anisotropy);
}

lucent_status eng_fit_gltf(const lucent_engine_target *t, const lucent_engine_fit_desc *desc,
                           lucent_engine_fit_result *r)
{
    lucent_gltf_material g;
    lucent_material medium;
    /* thicknessFactor is the mesh's (lucent pack: its mean chord); any positive value gives the same medium */
    lucent_status s = lucent_gltf_material_from_lucent(&t->material, 0.0, 1.0, &g);
    if (s == LUCENT_OK) s = lucent_gltf_material_to_lucent(&g, &medium, NULL);
    if (s != LUCENT_OK) return lucent_error_context(s, "gltf: the extensions cannot carry %s", t->material.name);
    int n = t->profile->count;
    double *model[3] = {0}, total[3];
    uint64_t photons = desc && desc->model_photons ? desc->model_photons : LUCENT_ENGINE_MODEL_PHOTONS;
    static const char *const labels[] = {"glTF model R", "glTF model G", "glTF model B"};
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        lucent_mc_layer layer = {.n = medium.eta,
                                 .sigma_a = medium.sigma_a[c],
                                 .sigma_s = medium.sigma_s[c],
                                 .g = medium.g[c],
                                 .thickness = INFINITY};
        lucent_mc_result mc = {0};
        s = lucent_mc_run(&(lucent_mc_desc){.layers = &layer,
                                            .layer_count = 1,
                                            .photons = photons,
                                            .seed = 3000 + 4 * t->seed + (uint64_t)c, /* not the truth's */
                                            .grid = {.dr = t->profile->dr, .nr = n},
                                            .pool = desc ? desc->pool : NULL,
                                            .label = labels[c]},
                          &mc);
        model[c] = s == LUCENT_OK ? malloc((size_t)n * sizeof(double)) : NULL;
        if (s == LUCENT_OK && !model[c]) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "gltf: out of memory");
        for (int j = 0; s == LUCENT_OK && j < n; j++) model[c][j] = mc.rd_r[j];
        total[c] = mc.rd;
        lucent_mc_result_free(&mc);
    }
    if (s == LUCENT_OK) s = eng_finish(t, model, total, r);
    if (s == LUCENT_OK) {
        gltf_params(&g, r);
        eng_note(r,
                 "the errors are a reader's that honours the draft KHR_materials_volume_scatter: the medium it "
                 "builds, traced by Lucent's Monte Carlo (%llu photons per channel)",
                 (unsigned long long)photons);
        eng_note(r, "attenuation is the ratified extension's absorption; thicknessFactor is the mesh's (lucent pack "
                    "writes its mean chord 4 V / A); roughnessFactor the boundary's (the truth's boundary is smooth)");
        eng_cannot(r, "scattering without the draft: a reader of the ratified extensions only sees a clear absorbing "
                      "volume (e_p 100%%, T 0)");
        bool g_differs;
        double g_mean = eng_mean_g(t, &g_differs);
        if (t->layer_count > 1) eng_cannot(r, "layers (%d): the top material is mapped", t->layer_count);
        if (t->material.skin.layer_count > 0)
            eng_cannot(r, "layers (%d, a spectral skin): its equivalent medium is mapped",
                       t->material.skin.layer_count);
        if (g_differs) eng_cannot(r, "a g per channel or layer (scatterAnisotropy is one: their mean %.3g)", g_mean);
    }
    for (int c = 0; c < 3; c++) free(model[c]);
    return s;
}
