/* `lucent kernel-eval`: every separable kernel model of a material against the ground truth,
 * in kernel space (Freude 2014, Table 6.3, Figure 6.2) and in image space on a test signal
 * (Tables 6.4-6.5, Figures 6.6-6.10). See docs/kernel-eval.md. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "base/json.h"
#include "base/strbuf.h"
#include "cli.h"
#include "lucent/lucent.h"

static const char k_usage[] =
    "usage: lucent kernel-eval MATERIAL [--models all|M1,M2,...] [--signal edge|shapes|IMAGE]\n"
    "                          [--out DIR] [options]\n"
    "\n"
    "Builds the ground-truth 2-D kernel of MATERIAL's profile and every kernel model of it,\n"
    "then compares them in kernel space (RMS over the grid, Freude Table 6.3; axis and diagonal\n"
    "slices, Figure 6.2) and in image space: the signal convolved exactly with the ground truth\n"
    "(2-D FFT) against each model's separable rank-N convolution and its taps (Tables 6.4-6.5).\n"
    "Writes into DIR (default NAME-eval, created if absent; its parent must exist):\n"
    "  kernel-axis.svg, kernel-diagonal.svg   slices y = 0 and x = y, one panel per channel\n"
    "  signal.png, exact.png/.exr             the signal and its exact convolution\n"
    "  MODEL.png/.exr, MODEL-taps.png/.exr    each model's convolution (separable; taps)\n"
    "  MODEL-diff.png, MODEL-taps-diff.png    heat maps of |model - exact| (mean over RGB)\n"
    "  tables.md, results.json                kernel- and image-space RMS per model and channel\n"
    "\n"
    "models (--models, default all): svd (rank 1), svd-norm (normalised, (5.12)), preint,\n"
    "  guided (k = 1), manual (Table A.1 presets only; skipped otherwise), sog (1 Gaussian),\n"
    "  jimenez. svd-rN and sog-rN (N = 1..16) pick a rank.\n"
    "\n"
    "options:\n"
    "  --signal S         edge (default), shapes, or a PNG/EXR/PFM image\n"
    "  --size N           signal side in pixels for edge and shapes (default 256)\n"
    "  --mm-per-pixel P   the signal's scale (default 0.1)\n"
    "  --taps N           taps per pass for the tap convolutions (odd, default 17; 0: none)\n"
    "  --table65          also svd rank N against sog with N Gaussians, N = 1..6 (Table 6.5;\n"
    "                     always on for Skin1)\n"
    "  --heat-scale E     the error mapped to white in the heat maps (default 0.1)\n"
    "  --profile P        dipole (default), better-dipole, burley or mc\n"
    "  --photons N        mc: photons per channel (default 1000000)\n"
    "  --seed S           mc: seed (default 1)\n"
    "  -q, --quiet        no informational lines\n";

enum { MAX_ENTRIES = 40, T65_MAX = 6 };

typedef struct entry {
    char name[32];
    lucent_kernel_desc desc;
    bool plot;       /* in the default set: drawn in the slices */
    lucent_kernel *k;
    char note[200];  /* why it was skipped ("" if built) */
    double krms[3];
    lucent_image_error_stats sep, taps;
    bool have_taps;
} entry;

typedef struct options {
    const char *spec, *out, *profile, *signal, *models;
    int size, taps, photons, seed;
    double mm_per_pixel, heat_scale;
    bool table65;
} options;

typedef struct eval {
    const options *o;
    lucent_material m;
    lucent_profile *p;
    lucent_kernel2d *gt;
    lucent_image *signal, *exact;
    int hp;         /* pixel kernel half-width */
    double *w;      /* resampling matrix, (2 hp + 1) x (2 gt->half + 1) */
    int *wlo, *whi; /* non-zero column range per row */
    entry e[MAX_ENTRIES];
    int count;
    int t65[T65_MAX][2]; /* entry indices of svd-rN, sog-rN */
    int t65_count;
    char dir[512];
} eval;


/* ---- Arguments ---- */

static int usage(const char *message, const char *arg)
{
    return cli_usage_error("kernel-eval", message, arg);
}

