/* lucent_compare_run on a tiny scene with a tiny reference (needs an OpenGL 4.5 context; llvmpipe
 * is enough). The errors, the object mask, the reference's noise and the net error are recomputed
 * here from their definitions (docs/compare.md), over the images the run wrote:
 *   mask: pixels whose 3x3 neighbourhood is fully covered (coverage >= 0.999) in the reference;
 *   relative RMS: sqrt(sum (m - r)^2 / sum r^2) over the mask, pooled over R, G, B and per channel;
 *   noise: sqrt(sum variance / sum r^2) over the mask; net: sqrt(max(e^2 - noise^2, 0)). */
#include <cjson/cJSON.h>

#include "lucent/eval.h"
#include "test.h"

typedef struct seen {
    int done, done_index, wrote, html;
    const lucent_compare_result *result;
    int methods_when_done;
} seen;

static void on_event(const lucent_eval_event *e, void *user)
{
    seen *s = user;
    if (e->kind == LUCENT_EVAL_SCENE_DONE) {
        s->done++, s->done_index = e->index;
        s->methods_when_done = s->result->scenes[e->index].report.method_count; /* complete when told */
    }
    if (e->kind == LUCENT_EVAL_WROTE) s->wrote++, s->html += strstr(e->path, "report.html") != NULL;
}

/* The mask by its definition, with no shortcut at the borders. */
static uint64_t hand_mask(const lucent_image *cov, float *dest)
{
    uint64_t n = 0;
    for (int y = 0; y < cov->height; y++)
        for (int x = 0; x < cov->width; x++) {
            bool in = true;
            for (int dy = -1; dy <= 1; dy++)
                for (int dx = -1; dx <= 1; dx++) {
                    int xx = x + dx, yy = y + dy;
                    in = in && xx >= 0 && yy >= 0 && xx < cov->width && yy < cov->height &&
                         cov->data[(size_t)yy * cov->width + xx] >= 0.999f;
                }
            dest[(size_t)y * cov->width + x] = in;
            n += in;
        }
    return n;
}

/* sqrt(sum (m - r)^2 / sum r^2) over the mask; channel c, or -1 for R, G, B pooled. */
static double hand_rel_rms(const lucent_image *m, const lucent_image *r, const float *mask, int c)
{
    double num = 0, den = 0;
    for (size_t i = 0; i < (size_t)r->width * (size_t)r->height; i++) {
        if (mask[i] != 1) continue;
        for (int k = 0; k < 3; k++) {
            if (c >= 0 && k != c) continue;
            double rv = r->data[i * r->channels + k], d = m->data[i * m->channels + k] - rv;
            num += d * d, den += rv * rv;
        }
    }
    return sqrt(num / den);
}

static double hand_noise(const lucent_image *r, const lucent_image *var, const float *mask)
{
    double v = 0, sq = 0;
    for (size_t i = 0; i < (size_t)r->width * (size_t)r->height; i++)
        for (int k = 0; k < 3 && mask[i] == 1; k++) {
            double rv = r->data[i * r->channels + k];
            v += var->data[i * var->channels + k], sq += rv * rv;
        }
    return sqrt(v / sq);
}

static cJSON *results_method(cJSON *root, int index)
{
    cJSON *scene = cJSON_GetArrayItem(cJSON_GetObjectItem(root, "scenes"), 0);
    return cJSON_GetArrayItem(cJSON_GetObjectItem(scene, "methods"), index);
}

static void check_method(const lucent_compare_scene_result *sr, int k, const char *dir, const float *mask, double noise,
                         cJSON *results)
{
    const lucent_compare_method *m = &sr->report.methods[k];
    char path[700], stem[64];
    snprintf(stem, sizeof stem, "%s", m->name);
    for (char *p = stem; *p; p++) *p = *p == ':' ? '-' : *p;
    snprintf(path, sizeof path, "%s/test-sphere/%s.exr", dir, stem);
    lucent_image *img = NULL;
    CHECK_OK(lucent_image_load(path, &img));
    if (!img) return;
    const lucent_image *ref = sr->reference->image;
    double e = hand_rel_rms(img, ref, mask, -1);
    CHECK_NEAR(m->rel_rms, e, 1e-9 * e);
    for (int c = 0; c < 3; c++) {
        double ec = hand_rel_rms(img, ref, mask, c);
        CHECK_NEAR(m->rel_rms_rgb[c], ec, 1e-9 * ec);
    }
    cJSON *j = results_method(results, k);
    double want_net = sqrt(fmax(e * e - noise * noise, 0));
    CHECK(j && !strcmp(cJSON_GetObjectItem(j, "method")->valuestring, m->name));
    CHECK(j && fabs(cJSON_GetObjectItem(j, "rel_rms_net")->valuedouble - want_net) <= 1e-9 * (want_net + 1e-12));
    CHECK(j && fabs(cJSON_GetObjectItem(j, "rel_rms")->valuedouble - e) <= 1e-9 * e);
    CHECK(m->frame_ms > 0 && sr->times[k].pass_count > 0);
    snprintf(path, sizeof path, "%s/test-sphere/%s-error.png", dir, stem);
    lucent_image *heat = NULL;
    CHECK_OK(lucent_image_load(path, &heat));
    lucent_image_destroy(heat);
    lucent_image_destroy(img);
}

