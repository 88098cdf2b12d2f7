/* A Lucent run compared with an MCML output file, bin by bin, in standard errors
 * (docs/mcml.md). MCML writes no standard errors; both programs score the same estimator
 * (weighted packets, absorption by weight, the same roulette: Wang, Jacques & Zheng 1995,
 * section 3), so the variance per photon is the same and MCML's standard error is Lucent's
 * scaled by sqrt(N_lucent / N_mcml). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mcml.h"
#include "mcml_internal.h"

#define SPARSE_REL_SE 0.3 /* relative SE above this: about 10 photons or fewer, not Gaussian */

static const char *const k_name[LUCENT_MCO_SECTION_COUNT] = {"RAT", "A_l", "A_z", "Rd_r", "Rd_a", "Tt_r", "Tt_a"};
static const char *const k_unit[LUCENT_MCO_SECTION_COUNT] = {"-", "-", "1/cm", "1/cm2", "sr-1", "1/cm2", "sr-1"};
static const char *const k_axis[LUCENT_MCO_SECTION_COUNT] = {"",       "",           "z [cm]", "r [cm]", "angle [rad]",
                                                             "r [cm]", "angle [rad]"};
static const char *const k_state[] = {"compared", "empty", "sparse", "unresolved", "incomparable"};

const char *lucent_mco_section_name(lucent_mco_section_id id) { return k_name[id]; }
const char *lucent_mco_section_unit(lucent_mco_section_id id) { return k_unit[id]; }
const char *lucent_mco_section_axis(lucent_mco_section_id id) { return k_axis[id]; }
const char *lucent_mco_bin_state_name(lucent_mco_bin_state state) { return k_state[state]; }

const char *lucent_mco_rat_name(int bin)
{
    static const char *const names[] = {"Rd", "A", "Tt"};
    return bin >= 0 && bin < 3 ? names[bin] : "?";
}

/* ---- checking that a run is the .mco's simulation ---- */

/* Equal as the .mco prints them (%G: 6 significant digits). */
static bool same(double a, double b)
{
    if (isinf(a) || isinf(b)) return a == b;
    return fabs(a - b) <= 1e-5 * fmax(fabs(a), fabs(b));
}

static lucent_status differs(const char *what, double mine, double theirs)
{
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s is %g, the .mco's is %g", what, mine, theirs);
}

static lucent_status check_layer(int i, const lucent_mc_layer *a, const lucent_mc_layer *b)
{
    char what[64];
    const double cm = MCML_CM;
    struct {
        const char *name;
        double mine, theirs;
    } f[] = {
        {"n", a->n, b->n},
        {"mua [1/cm]", a->sigma_a * cm, b->sigma_a * cm},
        {"mus [1/cm]", a->sigma_s * cm, b->sigma_s * cm},
        {"g", a->g, b->g},
        {"d [cm]", a->thickness / cm, b->thickness / cm},
    };
    for (size_t k = 0; k < sizeof f / sizeof *f; k++) {
        if (same(f[k].mine, f[k].theirs)) continue;
        snprintf(what, sizeof what, "layer %d: %s", i + 1, f[k].name);
        return differs(what, f[k].mine, f[k].theirs);
    }
    return LUCENT_OK;
}

lucent_status lucent_mco_check_run(const lucent_mco *mco, const lucent_mc_desc *desc)
{
    const lucent_mc_desc *m = &mco->run.desc;
    const double cm = MCML_CM;
    if (desc->layer_count != m->layer_count) return differs("the number of layers", desc->layer_count, m->layer_count);
    if (!same(desc->n_above, m->n_above)) return differs("n above", desc->n_above, m->n_above);
    if (!same(desc->n_below, m->n_below)) return differs("n below", desc->n_below, m->n_below);
    for (int i = 0; i < m->layer_count; i++) {
        lucent_status s = check_layer(i, &desc->layers[i], &m->layers[i]);
        if (s != LUCENT_OK) return s;
    }
    const lucent_mc_grid *a = &desc->grid, *b = &m->grid;
    if (!same(a->dz, b->dz)) return differs("dz [cm]", a->dz / cm, b->dz / cm);
    if (!same(a->dr, b->dr)) return differs("dr [cm]", a->dr / cm, b->dr / cm);
    if (a->nz != b->nz) return differs("nz", a->nz, b->nz);
    if (a->nr != b->nr) return differs("nr", a->nr, b->nr);
    if (a->na != b->na) return differs("na", a->na, b->na);
    return LUCENT_OK;
}

