/* lucent_kernel_eval_run: every separable kernel model of a material against the ground truth, in
 * kernel space (Freude 2014, Table 6.3, Figure 6.2) and in image space on a test signal
 * (Tables 6.4-6.5, Figures 6.6-6.10). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "eval/internal.h"
#include "eval/kernel_eval.h"

lucent_kernel_eval_desc lucent_kernel_eval_defaults(void)
{
    return (lucent_kernel_eval_desc){.profile = {.source = "dipole"},
                                     .signal = "edge",
                                     .size = LUCENT_SIGNAL_DEFAULT_SIZE,
                                     .mm_per_pixel = LUCENT_SIGNAL_MM_PER_PIXEL,
                                     .taps = 17,
                                     .heat_scale = 0.1};
}

/* ---- the desc ---- */

static lucent_status check_desc(const lucent_kernel_eval_desc *d)
{
    if (!d->material) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel-eval: material: required");
    if (d->model_count < 0 || d->model_count > LUCENT_KERNEL_EVAL_MAX_MODELS || (d->model_count && !d->models))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel-eval: model_count: at most %d models",
                            LUCENT_KERNEL_EVAL_MAX_MODELS);
    if (d->size < 0 || !(d->mm_per_pixel >= 0) || !isfinite(d->mm_per_pixel) || !(d->heat_scale >= 0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel-eval: size, mm_per_pixel and heat_scale must be >= 0");
    if (d->taps && (d->taps % 2 != 1 || d->taps < 3 || d->taps > 255))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel-eval: taps: %d is not an odd number in 3..255",
                            d->taps);
    if (d->profile.source && !lucent_profile_source_known(d->profile.source))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "kernel-eval: profile: unknown source '%s' (dipole, better-dipole, burley or mc)",
                            d->profile.source);
    return LUCENT_OK;
}

static lucent_kernel_eval_desc resolve(const lucent_kernel_eval_desc *desc)
{
    lucent_kernel_eval_desc d = *desc, def = lucent_kernel_eval_defaults();
    if (!d.profile.source) d.profile.source = def.profile.source;
    if (!d.profile.pool) d.profile.pool = d.pool;
    if (!d.signal) d.signal = def.signal;
    if (!d.size) d.size = def.size;
    if (!d.mm_per_pixel) d.mm_per_pixel = def.mm_per_pixel;
    if (!d.taps) d.taps = def.taps;
    if (d.no_taps) d.taps = 0;
    if (!d.heat_scale) d.heat_scale = def.heat_scale;
    return d;
}

/* ---- the models ---- */

lucent_status lucent_kernel_eval_model_parse(const char *name, lucent_kernel_desc *dest)
{
    lucent_kernel_model model;
    int rank = 1;
    char base[LUCENT_KERNEL_EVAL_NAME_SIZE], *end = NULL;
    if (strlen(name) >= sizeof base) goto unknown;
    snprintf(base, sizeof base, "%s", name);
    char *r = strstr(base, "-r");
    if (r && (!strncmp(base, "svd-r", 5) || !strncmp(base, "sog-r", 5))) {
        long v = r[2] ? strtol(r + 2, &end, 10) : 0; /* as the CLI reads whole numbers */
        if (!end || *end || v < 1 || v > LUCENT_KERNEL_MAX_RANK) goto unknown;
        rank = (int)v;
        *r = '\0';
    }
    bool norm = !strcmp(base, "svd-norm");
    if (norm) snprintf(base, sizeof base, "svd");
    if (lucent_kernel_model_parse(base, &model) != LUCENT_OK) goto unknown;
    *dest = lucent_kernel_defaults(model);
    dest->rank = rank, dest->k = 1, dest->normalize = norm;
    return LUCENT_OK;
unknown:
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "unknown model '%s' (svd, svd-norm, preint, guided, manual, sog, jimenez, svd-rN, sog-rN)",
                        name);
}

static lucent_status add(ke_run *ev, const char *name, bool plotted)
{
    if (ev->res->model_count >= LUCENT_KERNEL_EVAL_MAX_MODELS)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "kernel-eval: at most %d models",
                            LUCENT_KERNEL_EVAL_MAX_MODELS);
    lucent_kernel_eval_model *e = &ev->res->models[ev->res->model_count];
    memset(e, 0, sizeof *e);
    lucent_status s = lucent_kernel_eval_model_parse(name, &e->desc);
    if (s != LUCENT_OK) return s;
    snprintf(e->name, sizeof e->name, "%s", name);
    e->plotted = plotted;
    ev->res->model_count++;
    return LUCENT_OK;
}