static int parse_args(int argc, char **argv, options *o)
{
    static const char *const valued[] = {"--models", "--signal", "--out",  "--size",    "--mm-per-pixel",
                                         "--taps",   "--profile", "--photons", "--seed", "--heat-scale"};
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int n = -1;
        for (int j = 0; j < (int)(sizeof valued / sizeof valued[0]) && n < 0; j++)
            if (cli_option(argc, argv, &i, valued[j], &v)) n = j;
        if (n >= 0 && !v) return usage("%s needs a value", valued[n]);
        bool ok = true;
        switch (n) {
        case 0: o->models = v; break;
        case 1: o->signal = v; break;
        case 2: o->out = v; break;
        case 3: ok = cli_parse_int(v, &o->size) && o->size >= 8 && o->size <= 16384; break;
        case 4: ok = cli_parse_double(v, &o->mm_per_pixel) && o->mm_per_pixel > 0; break;
        case 5:
            ok = cli_parse_int(v, &o->taps) && (o->taps == 0 || (o->taps % 2 == 1 && o->taps >= 3 && o->taps <= 255));
            break;
        case 6: ok = lucent_profile_source_known(o->profile = v); break;
        case 7: ok = cli_parse_int(v, &o->photons) && o->photons > 0; break;
        case 8: ok = cli_parse_int(v, &o->seed); break;
        case 9: ok = cli_parse_double(v, &o->heat_scale) && o->heat_scale > 0; break;
        default:
            if (!strcmp(argv[i], "--table65"))
                o->table65 = true;
            else if (argv[i][0] == '-')
                return usage("unknown option '%s'", argv[i]);
            else if (o->spec)
                return usage("expected one material, got '%s' too", argv[i]);
            else
                o->spec = argv[i];
        }
        if (!ok) {
            static const char *const what[] = {
                "", "", "", "a whole number in 8..16384", "a number > 0 (mm)", "0 or an odd number in 3..255",
                "dipole, better-dipole, burley or mc", "a whole number > 0", "a whole number", "a number > 0"};
            return cli_usage_error("kernel-eval", "%s needs %s", valued[n], what[n]);
        }
    }
    if (!o->spec) return usage("expected a material%s", "");
    return CLI_OK;
}

/* ---- Models ---- */

static entry *add(eval *ev, const char *name, lucent_kernel_model model, int rank, bool plot)
{
    entry *e = &ev->e[ev->count++];
    memset(e, 0, sizeof *e);
    snprintf(e->name, sizeof e->name, "%s", name);
    e->desc = lucent_kernel_defaults(model);
    e->desc.rank = rank;
    e->desc.k = 1;
    e->plot = plot;
    return e;
}

/* Adds the model NAME (svd, svd-norm, preint, ..., svd-rN, sog-rN). False if unknown. */
static bool add_named(eval *ev, const char *name, bool plot)
{
    if (ev->count >= MAX_ENTRIES) return false;
    lucent_kernel_model model;
    int rank = 1;
    char base[32];
    snprintf(base, sizeof base, "%s", name);
    char *r = strstr(base, "-r");
    if (r && (!strncmp(base, "svd-r", 5) || !strncmp(base, "sog-r", 5))) {
        if (!cli_parse_int(r + 2, &rank) || rank < 1 || rank > LUCENT_KERNEL_MAX_RANK) return false;
        *r = '\0';
    }
    if (!strcmp(base, "svd-norm")) {
        add(ev, name, LUCENT_KERNEL_SVD, 1, plot)->desc.normalize = true;
        return true;
    }
    if (lucent_kernel_model_find(base, &model) != LUCENT_OK) return lucent_clear_error(), false;
    add(ev, name, model, rank, plot);
    return true;
}

static int choose_models(eval *ev)
{
    const char *list = ev->o->models;
    if (!list || !strcmp(list, "all")) list = "svd,svd-norm,preint,guided,manual,sog,jimenez";
    char buf[512];
    if (strlen(list) >= sizeof buf) return usage("--models: list too long%s", "");
    strcpy(buf, list);
    char *save = NULL;
    for (char *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save))
        if (!add_named(ev, t, true))
            return usage("unknown model '%s' (svd, svd-norm, preint, guided, manual, sog, jimenez, svd-rN, sog-rN)",
                         t);
    if (ev->count == 0) return usage("--models needs at least one model%s", "");
    return CLI_OK;
}

