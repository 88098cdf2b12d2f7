/* MCML output files (.mco) read back, and a Lucent run compared with one, section by section,
 * in standard errors: what a user needs to check Lucent against results MCML 1.2 already made
 * (Wang, Jacques & Zheng 1995, the MCML manual's chapter on the output file). docs/mcml.md.
 *
 * Units: as everywhere in Lucent, mm inside (the reader converts MCML's cm). The comparison's
 * writers speak MCML's units (cm), as the .mco they compare with. */
#ifndef LUCENT_MCML_H
#define LUCENT_MCML_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"
#include "lucent/mc.h"

#ifdef __cplusplus
extern "C" {
#endif

/* An MCML output file, format A1, converted to mm. Densities keep MCML's normalisations (the
 * same as lucent_mc_result's): a_z per mm, rd_r and tt_r per mm^2, rd_a and tt_a per sr,
 * a_rz per mm^3 and rd_ra, tt_ra per mm^2 sr, 2-D arrays row-major by radius as in the file. */
typedef struct lucent_mco {
    lucent_mcml_run run;   /* InParm: output name, photons, grid, layers (run.desc.layers) */
    double rsp, rd, a, tt; /* RAT */
    double *a_l;           /* [layer_count] */
    double *a_z;           /* [nz] */
    double *rd_r, *tt_r;   /* [nr] */
    double *rd_a, *tt_a;   /* [na] */
    double *a_rz;          /* [nr * nz]; NULL when the file has no A_rz section */
    double *rd_ra, *tt_ra; /* [nr * na]; NULL when absent */
} lucent_mco;

/* Parses .mco text; name is used in messages ("name: line 7: Rd_r: ..."). Every 1-D section
 * and RAT must be present once with exactly the count InParm implies; values must be finite
 * and >= 0. The 2-D sections (A_rz, Rd_ra, Tt_ra) are read when present. */
lucent_status lucent_mco_parse(const char *text, const char *name, lucent_mco *dest);

/* Reads and parses an .mco file. */
lucent_status lucent_mco_load(const char *path, lucent_mco *dest);

/* Frees what lucent_mco_parse allocated and zeroes m. */
void lucent_mco_free(lucent_mco *m);

/* ---- comparing a Lucent run with an .mco ---- */

/* The sections compared: the totals, absorption per layer, and the 1-D profiles. */
typedef enum lucent_mco_section_id {
    LUCENT_MCO_RAT, /* Rd, A, Tt */
    LUCENT_MCO_A_L,
    LUCENT_MCO_A_Z,
    LUCENT_MCO_RD_R,
    LUCENT_MCO_RD_A,
    LUCENT_MCO_TT_R,
    LUCENT_MCO_TT_A,
    LUCENT_MCO_SECTION_COUNT
} lucent_mco_section_id;

/* What became of one bin. */
typedef enum lucent_mco_bin_state {
    LUCENT_MCO_COMPARED,    /* counted: z is the difference in standard errors */
    LUCENT_MCO_EMPTY,       /* no weight on either side: nothing to compare */
    LUCENT_MCO_SPARSE,      /* too few photons for a Gaussian error (relative SE > 0.3) */
    LUCENT_MCO_UNRESOLVED,  /* weight on one side only, no error estimate: not counted */
    LUCENT_MCO_INCOMPARABLE /* the two sides measure different things (A_l off the dz grid) */
} lucent_mco_bin_state;

typedef struct lucent_mco_bin {
    double lucent, lucent_se; /* Lucent's value and standard error (mm units) */
    double mcml, mcml_se;     /* MCML's value, and its standard error as estimated */
    double z;                 /* (lucent - mcml) / sqrt(lucent_se^2 + mcml_se^2), 0 unless COMPARED */
    lucent_mco_bin_state state;
} lucent_mco_bin;

typedef struct lucent_mco_section {
    lucent_mco_section_id id;
    int count; /* bins */
    lucent_mco_bin *bins;
    double width; /* bin width in MCML's units: cm (A_z, Rd_r, Tt_r), rad (Rd_a, Tt_a),
                                0 for RAT and A_l; bin i sits at (i + 1/2) width */
    int compared, beyond3, sparse, unresolved, incomparable;
    double chi2; /* sum of z^2 over the compared bins */
    int worst;   /* compared bin of the largest |z| (-1: none) */
} lucent_mco_section;

typedef struct lucent_mco_comparison {
    uint64_t lucent_photons, mcml_photons;
    double se_scale;             /* mcml_se = lucent_se * se_scale = sqrt(lucent_photons / mcml_photons) */
    double rsp_lucent, rsp_mcml; /* exact on both sides */
    bool rsp_equal;              /* equal within the file's 6 significant digits */
    bool a_l_on_grid;            /* every layer boundary lies on the dz grid, inside it: MCML's A_l
                                (depth bins summed by the layer of their centre) is then exact */
    lucent_mco_section sections[LUCENT_MCO_SECTION_COUNT];
    int compared, beyond3; /* over all sections */
    double chi2;
} lucent_mco_comparison;

/* Compares a Lucent result with an .mco. The result must come from the .mco's geometry and
 * grid with MCML's conventions (lucent_mco_check_run says whether a run does). MCML writes no
 * standard errors: MCML's are estimated from Lucent's, scaled by sqrt(N_lucent / N_mcml), as both
 * score the same estimator (weighted packets, the same roulette) and so have the same variance
 * per photon. On success dest owns arrays freed by lucent_mco_comparison_free. */
lucent_status lucent_mco_compare(const lucent_mco *mco, const lucent_mc_result *result, lucent_mco_comparison *dest);

/* Checks that a run (from an .mci, say) describes the .mco's simulation: the same layers,
 * indices and grid (photons and seed may differ). The message names the first difference. */
lucent_status lucent_mco_check_run(const lucent_mco *mco, const lucent_mc_desc *desc);

/* The section's name as in the .mco ("RAT", "A_l", "Rd_r", ...) and its unit there ("1/cm2"). */
const char *lucent_mco_section_name(lucent_mco_section_id id);
const char *lucent_mco_section_unit(lucent_mco_section_id id);

/* What a section's bins run over ("z [cm]", "r [cm]", "angle [rad]"; "" for RAT, A_l), and the
 * name of bin i of RAT ("Rd", "A", "Tt"). */
const char *lucent_mco_section_axis(lucent_mco_section_id id);
const char *lucent_mco_rat_name(int bin);

/* The name of a bin's state ("compared", "empty", "sparse", "unresolved", "incomparable"). */
const char *lucent_mco_bin_state_name(lucent_mco_bin_state state);

/* Writes the comparison atomically: CSV (one row per bin) or JSON (the summary and every bin),
 * values in MCML's units (cm). */
lucent_status lucent_mco_comparison_write_csv(const char *path, const lucent_mco_comparison *c);
lucent_status lucent_mco_comparison_write_json(const char *path, const lucent_mco_comparison *c);

/* Frees what lucent_mco_compare allocated and zeroes c. */
void lucent_mco_comparison_free(lucent_mco_comparison *c);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_MCML_H */