TEST(compare_run_errors_are_the_relative_rms_over_the_mask)
{
    char scene[600], dir[600];
    snprintf(scene, sizeof scene, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    snprintf(dir, sizeof dir, "%s", test_path("cmp"));
    const char *scenes[] = {scene}, *methods[] = {"lambert", "ssss:preint"};
    lucent_compare_result r;
    seen s = {.result = &r, .done_index = -1};
    CHECK_OK(lucent_compare_run(&(lucent_compare_desc){.scenes = scenes,
                                                       .scene_count = 1,
                                                       .methods = methods,
                                                       .method_count = 2,
                                                       .spp = LUCENT_COMPARE_MIN_SPP, /* noise known */
                                                       .frames = 1,
                                                       .out = dir,
                                                       .on_event = on_event,
                                                       .user = &s},
                                &r));
    CHECK(r.scene_count == 1 && s.done == 1 && s.done_index == 0 && s.methods_when_done == 2 && s.html == 1);
    /* reference.exr/.png, its -variance.exr, -coverage.exr and reference.json, per method
     * .exr/.png/-error.png/-worst.png, errors.svg, the colour bar, 4 reports: 5 + 8 + 1 + 1 + 4. */
    CHECK_MSG(s.wrote == 19, "%d files told", s.wrote);
    if (r.scene_count != 1) return;
    const lucent_compare_scene_result *sr = &r.scenes[0];
    const lucent_image *cov = sr->reference->coverage, *ref = sr->reference->image;
    CHECK(sr->report.width == 48 && sr->report.height == 40 && sr->report.reference_spp == LUCENT_COMPARE_MIN_SPP);
    float *mask = malloc((size_t)cov->width * cov->height * sizeof *mask);
    uint64_t n = hand_mask(cov, mask);
    CHECK(n > 0 && sr->object_pixels == n);
    for (size_t i = 0; i < (size_t)cov->width * cov->height; i++) CHECK(sr->mask[i] == mask[i]);
    double noise = hand_noise(ref, sr->reference->variance, mask);
    CHECK_NEAR(sr->report.reference_noise, noise, 1e-9 * noise);
    char path[700];
    snprintf(path, sizeof path, "%s/results.json", dir);
    char *text = NULL;
    size_t size;
    CHECK_OK(lucent_read_file(path, &text, &size));
    cJSON *root = text ? cJSON_Parse(text) : NULL;
    cJSON *sc = root ? cJSON_GetArrayItem(cJSON_GetObjectItem(root, "scenes"), 0) : NULL;
    CHECK(sc && cJSON_GetObjectItem(sc, "object_pixels")->valuedouble == (double)n);
    for (int k = 0; root && k < 2; k++) check_method(sr, k, dir, mask, noise, root);
    lucent_image *written = NULL; /* the reference file is the reference measured against */
    snprintf(path, sizeof path, "%s/test-sphere/reference.exr", dir);
    CHECK_OK(lucent_image_load(path, &written));
    CHECK(written && !memcmp(written->data, ref->data, (size_t)ref->width * ref->height * 3 * sizeof(float)));
    lucent_image_destroy(written);
    cJSON_Delete(root);
    free(text);
    free(mask);
    lucent_compare_result_free(&r);
    CHECK(r.scenes == NULL && r.scene_count == 0);
}

TEST(compare_run_without_out_measures_and_writes_nothing)
{
    char scene[600];
    snprintf(scene, sizeof scene, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    const char *scenes[] = {scene}, *methods[] = {"lambert"}, *sets[] = {"render.width=24", "render.height=20"};
    lucent_compare_result r;
    seen s = {.result = &r};
    CHECK_OK(lucent_compare_run(&(lucent_compare_desc){.scenes = scenes,
                                                       .scene_count = 1,
                                                       .methods = methods,
                                                       .method_count = 1,
                                                       .overrides = sets,
                                                       .override_count = 2,
                                                       .spp = 2,
                                                       .frames = 1,
                                                       .scale = 2,
                                                       .on_event = on_event,
                                                       .user = &s},
                                &r));
    CHECK(s.done == 1 && s.wrote == 0);
    /* the overrides, then the scale on top of them */
    CHECK(r.scene_count == 1 && r.scenes[0].report.width == 48 && r.scenes[0].report.height == 40);
    CHECK(r.scene_count == 1 && strstr(r.scenes[0].report.scene_json, "48"));
    lucent_compare_result_free(&r);
}

TEST(compare_run_fails_on_a_bad_scene_and_keeps_nothing)
{
    char scene[600];
    snprintf(scene, sizeof scene, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    const char *scenes[] = {scene}, *methods[] = {"lambert"}, *sets[] = {"render.taps=4"};
    lucent_compare_result r;
    CHECK_ERR(lucent_compare_run(&(lucent_compare_desc){.scenes = scenes,
                                                        .scene_count = 1,
                                                        .methods = methods,
                                                        .method_count = 1,
                                                        .overrides = sets,
                                                        .override_count = 1,
                                                        .spp = 1},
                                 &r),
              LUCENT_ERR_PARSE, "sphere.json", "render.taps");
    CHECK(r.scenes == NULL && r.scene_count == 0);
}

/* The regions of the skin sphere (radius 10 mm at the origin, one directional light and an environment)
 * against the analytic sphere: per masked pixel the camera ray meets the sphere |x| = 10 at a point
 * whose normal is x / 10; its angle to the light classes it lit (< 75 degrees), terminator (75-105) or
 * attached shadow (> 105); no cast shadow on one convex body; all of it convex (radius 10 <= 20 mm).
 * The mesh is an icosphere (subdivisions 3: faces about 6 degrees across), so pixels within a facet of a
 * class boundary may differ: at least 90% agree. */
TEST(compare_regions_of_a_sphere_match_the_analytic_sphere)
{
    char scene[600];
    snprintf(scene, sizeof scene, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    const char *scenes[] = {scene}, *methods[] = {"lambert", "ssss:preint"};
    const char *sets[] = {"render.width=96", "render.height=80"};
    lucent_compare_result r;
    CHECK_OK(lucent_compare_run(&(lucent_compare_desc){.scenes = scenes,
                                                       .scene_count = 1,
                                                       .methods = methods,
                                                       .method_count = 2,
                                                       .overrides = sets,
                                                       .override_count = 2,
                                                       .spp = 8,
                                                       .frames = 1},
                                &r));
    if (r.scene_count != 1) return;
    const lucent_compare_scene_result *sr = &r.scenes[0];
    const lucent_compare_scene *sc = &sr->report;
    CHECK(sc->region_count == LUCENT_COMPARE_REGION_COUNT && sc->regions);
    lucent_scene *sn;
    CHECK_OK(lucent_scene_load(scene, &(lucent_scene_load_desc){.overrides = sets, .override_count = 2}, &sn));
    double l[3] = {-0.6, 0.3, 0.7}, ln = sqrt(0.36 + 0.09 + 0.49), cos75 = cos(75 * M_PI / 180);
    uint64_t want[3] = {0}, masked = 0;
    for (int y = 0; y < 80; y++)
        for (int x = 0; x < 96; x++) {
            if (sr->mask[y * 96 + x] != 1) continue;
            double o[3], d[3];
            lucent_camera_ray(&sn->camera, 96, 80, x + 0.5, y + 0.5, o, d);
            double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2], c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - 100;
            double disc = b * b - c;
            if (disc < 0) continue; /* the tessellation covers a little less than the sphere */
            double t = -b - sqrt(disc), cosl = 0;
            for (int k = 0; k < 3; k++) cosl += (o[k] + t * d[k]) / 10 * l[k] / ln;
            want[cosl > cos75 ? 0 : cosl >= -cos75 ? 1 : 2]++;
            masked++;
        }
    CHECK_MSG(masked > 1000, "%llu pixels", (unsigned long long)masked);
    for (int k = 0; k < 3; k++) {
        double got = (double)sc->regions[k].pixels, w = (double)want[k];
        CHECK_MSG(fabs(got - w) <= 0.1 * masked / 3 + 0.1 * w, "%s: %g pixels, the analytic sphere %g",
                  sc->regions[k].name, got, w);
    }
    CHECK(sc->regions[LUCENT_COMPARE_REGION_CAST_SHADOW].pixels == 0);
    CHECK(sc->regions[LUCENT_COMPARE_REGION_CONVEX].pixels == sr->object_pixels);
    uint64_t lit_term = sc->regions[0].pixels + sc->regions[1].pixels + sc->regions[2].pixels;
    CHECK(lit_term == sr->object_pixels); /* one directional light: every pixel in one of the three */
    /* the shares of the reference's squares add up to 1 over the partition, and so do a method's errors */
    double energy = 0, share = 0;
    for (int k = 0; k < 3; k++)
        energy += sc->regions[k].pixels ? sc->regions[k].energy : 0,
            share += sc->regions[k].pixels ? sc->regions[k].error_share[1] : 0;
    CHECK_NEAR(energy, 1, 1e-9);
    CHECK_NEAR(share, 1, 1e-9);
    CHECK(sc->methods[0].has_flip && sc->methods[0].flip > 0 && sc->methods[0].flip < 1);
    CHECK(sc->pair_se && sc->pair_se[1] > 0 && sc->pair_se[1] == sc->pair_se[2]);
    CHECK(sc->provenance && !strcmp(sc->provenance->version, LUCENT_VERSION_STRING) && sc->provenance->cores > 0);
    lucent_scene_destroy(sn);
    lucent_compare_result_free(&r);
}

/* A reference is written with what made it and reused by a later run (--reference): the same image,
 * variance and samples, and the same errors; with the reference folder as the output folder too; a
 * scene that differs in a field the tracer reads is refused, naming the field, while one that differs
 * only in a method's setting (render.taps) or the budget is not. Each light alone: the reference and
 * the methods with the other light at intensity 0 (the environment alone is a dim image). */
TEST(compare_reuses_a_reference_only_for_the_same_scene_and_measures_each_light)
{
    char scene[600], dir[600], dir2[600];
    snprintf(scene, sizeof scene, "%s/tests/fixtures/scenes/sphere.json", LUCENT_SOURCE_DIR);
    snprintf(dir, sizeof dir, "%s", test_path("cmp-ref"));
    snprintf(dir2, sizeof dir2, "%s", test_path("cmp-reuse"));
    const char *scenes[] = {scene}, *methods[] = {"lambert"}, *taps[] = {"render.taps=17"},
               *other[] = {"objects[0].material=skin2"};
    lucent_compare_result a, b;
    lucent_compare_desc d = {.scenes = scenes,
                             .scene_count = 1,
                             .methods = methods,
                             .method_count = 1,
                             .spp = 8,
                             .frames = 1,
                             .reference_runs = 2,
                             .out = dir};
    CHECK_OK(lucent_compare_run(&d, &a));
    d.reference = dir, d.out = dir2, d.overrides = taps, d.override_count = 1, d.spp = 1, d.per_light = true;
    CHECK_OK(lucent_compare_run(&d, &b));
    if (a.scene_count == 1 && b.scene_count == 1) {
        const lucent_trace_result *ra = a.scenes[0].reference, *rb = b.scenes[0].reference;
        size_t n = (size_t)ra->image->width * ra->image->height * 3;
        CHECK(rb->spp == ra->spp && rb->spp == 8 && b.scenes[0].report.reference_runs == 2);
        CHECK(!memcmp(ra->image->data, rb->image->data, n * sizeof(float)));
        CHECK(!memcmp(ra->variance->data, rb->variance->data, n * sizeof(float)));
        CHECK(a.scenes[0].report.methods[0].rel_rms == b.scenes[0].report.methods[0].rel_rms);
        CHECK(b.scenes[0].report.reference_from && strstr(b.scenes[0].report.reference_from, "cmp-ref"));
        /* each light alone: two lights, the sun's image carries most of the light */
        const lucent_compare_scene *sc = &b.scenes[0].report;
        CHECK(sc->light_count == 2 && sc->lights && strstr(sc->lights[0].name, "directional"));
        CHECK(sc->light_count == 2 && isfinite(sc->lights[0].rel_rms[0]) && isfinite(sc->lights[1].rel_rms[0]));
        CHECK(sc->light_count == 2 &&
              sc->lights[0].regions[LUCENT_COMPARE_REGION_LIT].pixels == sc->regions[LUCENT_COMPARE_REGION_LIT].pixels);
    }
    lucent_compare_result_free(&b);
    d.out = dir, d.per_light = false; /* the reference's own folder: read, not rewritten */
    CHECK_OK(lucent_compare_run(&d, &b));
    lucent_compare_result_free(&b);
    d.overrides = other;
    CHECK_ERR(lucent_compare_run(&d, &b), LUCENT_ERR_INVALID_ARGUMENT, "reference.json", "objects[0].material",
              "\"skin1\"", "\"skin2\"");
    d.overrides = NULL, d.override_count = 0, d.reference = test_path("none");
    CHECK_ERR(lucent_compare_run(&d, &b), LUCENT_ERR_IO, "none/test-sphere/reference.json");
    lucent_compare_result_free(&a);
}

TEST_MAIN(TEST_ENTRY(compare_run_errors_are_the_relative_rms_over_the_mask),
          TEST_ENTRY(compare_run_without_out_measures_and_writes_nothing),
          TEST_ENTRY(compare_run_fails_on_a_bad_scene_and_keeps_nothing),
          TEST_ENTRY(compare_regions_of_a_sphere_match_the_analytic_sphere),
          TEST_ENTRY(compare_reuses_a_reference_only_for_the_same_scene_and_measures_each_light))