static void add_table65(eval *ev)
{
    for (int n = 1; n <= T65_MAX && ev->count + 2 <= MAX_ENTRIES; n++) {
        char name[32];
        snprintf(name, sizeof name, "svd-r%d", n);
        ev->t65[n - 1][0] = ev->count;
        add(ev, name, LUCENT_KERNEL_SVD, n, false);
        snprintf(name, sizeof name, "sog-r%d", n);
        ev->t65[n - 1][1] = ev->count;
        add(ev, name, LUCENT_KERNEL_SOG, n, false);
        ev->t65_count = n;
    }
}

/* ---- Millimetres to pixels ----
 * The kernels are per-cell weights on cells of side h; a pixel of side p takes the part of each
 * cell it covers (exact area resampling, separable: the pixel kernel of a product a(x) a(y) is the
 * product of the pixel kernels of a). */

static lucent_status make_resampler(eval *ev)
{
    const lucent_kernel2d *gt = ev->gt;
    double h = gt->h, p = ev->o->mm_per_pixel;
    int hp = (int)ceil((gt->half + 0.5) * h / p - 0.5);
    if (hp < 0) hp = 0;
    if (hp > LUCENT_CONVOLVE_MAX_SIZE / 2)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "kernel of %.4g mm needs %d pixels at %.4g mm per pixel (at most %d): raise --mm-per-pixel",
                            (gt->half + 0.5) * h, 2 * hp + 1, p, LUCENT_CONVOLVE_MAX_SIZE);
    int np = 2 * hp + 1, nc = 2 * gt->half + 1;
    ev->hp = hp;
    ev->w = calloc((size_t)np * (size_t)nc, sizeof *ev->w);
    ev->wlo = malloc((size_t)np * sizeof *ev->wlo);
    ev->whi = malloc((size_t)np * sizeof *ev->whi);
    if (!ev->w || !ev->wlo || !ev->whi) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: resampler");
    for (int i = 0; i < np; i++) {
        double lo = (i - hp - 0.5) * p, hi = (i - hp + 0.5) * p;
        ev->wlo[i] = nc, ev->whi[i] = -1;
        for (int j = 0; j < nc; j++) {
            double clo = (j - gt->half - 0.5) * h, chi = (j - gt->half + 0.5) * h;
            double ov = fmin(hi, chi) - fmax(lo, clo);
            if (ov <= 0) continue;
            ev->w[(size_t)i * nc + j] = ov / h;
            if (j < ev->wlo[i]) ev->wlo[i] = j;
            ev->whi[i] = j;
        }
    }
    return LUCENT_OK;
}

static void resample_1d(const eval *ev, const double *a, float *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->gt->half + 1;
    for (int i = 0; i < np; i++) {
        double sum = 0;
        for (int j = ev->wlo[i]; j <= ev->whi[i]; j++) sum += ev->w[(size_t)i * nc + j] * a[j];
        dest[i] = (float)sum;
    }
}

/* The ground truth's channel c on the pixel grid, np * np floats. */
static lucent_status resample_2d(const eval *ev, int c, float *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->gt->half + 1;
    double *tmp = malloc((size_t)nc * (size_t)np * sizeof *tmp); /* tmp[yj][xi] */
    if (!tmp) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: resampling");
    const double *g = ev->gt->value[c];
    for (int yj = 0; yj < nc; yj++)
        for (int xi = 0; xi < np; xi++) {
            double sum = 0;
            for (int xj = ev->wlo[xi]; xj <= ev->whi[xi]; xj++)
                sum += g[(size_t)yj * nc + xj] * ev->w[(size_t)xi * nc + xj];
            tmp[(size_t)yj * np + xi] = sum;
        }
    for (int yi = 0; yi < np; yi++)
        for (int xi = 0; xi < np; xi++) {
            double sum = 0;
            for (int yj = ev->wlo[yi]; yj <= ev->whi[yi]; yj++)
                sum += ev->w[(size_t)yi * nc + yj] * tmp[(size_t)yj * np + xi];
            dest[(size_t)yi * np + xi] = (float)sum;
        }
    free(tmp);
    return LUCENT_OK;
}

/* ---- Files ---- */

static void path_in(const eval *ev, const char *name, char *dest, size_t size)
{
    int n = snprintf(dest, size, "%s/%s", ev->dir, name);
    if (n >= (int)size) dest[size - 1] = '\0';
}

