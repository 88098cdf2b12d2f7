/* Shared by `lucent kernel` and `lucent kernel-eval`: the radial profile a kernel is built from. */
#ifndef LUCENT_TOOLS_KERNEL_COMMON_H
#define LUCENT_TOOLS_KERNEL_COMMON_H

#include "lucent/lucent.h"

/* True when name is a profile kind the kernel commands accept. */
bool kernel_profile_known(const char *name);

/* R_d(r) of m by profile kind: "dipole", "better-dipole", "burley" or "mc" (Monte Carlo of a
 * half-space on the default grid, photons per channel, seed; Freude Table 6.1). */
lucent_status kernel_make_profile(const char *profile, int photons, int seed, const lucent_material *m,
                                  lucent_profile **dest);

#endif
