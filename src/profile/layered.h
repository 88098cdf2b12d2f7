/* Internal to src/profile: the layered multipole's transforms and spectral mixtures of stacks, for the
 * spectral skin (skin.c). The composition itself is multipole.c's (Donner & Jensen 2005). */
#ifndef LUCENT_PROFILE_LAYERED_H
#define LUCENT_PROFILE_LAYERED_H

#include "lucent/profile.h"

/* The stack's Hankel transforms at frequency k (mm^-1) per channel: rt of the reflectance seen from the
 * top, td of the transmittance downwards. At k = 0 they are the plane integrals (total R and T). The
 * layers must be valid (layered_mix_check). */
void layered_hat(const lucent_layer *layers, int count, double k, double rt[3], double td[3]);

/* Checks count layers as lucent_profile_layered does. */
lucent_status layered_mix_check(const lucent_layer *layers, int count);

/* The profile of a spectral mixture: set_count stacks of count layers each (sets[i count .. i count +
 * count - 1]), whose three channels are three bands; channel c of dest is sum_t weight[c (3 set_count) + t]
 * times stack t (t = 3 i + channel), inverted once. grid must be complete (dr, count). dest[0] is R,
 * dest[1] is T. */
lucent_status layered_profile_mix(const lucent_layer *sets, int set_count, int count, const double *weight,
                                  const lucent_profile_grid *grid, lucent_profile *dest[2]);

#endif