static lucent_status wrote(lucent_status s, const char *path)
{
    if (s == LUCENT_OK) cli_info("wrote %s", path);
    return s;
}

/* NAME.png (clamped, sRGB) and NAME.exr (linear float). */
static lucent_status write_pair(const eval *ev, const char *name, const lucent_image *img, bool exr)
{
    char path[600], file[128];
    snprintf(file, sizeof file, "%s.png", name);
    path_in(ev, file, path, sizeof path);
    lucent_status s = wrote(lucent_image_write(path, img, NULL), path);
    if (s != LUCENT_OK || !exr) return s;
    snprintf(file, sizeof file, "%s.exr", name);
    path_in(ev, file, path, sizeof path);
    return wrote(lucent_image_write(path, img, NULL), path);
}

static lucent_status write_heat(const eval *ev, const char *name, const lucent_image *img)
{
    lucent_image *err = NULL, *heat = NULL;
    lucent_status s = lucent_image_error_map(img, ev->exact, false, 0, &err);
    if (s == LUCENT_OK) s = lucent_image_heatmap(err, (float)ev->o->heat_scale, &heat);
    char file[128];
    snprintf(file, sizeof file, "%s-diff", name);
    if (s == LUCENT_OK) s = write_pair(ev, file, heat, false);
    lucent_image_destroy(err);
    lucent_image_destroy(heat);
    return s;
}

/* ---- Image space ---- */

static lucent_status convolve_exact(eval *ev)
{
    int np = 2 * ev->hp + 1;
    float *w[3] = {NULL, NULL, NULL};
    lucent_status s = LUCENT_OK;
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) {
        w[c] = malloc((size_t)np * (size_t)np * sizeof *w[c]);
        s = w[c] ? resample_2d(ev, c, w[c]) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: kernel");
    }
    lucent_conv_kernel2d k = {np, {w[0], w[1], w[2]}};
    if (s == LUCENT_OK) s = lucent_image_create(ev->signal->width, ev->signal->height, ev->signal->channels, &ev->exact);
    if (s == LUCENT_OK) s = lucent_convolve_2d(ev->signal, &k, LUCENT_BORDER_CLAMP, cli_pool(), ev->exact);
    for (int c = 0; c < 3; c++) free(w[c]);
    return s;
}

static lucent_status convolve_separable(const eval *ev, const lucent_kernel *k, lucent_image *dest)
{
    int np = 2 * ev->hp + 1, nc = 2 * ev->gt->half + 1, rank = k->rank;
    float *buf = malloc((size_t)2 * rank * 3 * np * sizeof *buf);
    const float **kx = malloc((size_t)2 * rank * 3 * sizeof *kx);
    if (!buf || !kx) {
        free(buf), free(kx);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: separable kernel");
    }
    const float **ky = kx + rank * 3;
    for (int r = 0; r < rank; r++)
        for (int c = 0; c < 3; c++) {
            float *x = buf + ((size_t)r * 3 + c) * np, *y = buf + ((size_t)(rank + r) * 3 + c) * np;
            resample_1d(ev, k->a[c] + (size_t)r * nc, y);
            for (int i = 0; i < np; i++) x[i] = (float)k->sign[c][r] * y[i];
            kx[r * 3 + c] = x, ky[r * 3 + c] = y;
        }
    lucent_status s = lucent_convolve_separable_sum(ev->signal, rank, kx, ky, np, LUCENT_BORDER_CLAMP, cli_pool(), dest);
    free(buf);
    free(kx);
    return s;
}

static lucent_status convolve_taps(const eval *ev, const lucent_kernel *k, lucent_image *dest)
{
    lucent_taps_desc td = lucent_taps_defaults();
    td.count = ev->o->taps;
    lucent_taps *t = NULL;
    lucent_status s = lucent_kernel_taps(k, &td, &t);
    if (s != LUCENT_OK) return s;
    size_t n = (size_t)t->count, per = n * (size_t)t->rank;
    float *buf = malloc((n + 3 * per + 3 * (size_t)t->rank) * sizeof *buf);
    if (!buf) {
        lucent_taps_destroy(t);
        return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: taps");
    }
    for (size_t i = 0; i < n; i++) buf[i] = (float)(t->offset[i] / ev->o->mm_per_pixel);
    lucent_conv_taps ct = {.count = t->count, .rank = t->rank, .offsets = buf};
    for (int c = 0; c < 3; c++) {
        float *w = buf + n + c * per, *sg = buf + n + 3 * per + (size_t)c * t->rank;
        for (size_t i = 0; i < per; i++) w[i] = (float)t->weight[c][i];
        for (int r = 0; r < t->rank; r++) sg[r] = (float)t->sign[c][r];
        ct.weights[c] = w, ct.sign[c] = sg;
    }
    s = lucent_convolve_taps(ev->signal, &ct, LUCENT_BORDER_CLAMP, cli_pool(), dest);
    free(buf);
    lucent_taps_destroy(t);
    return s;
}

