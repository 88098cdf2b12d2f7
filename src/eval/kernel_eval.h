/* kernel-eval's state during a run, shared by kernel_eval.c (the models and files) and
 * kernel_eval_convolve.c (millimetres to pixels, the three convolutions). */
#ifndef LUCENT_SRC_EVAL_KERNEL_EVAL_H
#define LUCENT_SRC_EVAL_KERNEL_EVAL_H

#include "lucent/eval.h"

typedef struct ke_run {
    lucent_kernel_eval_desc d;      /* defaults resolved */
    lucent_kernel_eval_result *res; /* filled as the run goes */
    lucent_profile *profile;
    lucent_image *signal, *exact;
    int hp;         /* pixel kernel half-width */
    double *w;      /* resampling matrix, (2 hp + 1) x (2 gt->half + 1) */
    int *wlo, *whi; /* non-zero column range per row */
} ke_run;

/* The resampling of the ground truth's cells onto pixels (sets hp, w, wlo, whi and
 * res->kernel_pixels). */
lucent_status ke_make_resampler(ke_run *ev);

/* ev->exact: the signal convolved with the resampled ground truth (2-D FFT). */
lucent_status ke_convolve_exact(ke_run *ev);

/* The signal convolved with k's resampled passes (separable, rank N), into dest. */
lucent_status ke_convolve_separable(const ke_run *ev, const lucent_kernel *k, lucent_image *dest);

/* The signal convolved with k's taps (ev->res->taps per pass), into dest. */
lucent_status ke_convolve_taps(const ke_run *ev, const lucent_kernel *k, lucent_image *dest);

#endif
