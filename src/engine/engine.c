/* The engines' table, the dispatch of a fit to its family, and the report of one material. */
#include <stdlib.h>
#include <string.h>

#include "engine/internal.h"

typedef enum family { FAMILY_BURLEY, FAMILY_SEPARABLE, FAMILY_GODOT, FAMILY_WALK, FAMILY_GLTF } family;

static const struct {
    const char *name, *title;
    family family;
} k_engines[LUCENT_ENGINE_COUNT] = {
    [LUCENT_ENGINE_UNREAL_BURLEY] = {"unreal-burley", "Unreal Engine 5 Subsurface Profile (Burley)", FAMILY_BURLEY},
    [LUCENT_ENGINE_UNREAL_SEPARABLE] = {"unreal-separable", "Unreal Engine Subsurface Profile (legacy separable)",
                                        FAMILY_SEPARABLE},
    [LUCENT_ENGINE_UNITY_HDRP] = {"unity-hdrp", "Unity HDRP Diffusion Profile", FAMILY_BURLEY},
    [LUCENT_ENGINE_BLENDER3_BURLEY] = {"blender3-burley", "Blender 3.x Principled BSDF (Christensen-Burley)",
                                       FAMILY_BURLEY},
    [LUCENT_ENGINE_BLENDER3_RANDOM_WALK] = {"blender3-rw", "Blender 3.x Principled BSDF (Random Walk)", FAMILY_WALK},
    [LUCENT_ENGINE_BLENDER4_BURLEY] = {"blender4-burley", "Blender 4.x Principled BSDF (Christensen-Burley)",
                                       FAMILY_BURLEY},
    [LUCENT_ENGINE_OPENPBR] = {"openpbr", "OpenPBR Surface 1.x (subsurface)", FAMILY_WALK},
    [LUCENT_ENGINE_GODOT] = {"godot", "Godot 4 StandardMaterial3D", FAMILY_GODOT},
    [LUCENT_ENGINE_GLTF] =
        {"gltf", "glTF 2.0 KHR_materials_volume, _transmission, _diffuse_transmission, draft _volume_scatter",
         FAMILY_GLTF},
};

const char *lucent_engine_name(lucent_engine_id engine)
{
    return engine >= 0 && engine < LUCENT_ENGINE_COUNT ? k_engines[engine].name : "unknown";
}

const char *lucent_engine_title(lucent_engine_id engine)
{
    return engine >= 0 && engine < LUCENT_ENGINE_COUNT ? k_engines[engine].title : "unknown";
}

lucent_status lucent_engine_parse(const char *name, lucent_engine_id *dest)
{
    for (int e = 0; name && e < LUCENT_ENGINE_COUNT; e++)
        if (!strcmp(name, k_engines[e].name)) {
            *dest = (lucent_engine_id)e;
            return LUCENT_OK;
        }
    char list[400] = "";
    for (int e = 0; e < LUCENT_ENGINE_COUNT; e++)
        snprintf(list + strlen(list), sizeof list - strlen(list), "%s%s", e ? ", " : "", k_engines[e].name);
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown engine \"%s\" (%s)", name ? name : "", list);
}

