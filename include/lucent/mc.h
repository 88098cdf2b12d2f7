/* Lucent Monte Carlo: photon transport in multi-layered slabs, with the physics of MCML
 * (Wang, Jacques & Zheng 1995, "MCML - Monte Carlo modeling of light transport in
 * multi-layered tissues"): weighted photon packets, Russian roulette, Henyey-Greenstein
 * scattering, Fresnel reflection and refraction at every boundary (total internal reflection
 * included), specular reflection at entry. Scores the radial and angular profiles of diffuse
 * reflectance and transmittance, the absorption by depth (and optionally by radius and depth),
 * and the totals, each with a standard error from independent batches.
 *
 * Also reads MCML input files (.mci) and writes MCML output files (.mco): see docs/mcml.md.
 *
 * Units: lengths in mm, coefficients in mm^-1 (MCML files speak cm; they are converted when
 * read and written). Results are identical for a given seed whatever the thread count; the kernel
 * runs on the SIMD path lucent_isa_active() names (lucent/base.h), whose results agree with the
 * scalar path's statistically, not bit for bit. */
#ifndef LUCENT_MC_H
#define LUCENT_MC_H

#include <stdbool.h>
#include <stdint.h>

#include "lucent/base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Limits checked by lucent_mc_run (and by the .mci reader). */
#define LUCENT_MC_MAX_LAYERS 100
#define LUCENT_MC_MAX_PHOTONS 1000000000000.0 /* 1e12 */
#define LUCENT_MC_MAX_RADIAL_BINS 100000      /* nr, nz */
#define LUCENT_MC_MAX_ANGLE_BINS 10000        /* na */
#define LUCENT_MC_MAX_GRID_CELLS 20000000     /* nr * nz and nr * na */
#define LUCENT_MC_MAX_BATCHES 1024
/* sigma_t = sigma_a + sigma_s of a scattering layer, mm^-1: float steps of 1/sigma_t mm (and positions
 * in float) cannot be taken outside this range. */
#define LUCENT_MC_MIN_SIGMA_T 1e-12
#define LUCENT_MC_MAX_SIGMA_T 1e12
#define LUCENT_MC_MAX_THICKNESS 1e9 /* mm, a finite layer */
#define LUCENT_MC_MIN_BIN 1e-15     /* mm: dr and dz */
#define LUCENT_MC_MAX_EXTENT 1e12   /* mm: nr dr and nz dz */
/* Interactions (and boundary crossings) one photon packet may take; a packet that reaches it is
 * dropped unscored and counted (lucent_mc_result.capped): with sigma_a / sigma_t above 1e-5 the weight
 * meets Russian roulette well before this many steps, so only a medium that barely absorbs gets here. */
#define LUCENT_MC_MAX_STEPS (1 << 20)
/* The per-thread score arrays of one run, all threads together: above this the run is refused (fewer
 * threads or a smaller grid). */
#define LUCENT_MC_MAX_TALLY_BYTES ((size_t)2 << 30)

/* One layer of the slab, top to bottom. */
typedef struct lucent_mc_layer {
    double n;         /* index of refraction, >= 1 (0: 1) */
    double sigma_a;   /* absorption coefficient, mm^-1, >= 0 */
    double sigma_s;   /* scattering coefficient, mm^-1, >= 0 (both 0: a clear "glass" layer) */
    double g;         /* Henyey-Greenstein anisotropy, in [-1, 1] */
    double thickness; /* mm; <= 0 or INFINITY: semi-infinite (the last layer only) */
} lucent_mc_layer;

/* The scoring grid. Radial bins have width dr (bin i covers [i dr, (i+1) dr)), depth bins dz,
 * exit-angle bins da = pi / (2 na). Zero fields take the defaults of lucent_mc_defaults. */
typedef struct lucent_mc_grid {
    double dr; /* mm (0: one twentieth of the first layer's transport mean free path) */
    double dz; /* mm (0: dr) */
    int nr;    /* radial bins (0: 640) */
    int nz;    /* depth bins (0: 200) */
    int na;    /* exit-angle bins over [0, pi/2] (0: 30) */
} lucent_mc_grid;

/* One simulation. Zero fields mean the default (lucent_mc_defaults). */
typedef struct lucent_mc_desc {
    const lucent_mc_layer *layers; /* layer_count layers, top first */
    int layer_count;
    double n_above;   /* index of refraction above the slab (0: 1) */
    double n_below;   /* index below the slab (0: 1); unused when the last layer is semi-infinite */
    uint64_t photons; /* photon packets launched (0: 100000) */
    uint64_t seed;    /* the result is a function of the seed, not of the thread count */
    lucent_mc_grid grid;
    bool score_a_rz;        /* also score A(r, z) (the slow part; MCML always does) */
    bool last_bin_collects; /* MCML's convention: weight beyond the grid is scored in the last
                               radial / depth bin; otherwise it is counted only in *_beyond */
    int batches;            /* independent batches for the standard errors (0: 32) */
    lucent_pool *pool;      /* NULL: run on the calling thread */
    const char *label;      /* progress bar label (NULL: "Monte Carlo") */
} lucent_mc_desc;

