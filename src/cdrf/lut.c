/* The CDRF look-up table (Kubo section V, Fig. 8): cos theta in [-1, 1] across, sigma in
 * [0, sigma_max] down, single-channel float; written as EXR, PFM or a C array. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/strbuf.h"
#include "lucent/cdrf.h"

enum { LUT_MAX_SIDE = 8192 };

lucent_cdrf_lut_desc lucent_cdrf_lut_defaults(void)
{
    return (lucent_cdrf_lut_desc){.variant = LUCENT_CDRF_KUBO, .width = 256, .height = 256, .sigma_max = 3.0};
}

typedef struct lut_job {
    lucent_cdrf_lut_desc d;
    lucent_image *img;
} lut_job;

static lucent_status lut_rows(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    lut_job *job = ctx;
    int w = job->d.width, h = job->d.height;
    for (uint64_t j = begin; j < end; j++) {
        double sigma = job->d.sigma_max * (double)j / (h - 1);
        for (int i = 0; i < w; i++) {
            double c = -1.0 + 2.0 * i / (w - 1);
            if (c > 1) c = 1;
            double v = sigma == 0 && job->d.variant == LUCENT_CDRF_KUBO
                           ? fmax(c, 0.0) /* Eq. 2 exactly */
                           : lucent_cdrf_eval(job->d.variant, acos(c), sigma);
            job->img->data[j * (uint64_t)w + (uint64_t)i] = (float)v;
        }
    }
    return LUCENT_OK;
}

lucent_status lucent_cdrf_lut_build(const lucent_cdrf_lut_desc *desc, lucent_image **dest)
{
    *dest = NULL;
    lucent_cdrf_lut_desc d = lucent_cdrf_lut_defaults();
    if (desc) {
        d.variant = desc->variant;
        d.pool = desc->pool;
        if (desc->width) d.width = desc->width;
        if (desc->height) d.height = desc->height;
        if (desc->sigma_max != 0) d.sigma_max = desc->sigma_max;
    }
    if (d.width < 2 || d.height < 2 || d.width > LUT_MAX_SIDE || d.height > LUT_MAX_SIDE)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF LUT: width and height must be in [2, %d] (got %d x %d)",
                            LUT_MAX_SIDE, d.width, d.height);
    if (!(d.sigma_max > 0) || !isfinite(d.sigma_max) || d.sigma_max > 100)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF LUT: sigma_max must be in (0, 100] radians");
    if (d.variant != LUCENT_CDRF_KUBO && d.variant != LUCENT_CDRF_COLLOMB)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "CDRF LUT: unknown variant %d", (int)d.variant);
    lut_job job = {.d = d};
    lucent_status s = lucent_image_create(d.width, d.height, 1, &job.img);
    if (s == LUCENT_OK) s = lucent_parallel_for(d.pool, (uint64_t)d.height, 8, lut_rows, &job);
    if (s != LUCENT_OK) {
        lucent_image_destroy(job.img);
        return s;
    }
    *dest = job.img;
    return LUCENT_OK;
}

static bool has_ext(const char *path, const char *ext)
{
    size_t n = strlen(path), e = strlen(ext);
    return n > e && strcasecmp(path + n - e, ext) == 0;
}

/* A C float literal that reads back exactly: "%.9g" plus ".0" when it lacks a point, then 'f'. */
static void float_literal(float v, char *dest, size_t size)
{
    if (!isfinite(v)) v = 0;
    int n = snprintf(dest, size, "%.9g", (double)v);
    if (n > 0 && (size_t)n + 3 < size && !strpbrk(dest, ".e")) strcat(dest, ".0");
    strcat(dest, "f");
}

static lucent_status write_c(const char *path, const lucent_image *lut, double sigma_max, const char *name)
{
    lucent_strbuf b = {0};
    char *text = NULL;
    const char *nm = name ? name : "lucent_cdrf_lut";
    lucent_strbuf_printf(&b,
                         "/* The curvature-dependent reflectance LUT (Kubo, Dobashi & Morishima), written by lucent.\n"
                         " * %s[j][i]: cos theta = -1 + 2 i / %d, sigma = %.9g j / %d (radians). */\n",
                         nm, lut->width - 1, sigma_max, lut->height - 1);
    lucent_strbuf_printf(&b, "#define %s_WIDTH %d\n#define %s_HEIGHT %d\n#define %s_SIGMA_MAX %.9g\n", nm, lut->width,
                         nm, lut->height, nm, sigma_max);
    lucent_strbuf_printf(&b, "static const float %s[%d][%d] = {\n", nm, lut->height, lut->width);
    for (int j = 0; j < lut->height; j++) {
        lucent_strbuf_printf(&b, "    {");
        for (int i = 0; i < lut->width; i++) {
            char num[48];
            float_literal(lut->data[(size_t)j * (size_t)lut->width + (size_t)i], num, sizeof num);
            lucent_strbuf_printf(&b, "%s%s", i ? (i % 8 ? ", " : ",\n     ") : "", num);
        }
        lucent_strbuf_printf(&b, "},\n");
    }
    lucent_strbuf_printf(&b, "};\n");
    lucent_status s = lucent_strbuf_finish(&b, &text);
    if (s == LUCENT_OK) s = lucent_write_file(path, text, strlen(text));
    free(text);
    return s;
}

lucent_status lucent_cdrf_lut_write(const char *path, const lucent_image *lut, double sigma_max, const char *name)
{
    if (!lut || lut->channels != 1)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: a CDRF LUT has one channel", path);
    if (has_ext(path, ".c") || has_ext(path, ".h")) return write_c(path, lut, sigma_max, name);
    if (has_ext(path, ".exr") || has_ext(path, ".pfm")) return lucent_image_write(path, lut, NULL);
    return lucent_error(LUCENT_ERR_UNSUPPORTED, "%s: unknown LUT format (use .exr, .pfm or .c)", path);
}