/* The asked models, then Table 6.5's pairs when asked (or for Skin1). */
static lucent_status choose_models(ke_run *ev)
{
    lucent_status s = LUCENT_OK;
    if (ev->d.model_count) {
        for (int i = 0; i < ev->d.model_count && s == LUCENT_OK; i++) s = add(ev, ev->d.models[i], true);
    } else {
        char buf[] = LUCENT_KERNEL_EVAL_DEFAULT_MODELS;
        for (char *save = NULL, *t = strtok_r(buf, ",", &save); t && s == LUCENT_OK; t = strtok_r(NULL, ",", &save))
            s = add(ev, t, true);
    }
    if (!ev->d.table65 && strcasecmp(ev->res->material.name, "skin1")) return s;
    lucent_kernel_eval_result *res = ev->res;
    for (int n = 1; n <= LUCENT_KERNEL_EVAL_TABLE65 && s == LUCENT_OK; n++) {
        if (res->model_count + 2 > LUCENT_KERNEL_EVAL_MAX_MODELS) break;
        char name[LUCENT_KERNEL_EVAL_NAME_SIZE];
        res->table65[n - 1][0] = res->model_count;
        snprintf(name, sizeof name, "svd-r%d", n);
        s = add(ev, name, false);
        res->table65[n - 1][1] = res->model_count;
        snprintf(name, sizeof name, "sog-r%d", n);
        if (s == LUCENT_OK) s = add(ev, name, false);
        if (s == LUCENT_OK) res->table65_count = n;
    }
    return s;
}

/* ---- files ---- */

/* DIR/NAME.png (clamped, sRGB) and, with exr, DIR/NAME.exr (linear float). */
static lucent_status write_pair(const ke_run *ev, const char *name, const lucent_image *img, bool exr)
{
    if (!ev->d.out) return LUCENT_OK;
    char path[EVAL_PATH_SIZE];
    lucent_status s = eval_path_printf(path, sizeof path, "%s/%s.png", ev->d.out, name);
    if (s == LUCENT_OK) s = eval_wrote(ev->d.on_event, ev->d.user, lucent_image_write(path, img, NULL), path);
    if (s != LUCENT_OK || !exr) return s;
    s = eval_path_printf(path, sizeof path, "%s/%s.exr", ev->d.out, name);
    if (s == LUCENT_OK) s = eval_wrote(ev->d.on_event, ev->d.user, lucent_image_write(path, img, NULL), path);
    return s;
}

/* DIR/NAME-diff.png: the heat map of |img - exact|, mean over RGB. */
static lucent_status write_heat(const ke_run *ev, const char *name, const lucent_image *img)
{
    if (!ev->d.out) return LUCENT_OK;
    lucent_image *err = NULL, *heat = NULL;
    lucent_status s = lucent_image_error_map(img, ev->exact, false, 0, &err);
    if (s == LUCENT_OK) s = lucent_image_heatmap(err, (float)ev->d.heat_scale, &heat);
    char file[EVAL_NAME_SIZE + 16];
    snprintf(file, sizeof file, "%s-diff", name);
    if (s == LUCENT_OK) s = write_pair(ev, file, heat, false);
    lucent_image_destroy(err);
    lucent_image_destroy(heat);
    return s;
}

static lucent_status write_reports(const ke_run *ev)
{
    if (!ev->d.out) return LUCENT_OK;
    static const char *const names[] = {"kernel-axis.svg", "kernel-diagonal.svg", "tables.md", "results.json"};
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < 4 && s == LUCENT_OK; k++) {
        char path[EVAL_PATH_SIZE];
        s = eval_path_printf(path, sizeof path, "%s/%s", ev->d.out, names[k]);
        if (s != LUCENT_OK) break;
        s = k < 2    ? lucent_kernel_eval_write_slices(path, ev->res, k == 1)
            : k == 2 ? lucent_kernel_eval_write_tables(path, ev->res)
                     : lucent_kernel_eval_write_json(path, ev->res);
        eval_wrote(ev->d.on_event, ev->d.user, s, path);
    }
    return s;
}

/* ---- one model ---- */