/* Builds entry e, measures it in kernel and image space, writes its images. */
static lucent_status evaluate(eval *ev, entry *e)
{
    lucent_status s = lucent_kernel_build(ev->gt, ev->p, ev->m.name, &e->desc, &e->k);
    if (s != LUCENT_OK) {
        if (e->desc.model != LUCENT_KERNEL_MANUAL) return s;
        snprintf(e->note, sizeof e->note, "%s", lucent_last_error()); /* no Table A.1 preset */
        lucent_clear_error();
        cli_info("%s: skipped (%s)", e->name, e->note);
        return LUCENT_OK;
    }
    lucent_kernel_rms(e->k, ev->gt, e->krms);
    lucent_image *img = NULL;
    s = lucent_image_create(ev->signal->width, ev->signal->height, ev->signal->channels, &img);
    if (s == LUCENT_OK) s = convolve_separable(ev, e->k, img);
    if (s == LUCENT_OK) s = lucent_image_compare(img, ev->exact, NULL, &e->sep);
    if (s == LUCENT_OK && e->plot) s = write_pair(ev, e->name, img, true);
    if (s == LUCENT_OK && e->plot) s = write_heat(ev, e->name, img);
    if (s == LUCENT_OK && ev->o->taps > 0) {
        char name[64];
        snprintf(name, sizeof name, "%s-taps", e->name);
        s = convolve_taps(ev, e->k, img);
        if (s == LUCENT_OK) s = lucent_image_compare(img, ev->exact, NULL, &e->taps);
        if (s == LUCENT_OK && e->plot) s = write_pair(ev, name, img, true);
        if (s == LUCENT_OK && e->plot) s = write_heat(ev, name, img);
        e->have_taps = s == LUCENT_OK;
    }
    lucent_image_destroy(img);
    return s;
}

/* ---- Kernel slices (Figure 6.2) ---- */

/* A(i, j) of channel c, per mm^2. */
static double model_at(const lucent_kernel *k, int c, int i, int j)
{
    int n = 2 * k->half + 1;
    double sum = 0;
    for (int r = 0; r < k->rank; r++) sum += k->sign[c][r] * k->a[c][r * n + i] * k->a[c][r * n + j];
    return sum / (k->h * k->h);
}

