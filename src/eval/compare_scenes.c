/* lucent_compare_run's further measures of a scene: every method's error per region of the image,
 * each light alone (reference and methods), and the up-front word on methods that are slow on the
 * run's GL renderer. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "eval/compare_store.h"

/* ---- regions ---- */

/* Fills t from the region bits: per region the pixels, the reference's share and noise, and per method
 * (images[0 .. count)) the error, the brightness and the share of its squared error. */
static lucent_status fill_regions(region_table *t, const uint8_t *bits, const float *mask, const lucent_image *ref,
                                  const lucent_image *var, lucent_image *const *images, int count)
{
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < LUCENT_COMPARE_REGION_COUNT && s == LUCENT_OK; k++) {
        lucent_compare_region_values v = {0};
        s = lucent_compare_region_measure(bits, k, mask, ref, var, ref, &v);
        t->regions[k] = (lucent_compare_region){.name = lucent_compare_region_name(k),
                                                .pixels = v.pixels,
                                                .energy = v.energy,
                                                .reference_noise = v.reference_noise,
                                                .rel_rms = t->rel_rms[k],
                                                .ratio = t->ratio[k],
                                                .error_share = t->share[k]};
        for (int m = 0; m < count && s == LUCENT_OK; m++) {
            s = lucent_compare_region_measure(bits, k, mask, ref, var, images[m], &v);
            t->rel_rms[k][m] = v.rel_rms, t->ratio[k][m] = v.ratio, t->share[k][m] = v.error_share;
        }
    }
    return s;
}

/* What each pixel of the scene sees (the tracer's probe), once. */
static lucent_status probe_scene(scene_store *ss)
{
    if (ss->probe.object) return LUCENT_OK;
    lucent_tracer *tr;
    lucent_status s = lucent_tracer_create(ss->scene, NULL, &tr);
    if (s == LUCENT_OK) s = lucent_tracer_probe(tr, &ss->probe);
    lucent_tracer_destroy(tr);
    return s;
}

lucent_status eval_scene_regions(const run *r, scene_store *ss)
{
    const lucent_trace_result *ref = &ss->ref.result;
    size_t n = (size_t)ref->image->width * (size_t)ref->image->height;
    lucent_status s = probe_scene(ss);
    if (s == LUCENT_OK && !(ss->region_bits = malloc(n))) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK)
        s = lucent_compare_regions(ss->scene, &ss->probe, ref->coverage, ss->mask, NULL, r->d.pool, ss->region_bits);
    if (s == LUCENT_OK)
        s = fill_regions(&ss->region, ss->region_bits, ss->mask, ref->image, ref->variance, ss->images,
                         ss->method_count);
    if (s == LUCENT_OK) ss->regions = ss->region.regions, ss->region_count = LUCENT_COMPARE_REGION_COUNT;
    return s == LUCENT_OK ? s : lucent_error_context(s, "%s: regions", ss->stem);
}

/* ---- each light alone ---- */

/* Renders every method of the scene's table with scene (one light on) into images. */
static lucent_status render_methods(const run *r, const scene_store *ss, const lucent_scene *scene,
                                    const char *cache_dir, const char *label, lucent_image **images)
{
    lucent_renderer *rend = NULL;
    lucent_status s =
        lucent_renderer_create(r->gl, scene, &(lucent_renderer_desc){.pool = r->d.pool, .cache_dir = cache_dir}, &rend);
    lucent_progress *bar = lucent_progress_begin(label, (uint64_t)ss->renderer_count);
    lucent_progress_set_unit(bar, "method");
    for (int m = 0; m < ss->renderer_count && s == LUCENT_OK; m++) {
        lucent_render_settings rs = scene->render;
        lucent_render_result res = {0};
        s = eval_method_settings(ss->methods[m].name, &rs);
        eval_image_samples(r->d.samples, &rs);
        if (s == LUCENT_OK) s = lucent_render(rend, &rs, &res);
        if (s == LUCENT_OK) images[m] = res.image, res.image = NULL;
        lucent_render_result_free(&res);
        lucent_progress_add(bar, 1);
        if (s != LUCENT_OK) s = lucent_error_context(s, "method %s", ss->methods[m].name);
    }
    lucent_progress_end(bar);
    lucent_renderer_destroy(rend);
    return s;
}

