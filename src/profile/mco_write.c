/* The comparison of a Lucent run with an .mco written out: CSV (a row per bin) and JSON (the
 * summary and every bin), in MCML's units (cm), as the file compared with. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/json.h"
#include "lucent/mcml.h"
#include "mcml_internal.h"

/* Lucent's mm-based densities to the .mco's cm-based ones. */
static double to_cm_units(lucent_mco_section_id id)
{
    switch (id) {
    case LUCENT_MCO_A_Z: return MCML_CM;
    case LUCENT_MCO_RD_R:
    case LUCENT_MCO_TT_R: return MCML_CM * MCML_CM;
    default: return 1.0;
    }
}

/* Where bin i sits: "Rd", "layer 2", or the bin centre on the section's axis. */
static void position(const lucent_mco_section *s, int i, char *dest, size_t size)
{
    if (s->id == LUCENT_MCO_RAT)
        snprintf(dest, size, "%s", lucent_mco_rat_name(i));
    else if (s->id == LUCENT_MCO_A_L)
        snprintf(dest, size, "layer %d", i + 1);
    else
        snprintf(dest, size, "%.6g", (i + 0.5) * s->width);
}

lucent_status lucent_mco_comparison_write_csv(const char *path, const lucent_mco_comparison *c)
{
    lucent_atomic_file *af;
    FILE *f;
    lucent_status st = lucent_atomic_open(path, &af, &f);
    if (st != LUCENT_OK) return st;
    fprintf(f, "section,bin,position,axis,unit,lucent,lucent_se,mcml,mcml_se,diff_se,state\n");
    fprintf(f, "Rsp,0,Rsp,,-,%.9g,0,%.9g,0,,%s\n", c->rsp_lucent, c->rsp_mcml, c->rsp_equal ? "equal" : "differs");
    for (int k = 0; k < LUCENT_MCO_SECTION_COUNT; k++) {
        const lucent_mco_section *s = &c->sections[k];
        double u = to_cm_units(s->id);
        for (int i = 0; i < s->count; i++) {
            const lucent_mco_bin *b = &s->bins[i];
            char where[32];
            position(s, i, where, sizeof where);
            fprintf(f, "%s,%d,%s,%s,%s,%.9g,%.9g,%.9g,%.9g,", lucent_mco_section_name(s->id), i, where,
                    lucent_mco_section_axis(s->id), lucent_mco_section_unit(s->id), b->lucent * u, b->lucent_se * u,
                    b->mcml * u, b->mcml_se * u);
            if (b->state == LUCENT_MCO_COMPARED) fprintf(f, "%.4f", b->z);
            fprintf(f, ",%s\n", lucent_mco_bin_state_name(b->state));
        }
    }
    if (ferror(f)) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}

static bool add_bin(cJSON *bins, const lucent_mco_section *s, int i)
{
    const lucent_mco_bin *b = &s->bins[i];
    double u = to_cm_units(s->id);
    char where[32];
    position(s, i, where, sizeof where);
    cJSON *o = cJSON_CreateObject();
    if (!o || !cJSON_AddItemToArray(bins, o)) {
        cJSON_Delete(o);
        return false;
    }
    bool ok = cJSON_AddNumberToObject(o, "bin", i) && cJSON_AddStringToObject(o, "position", where) &&
              cJSON_AddNumberToObject(o, "lucent", b->lucent * u) &&
              cJSON_AddNumberToObject(o, "lucent_se", b->lucent_se * u) &&
              cJSON_AddNumberToObject(o, "mcml", b->mcml * u) &&
              cJSON_AddNumberToObject(o, "mcml_se", b->mcml_se * u) &&
              cJSON_AddStringToObject(o, "state", lucent_mco_bin_state_name(b->state));
    if (ok && b->state == LUCENT_MCO_COMPARED) ok = cJSON_AddNumberToObject(o, "diff_se", b->z);
    return ok;
}

static bool add_counts(cJSON *o, int compared, int beyond3, double chi2)
{
    return cJSON_AddNumberToObject(o, "compared", compared) && cJSON_AddNumberToObject(o, "beyond_3se", beyond3) &&
           cJSON_AddNumberToObject(o, "beyond_3se_expected_by_chance", 0.0027 * compared) &&
           (compared ? cJSON_AddNumberToObject(o, "chi2_per_bin", chi2 / compared)
                     : cJSON_AddNullToObject(o, "chi2_per_bin"));
}

static bool add_section(cJSON *sections, const lucent_mco_section *s)
{
    cJSON *o = cJSON_CreateObject();
    if (!o || !cJSON_AddItemToArray(sections, o)) {
        cJSON_Delete(o);
        return false;
    }
    bool ok = cJSON_AddStringToObject(o, "name", lucent_mco_section_name(s->id)) &&
              cJSON_AddStringToObject(o, "unit", lucent_mco_section_unit(s->id)) &&
              cJSON_AddStringToObject(o, "axis", lucent_mco_section_axis(s->id)) &&
              cJSON_AddNumberToObject(o, "width", s->width) && add_counts(o, s->compared, s->beyond3, s->chi2) &&
              cJSON_AddNumberToObject(o, "sparse", s->sparse) &&
              cJSON_AddNumberToObject(o, "unresolved", s->unresolved) &&
              cJSON_AddNumberToObject(o, "incomparable", s->incomparable);
    if (ok && s->worst >= 0) {
        cJSON *w = cJSON_AddObjectToObject(o, "worst");
        ok = w && cJSON_AddNumberToObject(w, "bin", s->worst) &&
             cJSON_AddNumberToObject(w, "diff_se", s->bins[s->worst].z);
    }
    cJSON *bins = ok ? cJSON_AddArrayToObject(o, "bins") : NULL;
    ok = bins != NULL;
    for (int i = 0; ok && i < s->count; i++) ok = add_bin(bins, s, i);
    return ok;
}

static cJSON *comparison_json(const lucent_mco_comparison *c)
{
    cJSON *root = cJSON_CreateObject();
    cJSON *rsp = root ? cJSON_AddObjectToObject(root, "rsp") : NULL;
    bool ok = rsp && cJSON_AddStringToObject(root, "units", "MCML's: cm") &&
              cJSON_AddNumberToObject(root, "lucent_photons", (double)c->lucent_photons) &&
              cJSON_AddNumberToObject(root, "mcml_photons", (double)c->mcml_photons) &&
              cJSON_AddNumberToObject(root, "mcml_se_scale", c->se_scale) &&
              cJSON_AddNumberToObject(rsp, "lucent", c->rsp_lucent) &&
              cJSON_AddNumberToObject(rsp, "mcml", c->rsp_mcml) && cJSON_AddBoolToObject(rsp, "equal", c->rsp_equal) &&
              cJSON_AddBoolToObject(root, "a_l_on_grid", c->a_l_on_grid);
    cJSON *summary = ok ? cJSON_AddObjectToObject(root, "summary") : NULL;
    ok = summary && add_counts(summary, c->compared, c->beyond3, c->chi2);
    cJSON *sections = ok ? cJSON_AddArrayToObject(root, "sections") : NULL;
    ok = sections != NULL;
    for (int k = 0; ok && k < LUCENT_MCO_SECTION_COUNT; k++) ok = add_section(sections, &c->sections[k]);
    if (!ok) {
        cJSON_Delete(root);
        return NULL;
    }
    return root;
}

lucent_status lucent_mco_comparison_write_json(const char *path, const lucent_mco_comparison *c)
{
    cJSON *root = comparison_json(c);
    if (!root) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    lucent_status s = lucent_json_write_file(path, root);
    cJSON_Delete(root);
    return s;
}