static lucent_status write_slices(const eval *ev, bool diagonal)
{
    const lucent_kernel2d *gt = ev->gt;
    int n = 2 * gt->half + 1, curves = 1;
    for (int i = 0; i < ev->count; i++) curves += ev->e[i].plot && ev->e[i].k;
    double *buf = malloc((size_t)n * (size_t)(1 + 3 * curves) * sizeof *buf);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: slices");
    double *x = buf, scale = diagonal ? sqrt(2.0) : 1.0, reach = 0;
    for (int j = 0; j < n; j++) x[j] = (j - gt->half) * gt->h * scale;
    lucent_plot_series s[3][16];
    lucent_plot_panel panels[3];
    static const char *const titles[] = {"red channel", "green channel", "blue channel"};
    static const char *const colors[] = {"#e67e22", "#2e64c8", "#27ae60", "#8e44ad", "#c0392b", "#8c564b", "#7f8c8d",
                                         "#d35400", "#2c3e50", "#f1c40f", "#1abc9c", "#e84393", "#6c5ce7", "#00b894", "#636e72"};
    for (int c = 0; c < 3; c++) {
        double *y = buf + n * (1 + (size_t)c * curves), peak = 0;
        for (int j = 0; j < n; j++) {
            y[j] = gt->value[c][(size_t)(diagonal ? j : gt->half) * n + j] / (gt->h * gt->h);
            peak = fmax(peak, y[j]);
        }
        for (int j = 0; j < n; j++)
            if (y[j] > 1e-2 * peak) reach = fmax(reach, fabs(x[j]));
        int m = 0;
        s[c][m++] = (lucent_plot_series){.label = "ground truth", .x = x, .y = y, .count = n, .color = "#000000"};
        for (int i = 0; i < ev->count && m < 16; i++) {
            const entry *e = &ev->e[i];
            if (!e->plot || !e->k) continue;
            double *ym = buf + n * (1 + (size_t)c * curves + m);
            for (int j = 0; j < n; j++) ym[j] = model_at(e->k, c, diagonal ? j : gt->half, j);
            s[c][m] = (lucent_plot_series){.label = e->name, .x = x, .y = ym, .count = n,
                                           .color = colors[(m - 1) % 15], .dashed = true};
            m++;
        }
        panels[c] = (lucent_plot_panel){.title = titles[c], .x_label = diagonal ? "r along x = y (mm)" : "x (mm), y = 0",
                                        .y_label = c == 0 ? "kernel (1/mm^2)" : NULL, .series = s[c],
                                        .series_count = m, .y_min = 0, .y_max = 1.6 * peak};
    }
    if (reach <= 0) reach = gt->half * gt->h * scale;
    for (int c = 0; c < 3; c++) panels[c].x_min = -reach, panels[c].x_max = reach;
    char title[200], path[600];
    snprintf(title, sizeof title, "%s: kernel models against the ground truth, %s slice", ev->m.name,
             diagonal ? "diagonal" : "axis (y = 0)");
    path_in(ev, diagonal ? "kernel-diagonal.svg" : "kernel-axis.svg", path, sizeof path);
    lucent_plot_desc desc = {.title = title, .panels = panels, .panel_count = 3, .panel_width = 440};
    lucent_status st = wrote(lucent_plot_write_svg(path, &desc), path);
    free(buf);
    return st;
}

/* ---- Tables ---- */

static void md_row(lucent_strbuf *b, const char *name, const double v[3])
{
    lucent_strbuf_printf(b, "| %s | %.4g | %.4g | %.4g |\n", name, v[0], v[1], v[2]);
}

static lucent_status write_tables(const eval *ev)
{
    lucent_strbuf b = {0};
    const options *o = ev->o;
    lucent_strbuf_printf(&b, "# %s: kernel models against the ground truth\n\n", ev->m.name);
    lucent_strbuf_printf(&b, "Profile %s; ground truth %d x %d cells of %.4g mm. Signal %s, %d x %d pixels at %.4g mm "
                             "per pixel (pixel kernel %d x %d), clamped borders.\n\n",
                         o->profile, 2 * ev->gt->half + 1, 2 * ev->gt->half + 1, ev->gt->h, o->signal,
                         ev->signal->width, ev->signal->height, o->mm_per_pixel, 2 * ev->hp + 1, 2 * ev->hp + 1);
    lucent_strbuf_printf(&b, "## Kernel space (Freude Table 6.3)\n\nRMS of A - R_d over the grid cells (cell weights; "
                             "each channel sums to 1).\n\n| model | R | G | B |\n|---|---|---|---|\n");
    for (int i = 0; i < ev->count; i++)
        if (ev->e[i].plot && ev->e[i].k) md_row(&b, ev->e[i].name, ev->e[i].krms);
    lucent_strbuf_printf(&b, "\n## Image space (Freude Table 6.4)\n\nRMS (relative RMS) of the model's convolution "
                             "against the exact 2-D convolution.\n\n| model | R | G | B |\n|---|---|---|---|\n");
    for (int pass = 0; pass < 2; pass++)
        for (int i = 0; i < ev->count; i++) {
            const entry *e = &ev->e[i];
            if (!e->plot || !e->k || (pass && !e->have_taps)) continue;
            const lucent_image_error_stats *st = pass ? &e->taps : &e->sep;
            lucent_strbuf_printf(&b, "| %s%s |", e->name, pass ? ", taps" : ", separable");
            for (int c = 0; c < 3; c++) lucent_strbuf_printf(&b, " %.4g (%.3g) |", st->rms[c], st->rel_rms[c]);
            lucent_strbuf_printf(&b, "\n");
        }
    if (o->taps > 0) lucent_strbuf_printf(&b, "\nTaps: %d per pass.\n", o->taps);
    for (int i = 0; i < ev->count; i++)
        if (ev->e[i].note[0]) lucent_strbuf_printf(&b, "\nSkipped %s: %s\n", ev->e[i].name, ev->e[i].note);
    if (ev->t65_count > 0) {
        lucent_strbuf_printf(&b, "\n## SVD rank N against N Gaussians (Freude Table 6.5)\n\nImage-space RMS of the "
                                 "separable convolutions (mean over R, G, B), kernel-space RMS in brackets.\n\n"
                                 "| N | SVD | SoG | better |\n|---|---|---|---|\n");
        for (int n = 0; n < ev->t65_count; n++) {
            const entry *a = &ev->e[ev->t65[n][0]], *g = &ev->e[ev->t65[n][1]];
            double ia = (a->sep.rms[0] + a->sep.rms[1] + a->sep.rms[2]) / 3;
            double ig = (g->sep.rms[0] + g->sep.rms[1] + g->sep.rms[2]) / 3;
            double ka = (a->krms[0] + a->krms[1] + a->krms[2]) / 3, kg = (g->krms[0] + g->krms[1] + g->krms[2]) / 3;
            lucent_strbuf_printf(&b, "| %d | %.4g (%.3g) | %.4g (%.3g) | %s |\n", n + 1, ia, ka, ig, kg,
                                 ia < ig ? "SVD" : ia > ig ? "SoG" : "tie");
        }
    }
    char *text = NULL, path[600];
    lucent_status s = lucent_strbuf_finish(&b, &text);
    path_in(ev, "tables.md", path, sizeof path);
    if (s == LUCENT_OK) s = wrote(lucent_write_file(path, text, strlen(text)), path);
    free(text);
    return s;
}