/* Light l alone: its reference, every method, their errors overall and by region. */
static lucent_status measure_light(const run *r, const char *cache_dir, scene_store *ss, int l)
{
    const lucent_scene *full = ss->scene;
    char off[EVAL_MAX_LIGHTS][48];
    const char *sets[EVAL_MAX_LIGHTS];
    int n = 0;
    for (int k = 0; k < full->light_count && n < EVAL_MAX_LIGHTS; k++)
        if (k != l) snprintf(off[n], sizeof off[n], "lights[%d].intensity=0", k), sets[n] = off[n], n++;
    lucent_scene *scene = NULL;
    eval_reference ref = {0};
    lucent_image *images[LUCENT_COMPARE_MAX_METHODS] = {0};
    char label[EVAL_NAME_SIZE + 48];
    snprintf(ss->light_name[l], sizeof ss->light_name[l], "lights[%d] (%s)", l,
             lucent_light_type_name(full->lights[l].type));
    lucent_status s = eval_load_scene(r, r->d.scenes[r->scene_index], sets, n, &scene);
    snprintf(label, sizeof label, "reference %s, lights[%d] alone", ss->stem, l);
    if (s == LUCENT_OK)
        s = eval_reference_trace(
            scene,
            &(eval_reference_desc){
                .spp = r->d.spp, .time_limit = r->d.time_limit, .runs = 1, .pool = r->d.pool, .label = label},
            &ref);
    snprintf(label, sizeof label, "%s lights[%d] alone", ss->stem, l);
    if (s == LUCENT_OK) s = render_methods(r, ss, scene, cache_dir, label, images);
    bool on[64] = {false};
    on[l] = true;
    uint8_t *bits = malloc((size_t)ss->probe.width * (size_t)ss->probe.height);
    if (s == LUCENT_OK && !bits) s = lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    if (s == LUCENT_OK)
        s = lucent_compare_regions(full, &ss->probe, ss->ref.result.coverage, ss->mask, on, r->d.pool, bits);
    if (s == LUCENT_OK)
        s = fill_regions(&ss->light_region[l], bits, ss->mask, ref.result.image, ref.result.variance, images,
                         ss->renderer_count);
    for (int m = ss->renderer_count; m < ss->method_count; m++) { /* a peer renders the whole scene only */
        ss->light_rms[l][m] = ss->light_ratio[l][m] = NAN;
        for (int k = 0; k < LUCENT_COMPARE_REGION_COUNT; k++)
            ss->light_region[l].rel_rms[k][m] = ss->light_region[l].ratio[k][m] = ss->light_region[l].share[k][m] = NAN;
    }
    for (int m = 0; m < ss->renderer_count && s == LUCENT_OK; m++) {
        lucent_image_error_stats e;
        s = lucent_image_compare(images[m], ref.result.image, ss->mask, &e);
        ss->light_rms[l][m] = e.rel_rms_all;
        double sm = 0, sr = 0;
        for (size_t i = 0; i < (size_t)ss->probe.width * (size_t)ss->probe.height; i++)
            for (int c = 0; c < 3 && ss->mask[i] > 0.5f; c++)
                sm += images[m]->data[i * (size_t)images[m]->channels + (size_t)c],
                    sr += ref.result.image->data[i * (size_t)ref.result.image->channels + (size_t)c];
        ss->light_ratio[l][m] = sr != 0 ? sm / sr : NAN;
    }
    if (s == LUCENT_OK)
        ss->lights[l] = (lucent_compare_light){
            .name = ss->light_name[l],
            .reference_spp = (int)ref.result.spp,
            .reference_noise = ref.result.spp >= LUCENT_COMPARE_MIN_SPP
                                   ? lucent_compare_reference_noise(ref.result.image, ref.result.variance, ss->mask)
                                   : NAN,
            .rel_rms = ss->light_rms[l],
            .ratio = ss->light_ratio[l],
            .regions = ss->light_region[l].regions,
            .region_count = LUCENT_COMPARE_REGION_COUNT};
    free(bits);
    for (int m = 0; m < LUCENT_COMPARE_MAX_METHODS; m++) lucent_image_destroy(images[m]);
    eval_reference_free(&ref);
    lucent_scene_destroy(scene);
    return s == LUCENT_OK ? s : lucent_error_context(s, "%s: lights[%d] alone", ss->stem, l);
}

lucent_status eval_scene_lights(const run *r, const char *cache_dir, scene_store *ss)
{
    lucent_status s = probe_scene(ss);
    int count = ss->scene->light_count < EVAL_MAX_LIGHTS ? ss->scene->light_count : EVAL_MAX_LIGHTS;
    for (int l = 0; l < count && s == LUCENT_OK; l++) {
        s = measure_light(r, cache_dir, ss, l);
        if (s == LUCENT_OK) ss->light_count = l + 1;
    }
    return s;
}

/* ---- slow methods ---- */

/* Seconds a frame of the methods that are slow on a software rasteriser: llvmpipe on 2 cores,
 * bunny-skin at --scale 0.5 (256 x 256), load average 15 (docs/compare.md, "Run times"; lambert took
 * 0.39 s there): texture-space diffusion renders and blurs each object's atlas at render.tsd_size,
 * points splats every surfel in several passes. */
static const struct {
    const char *method;
    double seconds;
} k_slow[] = {{"tsd", 33}, {"points", 13}};

static bool software_gl(const char *renderer)
{
    return strstr(renderer, "llvmpipe") || strstr(renderer, "softpipe") || strstr(renderer, "SwiftShader") ||
           strstr(renderer, "software");
}

void eval_warn_slow(const run *r)
{
    if (!r->d.on_event || !software_gl(r->device)) return;
    int timed = r->d.frames < LUCENT_COMPARE_MAX_FRAMES ? r->d.frames : LUCENT_COMPARE_MAX_FRAMES;
    lucent_render_settings probe = lucent_render_settings_defaults();
    eval_image_samples(r->d.samples, &probe);
    int frames = timed + probe.view.samples; /* the image's samples, then the timed frames */
    for (int i = 0; i < r->d.method_count; i++) {
        const char *m = r->d.methods[i];
        for (size_t k = 0; k < sizeof k_slow / sizeof k_slow[0]; k++) {
            size_t len = strlen(k_slow[k].method);
            if (strncmp(m, k_slow[k].method, len) != 0 || (m[len] != '\0' && m[len] != ':')) continue;
            double total = k_slow[k].seconds * frames * r->d.scene_count;
            char reason[400];
            snprintf(reason, sizeof reason,
                     "%s is slow on a software GL renderer (%.120s): about %.0f s a frame on 2 cores at 256 x 256 "
                     "(bunny-skin, --scale 0.5), %d frames a scene (--frames %d and the image's --samples %d): "
                     "about %.0f min for %d scene%s; --frames 1 --samples 1 or leaving it out saves most of it",
                     m, r->device, k_slow[k].seconds, frames, timed, probe.view.samples,
                     total / 60 < 1 ? 1 : total / 60, r->d.scene_count, r->d.scene_count == 1 ? "" : "s");
            r->d.on_event(&(lucent_eval_event){.kind = LUCENT_EVAL_SLOW, .name = m, .reason = reason, .index = -1},
                          r->d.user);
        }
    }
}