/* ---- the comparison ---- */

/* MCML's A_l sums the depth bins by the layer of their centre (MCML's IzToLayer): exact when
 * every boundary between layers is a multiple of dz and lies inside the grid, before its last
 * bin (which collects everything deeper). */
static bool layers_on_grid(const lucent_mc_desc *d)
{
    double z = 0, dz = d->grid.dz;
    for (int i = 0; i + 1 < d->layer_count; i++) {
        z += d->layers[i].thickness;
        double k = z / dz;
        if (fabs(k - nearbyint(k)) > 1e-6 * fmax(1.0, k) || nearbyint(k) > d->grid.nz - 1) return false;
    }
    return true;
}

static void judge(lucent_mco_bin *b, double se_scale)
{
    b->mcml_se = b->lucent_se * se_scale;
    b->z = 0;
    double se = sqrt(b->lucent_se * b->lucent_se + b->mcml_se * b->mcml_se);
    if (b->lucent == 0 && b->mcml == 0)
        b->state = LUCENT_MCO_EMPTY;
    else if (se == 0)
        b->state = LUCENT_MCO_UNRESOLVED;
    else if (fmax(b->lucent_se, b->mcml_se) > SPARSE_REL_SE * b->lucent)
        b->state = LUCENT_MCO_SPARSE;
    else {
        b->state = LUCENT_MCO_COMPARED;
        b->z = (b->lucent - b->mcml) / se;
    }
}

static lucent_status fill(lucent_mco_section *sec, lucent_mco_section_id id, int count, const double *lv,
                          const double *lse, const double *mv, double se_scale)
{
    sec->id = id;
    sec->count = count;
    sec->worst = -1;
    sec->bins = calloc((size_t)(count ? count : 1), sizeof *sec->bins);
    if (!sec->bins) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < count; i++) {
        lucent_mco_bin *b = &sec->bins[i];
        *b = (lucent_mco_bin){.lucent = lv[i], .lucent_se = lse[i], .mcml = mv[i]};
        judge(b, se_scale);
    }
    return LUCENT_OK;
}

static void tally(lucent_mco_section *sec, lucent_mco_comparison *c)
{
    for (int i = 0; i < sec->count; i++) {
        const lucent_mco_bin *b = &sec->bins[i];
        switch (b->state) {
        case LUCENT_MCO_COMPARED:
            sec->compared++;
            sec->chi2 += b->z * b->z;
            if (fabs(b->z) > 3.0) sec->beyond3++;
            if (sec->worst < 0 || fabs(b->z) > fabs(sec->bins[sec->worst].z)) sec->worst = i;
            break;
        case LUCENT_MCO_SPARSE: sec->sparse++; break;
        case LUCENT_MCO_UNRESOLVED: sec->unresolved++; break;
        case LUCENT_MCO_INCOMPARABLE: sec->incomparable++; break;
        case LUCENT_MCO_EMPTY: break;
        }
    }
    c->compared += sec->compared;
    c->beyond3 += sec->beyond3;
    c->chi2 += sec->chi2;
}

static lucent_status check_shapes(const lucent_mco *mco, const lucent_mc_result *r)
{
    const lucent_mc_grid *a = &r->grid, *b = &mco->run.desc.grid;
    if (r->layer_count != mco->run.desc.layer_count || a->nr != b->nr || a->nz != b->nz || a->na != b->na)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "the result's layers and grid (%d layers, nz %d, nr %d, na %d) are not "
                            "the .mco's (%d, %d, %d, %d)",
                            r->layer_count, a->nz, a->nr, a->na, mco->run.desc.layer_count, b->nz, b->nr, b->na);
    if (r->photons == 0 || mco->run.desc.photons == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "no photons to compare");
    return LUCENT_OK;
}