static void json_stats(cJSON *j, const char *key, const lucent_image_error_stats *st)
{
    cJSON *o = cJSON_AddObjectToObject(j, key);
    lucent_json_add_numbers(o, "rms", st->rms, 3);
    lucent_json_add_numbers(o, "relative_rms", st->rel_rms, 3);
    lucent_json_add_numbers(o, "max_abs", st->max_abs, 3);
}

static lucent_status write_json(const eval *ev)
{
    const options *o = ev->o;
    cJSON *root = cJSON_CreateObject();
    cJSON_AddStringToObject(root, "material", ev->m.name);
    cJSON_AddStringToObject(root, "profile", o->profile);
    cJSON *gt = cJSON_AddObjectToObject(root, "ground_truth");
    cJSON_AddNumberToObject(gt, "cells", 2 * ev->gt->half + 1);
    cJSON_AddNumberToObject(gt, "cell_mm", ev->gt->h);
    cJSON *sig = cJSON_AddObjectToObject(root, "signal");
    cJSON_AddStringToObject(sig, "name", o->signal);
    cJSON_AddNumberToObject(sig, "width", ev->signal->width);
    cJSON_AddNumberToObject(sig, "height", ev->signal->height);
    cJSON_AddNumberToObject(sig, "mm_per_pixel", o->mm_per_pixel);
    cJSON_AddNumberToObject(sig, "kernel_pixels", 2 * ev->hp + 1);
    cJSON_AddStringToObject(sig, "border", "clamp");
    cJSON_AddNumberToObject(root, "taps", o->taps);
    cJSON *models = cJSON_AddArrayToObject(root, "models");
    for (int i = 0; i < ev->count; i++) {
        const entry *e = &ev->e[i];
        cJSON *j = cJSON_CreateObject();
        cJSON_AddItemToArray(models, j);
        cJSON_AddStringToObject(j, "name", e->name);
        cJSON_AddStringToObject(j, "model", lucent_kernel_model_name(e->desc.model));
        cJSON_AddNumberToObject(j, "rank", e->desc.rank);
        if (!e->k) {
            cJSON_AddStringToObject(j, "skipped", e->note);
            continue;
        }
        lucent_json_add_numbers(j, "kernel_rms", e->krms, 3);
        json_stats(j, "separable", &e->sep);
        if (e->have_taps) json_stats(j, "taps", &e->taps);
    }
    if (ev->t65_count > 0) {
        cJSON *t = cJSON_AddArrayToObject(root, "table65");
        for (int n = 0; n < ev->t65_count; n++) {
            const entry *a = &ev->e[ev->t65[n][0]], *g = &ev->e[ev->t65[n][1]];
            cJSON *j = cJSON_CreateObject();
            cJSON_AddItemToArray(t, j);
            cJSON_AddNumberToObject(j, "n", n + 1);
            lucent_json_add_numbers(j, "svd_kernel_rms", a->krms, 3);
            lucent_json_add_numbers(j, "sog_kernel_rms", g->krms, 3);
            lucent_json_add_numbers(j, "svd_image_rms", a->sep.rms, 3);
            lucent_json_add_numbers(j, "sog_image_rms", g->sep.rms, 3);
        }
    }
    char path[600];
    path_in(ev, "results.json", path, sizeof path);
    lucent_status s = wrote(lucent_json_write_file(path, root), path);
    cJSON_Delete(root);
    return s;
}

