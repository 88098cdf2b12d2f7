/* The CPU reference of the screen-space separable blur (lucent_ssss_blur_cpu): the same sums as
 * blur.frag.glsl, written independently in double precision, used by the tests to check the GPU
 * pass. See lucent/render.h and docs/render.md for the definition. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/reference/reference.h"

enum { MAX_MATERIALS = 8 };

typedef struct cpu_blur {
    const lucent_ssss_blur_desc *d;
    const float *depth;
    const uint8_t *material;
    int w, h;
    double scale;
    double radius[MAX_MATERIALS];
    bool positive[MAX_MATERIALS][LUCENT_KERNEL_MAX_RANK];
    /* one pass */
    const double *src; /* 3 per pixel */
    double *dest;      /* 3 per pixel */
    int pass;
    bool vertical;
} cpu_blur;

/* The fraction of a sample's weight kept by the depth filter. */
static double keep_fraction(lucent_depth_filter f, double zs, double z, double r)
{
    if (zs <= 0) return 0;
    if (f == LUCENT_DEPTH_NONE) return 1;
    double dz = zs - z;
    if (f == LUCENT_DEPTH_GAUSSIAN) return exp(-dz * dz / (2 * (r / 2) * (r / 2)));
    return 1 - fmin(fabs(dz) / r, 1);
}

static void pass_pixel(const cpu_blur *b, int x, int y, double *out)
{
    size_t i = (size_t)y * (size_t)b->w + (size_t)x;
    double z = b->depth[i];
    const double *centre = b->src + 3 * i;
    if (!(z > 0)) {
        for (int c = 0; c < 3; c++) out[c] = b->pass == 0 || !b->vertical ? centre[c] : 0;
        return;
    }
    int m = b->material ? b->material[i] : 0, n = b->vertical ? b->h : b->w, at = b->vertical ? y : x;
    const lucent_taps *t = b->d->taps[m];
    double sum[3] = {0}, lost[3] = {0}, total[3] = {0}, step = b->scale / z;
    for (int k = 0; k < t->count; k++) {
        double o = t->offset[k] * step, f = floor(o), frac = o - f;
        for (int j = 0; j < 2; j++) {
            int q = (int)fmin(fmax(at + f + j, 0), n - 1);
            size_t qi = b->vertical ? (size_t)q * (size_t)b->w + (size_t)x : (size_t)y * (size_t)b->w + (size_t)q;
            double a = keep_fraction(b->d->filter, b->depth[qi], z, b->radius[m]), wt = j ? frac : 1 - frac;
            for (int c = 0; c < 3; c++) {
                double w = t->weight[c][b->pass * t->count + k];
                sum[c] += w * wt * a * b->src[3 * qi + c];
                lost[c] += w * wt * (1 - a);
            }
        }
        for (int c = 0; c < 3; c++) total[c] += t->weight[c][b->pass * t->count + k];
    }
    bool normalise = b->d->filter == LUCENT_DEPTH_GAUSSIAN && b->positive[m][b->pass];
    for (int c = 0; c < 3; c++) {
        double keep = total[c] - lost[c];
        if (normalise)
            out[c] = keep > 1e-6 * total[c] ? sum[c] * total[c] / keep : total[c] * centre[c];
        else
            out[c] = sum[c] + lost[c] * centre[c];
        if (b->vertical) out[c] *= t->sign[c][b->pass];
    }
}

static lucent_status rows(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    const cpu_blur *b = ctx;
    for (uint64_t y = begin; y < end; y++)
        for (int x = 0; x < b->w; x++) pass_pixel(b, x, (int)y, b->dest + 3 * ((size_t)y * (size_t)b->w + (size_t)x));
    return LUCENT_OK;
}