static lucent_status run_fit(const lucent_engine_target *target, lucent_engine_id engine,
                             const lucent_engine_fit_desc *desc, bool hand, lucent_engine_fit_result *dest)
{
    *dest = (lucent_engine_fit_result){.engine = engine, .hand = hand, .transmit_error = NAN};
    if (engine < 0 || engine >= LUCENT_ENGINE_COUNT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine fit: unknown engine %d", (int)engine);
    if (!target || !target->profile)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine fit: the target is empty");
    lucent_status s;
    switch (k_engines[engine].family) {
    case FAMILY_BURLEY: s = eng_fit_burley(target, engine, hand, dest); break;
    case FAMILY_WALK: s = eng_fit_walk(target, engine, hand, desc, dest); break;
    case FAMILY_SEPARABLE:
        s = hand ? lucent_error(LUCENT_ERR_UNSUPPORTED, "%s has no radius for the hand mapping", k_engines[engine].name)
                 : eng_fit_separable(target, dest);
        break;
    case FAMILY_GLTF:
        s = hand ? lucent_error(LUCENT_ERR_UNSUPPORTED, "%s has no radius for the hand mapping", k_engines[engine].name)
                 : eng_fit_gltf(target, desc, dest);
        break;
    default:
        s = hand ? lucent_error(LUCENT_ERR_UNSUPPORTED, "%s has no radius for the hand mapping", k_engines[engine].name)
                 : eng_fit_godot(target, dest);
        break;
    }
    if (s != LUCENT_OK) {
        lucent_engine_fit_result_free(dest);
        return lucent_error_context(s, "%s", target->material.name);
    }
    if (hand) eng_note(dest, "the hand mapping: radius = 1 / sigma_tr of %s, colour = T", target->material.name);
    return LUCENT_OK;
}

lucent_status lucent_engine_fit(const lucent_engine_target *target, lucent_engine_id engine,
                                const lucent_engine_fit_desc *desc, lucent_engine_fit_result *dest)
{
    return run_fit(target, engine, desc, false, dest);
}

lucent_status lucent_engine_hand(const lucent_engine_target *target, lucent_engine_id engine,
                                 const lucent_engine_fit_desc *desc, lucent_engine_fit_result *dest)
{
    return run_fit(target, engine, desc, true, dest);
}

void lucent_engine_fit_result_free(lucent_engine_fit_result *result)
{
    if (!result) return;
    lucent_profile_destroy(result->profile);
    *result = (lucent_engine_fit_result){0};
}

/* ---- the report ---- */

static bool has_radius(lucent_engine_id e)
{
    return k_engines[e].family == FAMILY_BURLEY || k_engines[e].family == FAMILY_WALK;
}

lucent_status lucent_engine_report_run(const lucent_engine_report_desc *desc, lucent_engine_report *dest)
{
    *dest = (lucent_engine_report){0};
    if (!desc) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine report: no desc");
    if (desc->engine_count < 0 || desc->engine_count > LUCENT_ENGINE_COUNT || (desc->engine_count && !desc->engines))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "engine report: engine_count: 0 to %d engines",
                            LUCENT_ENGINE_COUNT);
    lucent_status s = lucent_engine_target_build(&desc->target, &dest->target);
    int count = desc->engine_count ? desc->engine_count : LUCENT_ENGINE_COUNT;
    for (int i = 0; i < count && s == LUCENT_OK; i++) {
        lucent_engine_id e = desc->engine_count ? desc->engines[i] : (lucent_engine_id)i;
        dest->count = i + 1;
        s = lucent_engine_fit(&dest->target, e, &desc->fit, &dest->fits[i]);
        if (s == LUCENT_OK && desc->hand && has_radius(e) && eng_hand_radius(&dest->target, (double[3]){0}))
            s = lucent_engine_hand(&dest->target, e, &desc->fit, &dest->hand[i]);
    }
    if (s != LUCENT_OK) lucent_engine_report_free(dest);
    return s;
}

void lucent_engine_report_free(lucent_engine_report *report)
{
    if (!report) return;
    for (int i = 0; i < LUCENT_ENGINE_COUNT; i++) {
        lucent_engine_fit_result_free(&report->fits[i]);
        lucent_engine_fit_result_free(&report->hand[i]);
    }
    lucent_engine_target_free(&report->target);
    *report = (lucent_engine_report){0};
}

lucent_status lucent_engine_report_create(const lucent_engine_report_desc *desc, lucent_engine_report **dest)
{
    *dest = malloc(sizeof **dest);
    if (!*dest) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "engine report: out of memory");
    lucent_status s = lucent_engine_report_run(desc, *dest);
    if (s != LUCENT_OK) free(*dest), *dest = NULL;
    return s;
}

void lucent_engine_report_destroy(lucent_engine_report *report)
{
    lucent_engine_report_free(report);
    free(report);
}
