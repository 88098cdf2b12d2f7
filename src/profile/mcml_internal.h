/* Internal to the MCML file readers (src/profile/mcml.c: .mci; src/profile/mco.c: .mco): the
 * line reader they share, and the run block (output name, photons, grid, layers) that an .mci
 * file holds once per run and an .mco file repeats as its InParm section. */
#ifndef LUCENT_SRC_PROFILE_MCML_INTERNAL_H
#define LUCENT_SRC_PROFILE_MCML_INTERNAL_H

#include <math.h>

#include "lucent/mc.h"

#define MCML_CM 10.0 /* mm per cm: MCML files speak cm, Lucent mm */

/* Data lines, with comments (# to the end of the line) and blank lines skipped. */
typedef struct mcml_reader {
    const char *name; /* the file, for messages */
    const char *p;    /* next unread character */
    int line;         /* lines consumed so far */
    int at;           /* line number of the current data line */
    char buf[1024];   /* the current data line, comment stripped */
} mcml_reader;

/* Sets "<name>: line <at>: <message>" and returns LUCENT_ERR_PARSE. */
lucent_status mcml_fail(const mcml_reader *r, const char *fmt, ...) LUCENT_PRINTF(2, 3);

/* Moves to the next data line; `what` names the expected content for the end-of-file message. */
lucent_status mcml_next_line(mcml_reader *r, const char *what);

/* Reads exactly `count` finite numbers from the current data line. */
lucent_status mcml_numbers(mcml_reader *r, int count, double *dest, const char *what);

/* Reads one run block from the next data line on (output file name and format, photons,
 * dz dr, nz nr na, layers with the indices above and below), converted to mm, and validates
 * it. MCML's conventions are set: A(r, z) scored, the last bins collecting beyond the grid. */
lucent_status mcml_read_run(mcml_reader *r, lucent_mcml_run *run);

/* The angular normalisations of MCML 1.2's .mco (its ScaleRdTt; checked on MCML 1.2.2's own
 * files, whose Rd_a and Rd_ra sum to its Rd only so) against Lucent's (lucent/mc.h: the exact
 * solid angle of each band, 4 pi sin(a) sin(da/2), a = (j + 1/2) da, da = pi / (2 na)):
 * Rd_a and Tt_a are per 2 pi sin(a) da; Rd_ra and Tt_ra per 4 pi sin(a) sin(da/2) cos(a).
 * Each factor turns a Lucent value into the file's. */
static inline double mcml_1d_per_lucent(int na)
{
    double da = 3.14159265358979323846 / (2.0 * na);
    return 2.0 * sin(da / 2.0) / da;
}

static inline double mcml_2d_per_lucent(int j, int na)
{
    return 1.0 / cos((j + 0.5) * 3.14159265358979323846 / (2.0 * na));
}

#endif