lucent_status gl_blur_check_args(const lucent_image *irr, const lucent_image *depth, const uint8_t *material,
                                 const lucent_ssss_blur_desc *d, const lucent_image *dest)
{
    if (!d || !d->taps || d->material_count < 1 || d->material_count > MAX_MATERIALS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "ssss blur: 1 to %d tap sets expected", MAX_MATERIALS);
    for (int m = 0; m < d->material_count; m++)
        if (!d->taps[m] || d->taps[m]->count != d->taps[0]->count || d->taps[m]->rank != d->taps[0]->rank)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "ssss blur: tap set %d differs in count or rank", m);
    if (!(d->pixel_scale > 0) || !isfinite(d->pixel_scale) || d->width_scale < 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "ssss blur: pixel_scale must be > 0, width_scale >= 0");
    if (irr->channels < 3 || depth->channels != 1 || dest->channels < 3 || depth->width != irr->width ||
        depth->height != irr->height || dest->width != irr->width || dest->height != irr->height)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "ssss blur: irradiance (RGB), depth (1 channel) and dest "
                                                         "(RGB) must have one size");
    size_t n = (size_t)irr->width * (size_t)irr->height;
    for (size_t i = 0; material && i < n; i++)
        if (material[i] >= d->material_count)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "ssss blur: pixel %zu has material %d of %d", i,
                                material[i], d->material_count);
    return LUCENT_OK;
}

static void setup(cpu_blur *b, const lucent_ssss_blur_desc *d)
{
    double ws = d->width_scale > 0 ? d->width_scale : 1;
    b->scale = d->pixel_scale * ws;
    for (int m = 0; m < d->material_count; m++) {
        const lucent_taps *t = d->taps[m];
        double r = 0;
        for (int k = 0; k < t->count; k++) r = fmax(r, fabs(t->offset[k]));
        b->radius[m] = ws * fmax(r, 1e-6);
        for (int p = 0; p < t->rank; p++) {
            b->positive[m][p] = true;
            for (int k = 0; k < t->count; k++)
                for (int c = 0; c < 3; c++) b->positive[m][p] &= t->weight[c][p * t->count + k] >= 0;
        }
    }
}

lucent_status lucent_ssss_blur_cpu(const lucent_image *irradiance, const lucent_image *depth, const uint8_t *material,
                                   const lucent_ssss_blur_desc *desc, lucent_pool *pool, lucent_image *dest)
{
    lucent_status s = gl_blur_check_args(irradiance, depth, material, desc, dest);
    if (s != LUCENT_OK) return s;
    cpu_blur b = {
        .d = desc, .depth = depth->data, .material = material, .w = irradiance->width, .h = irradiance->height};
    setup(&b, desc);
    size_t n = (size_t)b.w * (size_t)b.h;
    double *in = malloc(3 * n * sizeof *in), *tmp = malloc(3 * n * sizeof *tmp), *out = malloc(3 * n * sizeof *out);
    double *sum = calloc(3 * n, sizeof *sum);
    if (!in || !tmp || !out || !sum) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; s == LUCENT_OK && i < n; i++)
        for (int c = 0; c < 3; c++) in[3 * i + c] = irradiance->data[i * (size_t)irradiance->channels + (size_t)c];
    for (int p = 0; s == LUCENT_OK && p < desc->taps[0]->rank; p++) {
        b.pass = p, b.src = in, b.dest = tmp, b.vertical = false;
        s = lucent_parallel_for(pool, (uint64_t)b.h, 8, rows, &b);
        b.src = tmp, b.dest = out, b.vertical = true;
        if (s == LUCENT_OK) s = lucent_parallel_for(pool, (uint64_t)b.h, 8, rows, &b);
        for (size_t i = 0; s == LUCENT_OK && i < 3 * n; i++) sum[i] += out[i];
    }
    for (size_t i = 0; s == LUCENT_OK && i < n; i++)
        for (int c = 0; c < 3; c++) dest->data[i * (size_t)dest->channels + (size_t)c] = (float)sum[3 * i + c];
    free(in), free(tmp), free(out), free(sum);
    return s;
}