/* Builds model e, measures it in kernel and image space, writes its images. */
static lucent_status evaluate(ke_run *ev, int index)
{
    lucent_kernel_eval_model *e = &ev->res->models[index];
    lucent_status s =
        lucent_kernel_build(ev->res->ground_truth, ev->profile, ev->res->material.name, &e->desc, &e->kernel);
    if (s != LUCENT_OK) {
        if (e->desc.model != LUCENT_KERNEL_MANUAL) return s;
        snprintf(e->skipped, sizeof e->skipped, "%s", lucent_last_error()); /* no Table A.1 preset */
        lucent_clear_error();
        if (ev->d.on_event)
            ev->d.on_event(
                &(lucent_eval_event){
                    .kind = LUCENT_EVAL_SKIPPED, .name = e->name, .reason = e->skipped, .index = index},
                ev->d.user);
        return LUCENT_OK;
    }
    lucent_kernel_rms(e->kernel, ev->res->ground_truth, e->kernel_rms);
    lucent_image *img = NULL;
    s = lucent_image_create(ev->signal->width, ev->signal->height, ev->signal->channels, &img);
    if (s == LUCENT_OK) s = ke_convolve_separable(ev, e->kernel, img);
    if (s == LUCENT_OK) s = lucent_image_compare(img, ev->exact, NULL, &e->separable);
    if (s == LUCENT_OK && e->plotted) s = write_pair(ev, e->name, img, true);
    if (s == LUCENT_OK && e->plotted) s = write_heat(ev, e->name, img);
    if (s == LUCENT_OK && ev->res->taps > 0) {
        char name[EVAL_NAME_SIZE];
        snprintf(name, sizeof name, "%s-taps", e->name);
        s = ke_convolve_taps(ev, e->kernel, img);
        if (s == LUCENT_OK) s = lucent_image_compare(img, ev->exact, NULL, &e->taps);
        if (s == LUCENT_OK && e->plotted) s = write_pair(ev, name, img, true);
        if (s == LUCENT_OK && e->plotted) s = write_heat(ev, name, img);
        e->have_taps = s == LUCENT_OK;
    }
    lucent_image_destroy(img);
    return s;
}

/* ---- the run ---- */

static lucent_status load_signal(ke_run *ev)
{
    lucent_status s = lucent_signal_load(ev->d.signal, ev->d.size, ev->d.size, &ev->signal);
    if (s == LUCENT_OK && ev->signal->channels != 3) {
        lucent_image *rgb = NULL;
        s = lucent_image_convert_channels(ev->signal, 3, &rgb);
        lucent_image_destroy(ev->signal);
        ev->signal = rgb;
    }
    if (s == LUCENT_OK) {
        ev->res->signal_width = ev->signal->width;
        ev->res->signal_height = ev->signal->height;
    }
    return s;
}

static lucent_status run(ke_run *ev)
{
    lucent_kernel_eval_result *res = ev->res;
    lucent_status s = choose_models(ev);
    if (s == LUCENT_OK && ev->d.out) s = eval_make_dirs(ev->d.out);
    if (s == LUCENT_OK) s = lucent_profile_from_source(&ev->d.profile, &res->material, &ev->profile);
    if (s == LUCENT_OK) s = lucent_kernel2d_from_profile(ev->profile, NULL, &res->ground_truth);
    if (s == LUCENT_OK) s = ke_make_resampler(ev);
    if (s == LUCENT_OK) s = load_signal(ev);
    if (s == LUCENT_OK) s = write_pair(ev, "signal", ev->signal, false);
    if (s == LUCENT_OK) s = ke_convolve_exact(ev);
    if (s == LUCENT_OK) s = write_pair(ev, "exact", ev->exact, true);
    for (int i = 0; i < res->model_count && s == LUCENT_OK; i++) s = evaluate(ev, i);
    if (s == LUCENT_OK) s = write_reports(ev);
    return s;
}

lucent_status lucent_kernel_eval_run(const lucent_kernel_eval_desc *desc, lucent_kernel_eval_result *dest)
{
    *dest = (lucent_kernel_eval_result){0};
    lucent_status s = check_desc(desc);
    if (s != LUCENT_OK) return s;
    ke_run ev = {.d = resolve(desc), .res = dest};
    dest->material = *desc->material;
    snprintf(dest->profile, sizeof dest->profile, "%s", ev.d.profile.source);
    snprintf(dest->signal, sizeof dest->signal, "%s", ev.d.signal);
    dest->mm_per_pixel = ev.d.mm_per_pixel;
    dest->taps = ev.d.taps;
    dest->models = calloc(LUCENT_KERNEL_EVAL_MAX_MODELS, sizeof *dest->models);
    s = dest->models ? run(&ev) : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "kernel-eval: out of memory");
    lucent_profile_destroy(ev.profile);
    lucent_image_destroy(ev.signal);
    lucent_image_destroy(ev.exact);
    free(ev.w), free(ev.wlo), free(ev.whi);
    if (s != LUCENT_OK) lucent_kernel_eval_result_free(dest);
    return s;
}

void lucent_kernel_eval_result_free(lucent_kernel_eval_result *result)
{
    if (!result) return;
    for (int i = 0; result->models && i < result->model_count; i++) lucent_kernel_destroy(result->models[i].kernel);
    free(result->models);
    lucent_kernel2d_destroy(result->ground_truth);
    *result = (lucent_kernel_eval_result){0};
}