static lucent_status fill_sections(const lucent_mco *m, const lucent_mc_result *r, lucent_mco_comparison *c)
{
    const lucent_mc_grid *g = &m->run.desc.grid;
    double k = c->se_scale, cm = MCML_CM;
    double rat_l[3] = {r->rd, r->a, r->tt}, rat_se[3] = {r->rd_se, r->a_se, r->tt_se};
    double rat_m[3] = {m->rd, m->a, m->tt};
    lucent_mco_section *s = c->sections;
    lucent_status st = fill(&s[LUCENT_MCO_RAT], LUCENT_MCO_RAT, 3, rat_l, rat_se, rat_m, k);
    if (!st) st = fill(&s[LUCENT_MCO_A_L], LUCENT_MCO_A_L, r->layer_count, r->a_layer, r->a_layer_se, m->a_l, k);
    if (!st) st = fill(&s[LUCENT_MCO_A_Z], LUCENT_MCO_A_Z, g->nz, r->a_z, r->a_z_se, m->a_z, k);
    if (!st) st = fill(&s[LUCENT_MCO_RD_R], LUCENT_MCO_RD_R, g->nr, r->rd_r, r->rd_r_se, m->rd_r, k);
    if (!st) st = fill(&s[LUCENT_MCO_RD_A], LUCENT_MCO_RD_A, g->na, r->rd_a, r->rd_a_se, m->rd_a, k);
    if (!st) st = fill(&s[LUCENT_MCO_TT_R], LUCENT_MCO_TT_R, g->nr, r->tt_r, r->tt_r_se, m->tt_r, k);
    if (!st) st = fill(&s[LUCENT_MCO_TT_A], LUCENT_MCO_TT_A, g->na, r->tt_a, r->tt_a_se, m->tt_a, k);
    if (st) return st;
    double da = 3.14159265358979323846 / (2.0 * g->na);
    s[LUCENT_MCO_A_Z].width = g->dz / cm;
    s[LUCENT_MCO_RD_R].width = s[LUCENT_MCO_TT_R].width = g->dr / cm;
    s[LUCENT_MCO_RD_A].width = s[LUCENT_MCO_TT_A].width = da;
    return LUCENT_OK;
}

lucent_status lucent_mco_compare(const lucent_mco *mco, const lucent_mc_result *result, lucent_mco_comparison *dest)
{
    memset(dest, 0, sizeof *dest);
    lucent_status s = check_shapes(mco, result);
    if (s != LUCENT_OK) return s;
    dest->lucent_photons = result->photons;
    dest->mcml_photons = mco->run.desc.photons;
    dest->se_scale = sqrt((double)result->photons / (double)mco->run.desc.photons);
    dest->rsp_lucent = result->rsp;
    dest->rsp_mcml = mco->rsp;
    /* the .mco prints Rsp with 6 significant digits (%-14.6G) */
    dest->rsp_equal = fabs(result->rsp - mco->rsp) <= 5e-6 * fmax(result->rsp, mco->rsp) + 1e-12;
    dest->a_l_on_grid = layers_on_grid(&mco->run.desc);
    if ((s = fill_sections(mco, result, dest)) != LUCENT_OK) {
        lucent_mco_comparison_free(dest);
        return s;
    }
    if (!dest->a_l_on_grid)
        for (int i = 0; i < dest->sections[LUCENT_MCO_A_L].count; i++) {
            dest->sections[LUCENT_MCO_A_L].bins[i].state = LUCENT_MCO_INCOMPARABLE;
            dest->sections[LUCENT_MCO_A_L].bins[i].z = 0;
        }
    for (int i = 0; i < LUCENT_MCO_SECTION_COUNT; i++) tally(&dest->sections[i], dest);
    return LUCENT_OK;
}

void lucent_mco_comparison_free(lucent_mco_comparison *c)
{
    for (int i = 0; i < LUCENT_MCO_SECTION_COUNT; i++) free(c->sections[i].bins);
    memset(c, 0, sizeof *c);
}
