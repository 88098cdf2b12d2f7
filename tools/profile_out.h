/* Writers for `lucent profile`: a profile (or several models of one material) as JSON, CSV
 * and an SVG chart, all written atomically. */
#ifndef LUCENT_TOOLS_PROFILE_OUT_H
#define LUCENT_TOOLS_PROFILE_OUT_H

#include "lucent/profile.h"

typedef struct profile_out_desc {
    const char *prefix;               /* PREFIX.json/.csv/.svg (compare: PREFIX-MODEL.json/.csv) */
    const lucent_material *material;
    lucent_profile *const *profiles;  /* count profiles of the same grid */
    int count;
    bool compare;                     /* one chart panel per channel, one curve per model */
    uint64_t photons, seed;           /* recorded for Monte Carlo profiles */
    int sog;                          /* > 0: fit this many Gaussians and record them */
} profile_out_desc;

/* Writes every output and prints "wrote FILE" for each (unless --quiet). */
lucent_status profile_out_write(const profile_out_desc *d);

#endif