/* ---- Driver ---- */

static lucent_status make_dir(const char *dir)
{
    if (mkdir(dir, 0777) == 0) return LUCENT_OK;
    struct stat st;
    if (errno == EEXIST && stat(dir, &st) == 0 && S_ISDIR(st.st_mode)) return LUCENT_OK;
    return lucent_error(LUCENT_ERR_IO, "%s: cannot create the output directory: %s", dir, strerror(errno));
}

static lucent_status run(eval *ev)
{
    const options *o = ev->o;
    lucent_status s = lucent_material_resolve(o->spec, &ev->m);
    if (s != LUCENT_OK) return s;
    if (o->out)
        snprintf(ev->dir, sizeof ev->dir, "%s", o->out);
    else
        snprintf(ev->dir, sizeof ev->dir, "%s-eval", ev->m.name);
    if (o->table65 || !strcasecmp(ev->m.name, "skin1")) add_table65(ev);
    s = make_dir(ev->dir);
    if (s == LUCENT_OK) s = lucent_profile_from_source(
            &(lucent_profile_source_desc){.source = o->profile, .photons = (uint64_t)o->photons,
                                          .seed = (uint64_t)o->seed, .pool = cli_pool()},
            &ev->m, &ev->p);
    if (s == LUCENT_OK) s = lucent_kernel2d_from_profile(ev->p, NULL, &ev->gt);
    if (s == LUCENT_OK) s = make_resampler(ev);
    if (s == LUCENT_OK) s = lucent_signal_load(o->signal, o->size, o->size, &ev->signal);
    if (s == LUCENT_OK && ev->signal->channels != 3) {
        lucent_image *rgb = NULL;
        s = lucent_image_convert_channels(ev->signal, 3, &rgb);
        lucent_image_destroy(ev->signal);
        ev->signal = rgb;
    }
    if (s == LUCENT_OK) s = write_pair(ev, "signal", ev->signal, false);
    if (s == LUCENT_OK) s = convolve_exact(ev);
    if (s == LUCENT_OK) s = write_pair(ev, "exact", ev->exact, true);
    for (int i = 0; i < ev->count && s == LUCENT_OK; i++) s = evaluate(ev, &ev->e[i]);
    if (s == LUCENT_OK) s = write_slices(ev, false);
    if (s == LUCENT_OK) s = write_slices(ev, true);
    if (s == LUCENT_OK) s = write_tables(ev);
    if (s == LUCENT_OK) s = write_json(ev);
    return s;
}

int cmd_kernel_eval(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.profile = "dipole",
                 .signal = "edge",
                 .size = LUCENT_SIGNAL_DEFAULT_SIZE,
                 .taps = 17,
                 .photons = 1000000,
                 .seed = 1,
                 .mm_per_pixel = LUCENT_SIGNAL_MM_PER_PIXEL,
                 .heat_scale = 0.1};
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    eval *ev = calloc(1, sizeof *ev);
    if (!ev) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval"), cli_fail();
    ev->o = &o;
    rc = choose_models(ev);
    lucent_status s = rc == CLI_OK ? run(ev) : LUCENT_OK;
    for (int i = 0; i < ev->count; i++) lucent_kernel_destroy(ev->e[i].k);
    lucent_kernel2d_destroy(ev->gt);
    lucent_profile_destroy(ev->p);
    lucent_image_destroy(ev->signal);
    lucent_image_destroy(ev->exact);
    free(ev->w), free(ev->wlo), free(ev->whi);
    free(ev);
    if (rc != CLI_OK) return rc;
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