/* What a run measured. Fractions are of the launched photon weight (1 per photon).
 * Densities follow MCML's normalisations (Wang, Jacques & Zheng 1995, section 4.2), in mm:
 *   rd_r[i]   = Rd in radial bin i / (N 2 pi (i + 1/2) dr^2)            mm^-2
 *   rd_a[j]   = Rd in angle bin j / (N 4 pi sin((j + 1/2) da) sin(da/2)) sr^-1
 *   rd_ra     = the same per mm^2 sr, row-major [i * na + j]            mm^-2 sr^-1
 *   a_z[k]    = absorbed in depth bin k / (N dz)                        mm^-1
 *   a_rz      = absorbed in bin (i, k) / (N 2 pi (i + 1/2) dr^2 dz), row-major [i * nz + k], mm^-3
 * The *_se fields are standard errors estimated from the spread of the batch means. */
typedef struct lucent_mc_result {
    uint64_t photons;
    int batches;
    int layer_count;
    lucent_mc_grid grid;                     /* resolved (no zeros) */
    double rsp;                              /* specular reflectance at entry (exact, no error) */
    double rd, rd_se;                        /* total diffuse reflectance */
    double a, a_se;                          /* total absorption */
    double tt, tt_se;                        /* total transmittance (unscattered included) */
    double balance, balance_se;              /* rsp + rd + a + tt: 1 up to roulette noise */
    double rd_beyond, tt_beyond, a_z_beyond; /* fractions scored beyond the grid (0 when
                                                last_bin_collects) */
    double *a_layer, *a_layer_se;            /* [layer_count] fractions */
    double *rd_r, *rd_r_se, *tt_r, *tt_r_se; /* [nr] */
    double *rd_a, *rd_a_se, *tt_a, *tt_a_se; /* [na] */
    double *a_z, *a_z_se;                    /* [nz] */
    double *rd_ra, *tt_ra;                   /* [nr * na] */
    double *a_rz;                            /* [nr * nz]; NULL unless score_a_rz */
    uint64_t capped; /* packets stopped at LUCENT_MC_MAX_STEPS: their weight is missing from every
                        score, which are then lower bounds (a warning is logged) */
} lucent_mc_result;

/* Fills dest with the defaults that zero fields of desc take (layers left as given). */
void lucent_mc_defaults(const lucent_mc_desc *desc, lucent_mc_desc *dest);

/* Checks a desc (ranges, the semi-infinite layer last, grid limits); the message names the
 * field ("layers[1].g: must be in [-1, 1], got 1.5"). */
lucent_status lucent_mc_validate(const lucent_mc_desc *desc);

/* Runs the simulation. On success dest owns arrays freed by lucent_mc_result_free. */
lucent_status lucent_mc_run(const lucent_mc_desc *desc, lucent_mc_result *dest);

/* Frees the arrays of r and zeroes it (r may be zeroed already). */
void lucent_mc_result_free(lucent_mc_result *r);

/* Returns the specular reflectance at entry for these layers (MCML: the Fresnel reflectance
 * at normal incidence, with multiple reflections inside a clear first layer). */
double lucent_mc_specular(const lucent_mc_desc *desc);

/* ---- MCML files (.mci in, .mco out) ---- */

/* One run of an .mci file, converted to mm. */
typedef struct lucent_mcml_run {
    char *output; /* output file name as written in the .mci */
    int line;     /* line of the output file name (for messages) */
    lucent_mc_layer *layers;
    lucent_mc_desc desc; /* photons, grid, layers, n_above/below; desc.layers == layers */
} lucent_mcml_run;

typedef struct lucent_mcml_file {
    double version; /* the file version (1.0) */
    int run_count;
    lucent_mcml_run *runs;
} lucent_mcml_file;

/* Parses .mci text; name is used in messages ("name: line 7: ..."). */
lucent_status lucent_mcml_parse(const char *text, const char *name, lucent_mcml_file *dest);

/* Reads and parses an .mci file. */
lucent_status lucent_mcml_load(const char *path, lucent_mcml_file *dest);

/* Frees what lucent_mcml_parse allocated and zeroes f. */
void lucent_mcml_file_free(lucent_mcml_file *f);

/* Writes an MCML .mco file (format A1, cm units, MCML's sections and normalisations; the last
 * radial and depth bins collect everything beyond the grid when the run did so) atomically. Its
 * header names the SIMD path in use (lucent_isa_active(): the one the run took unless it changed).
 * The run's result must come from run->desc (A_rz is written as zeros when not scored). */
lucent_status lucent_mcml_write(const char *path, const lucent_mcml_run *run, const lucent_mc_result *result);

#ifdef __cplusplus
}
#endif

#endif /* LUCENT_MC_H */
