/* Tests of the path tracer (src/trace). Expected values come from physics or from the independent
 * light-traced sphere simulation of the CDRF module, never from the tracer itself:
 *   - furnace: a non-absorbing medium in a uniform radiance field L is in equilibrium, so every
 *     object pixel sees L (Kirchhoff; for an index-matched or smooth, energy-conserving boundary),
 *     and with absorption or a lossy rough boundary never more;
 *   - agreement: the equator of a Skin1 sphere lit from the side against lucent_cdrf_sphere_run;
 *   - determinism and 1/sqrt(spp) convergence; the refusal rule; bounded paths on open meshes.
 * Under AddressSanitizer the sample counts shrink (each check keeps enough samples to mean something). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/lucent.h"
#include "test.h"
#include "trace/field.h"
#include "trace/film.h"
#include "trace/internal.h"

#if defined(__SANITIZE_ADDRESS__)
#define SLOW 4 /* sanitizer builds run about ten times slower: a quarter of the work */
#else
#define SLOW 1
#endif

static lucent_scene *scene_from(const char *json)
{
    lucent_scene *sc = NULL;
    lucent_status s = lucent_scene_parse(json, "test.json", NULL, NULL, &sc);
    if (s != LUCENT_OK) fprintf(stderr, "  scene: %s\n", lucent_last_error());
    return sc;
}

/* A sphere of radius 1 mm at the origin seen from +z, in material MAT (JSON), with LIGHTS. */
static lucent_scene *sphere_scene(const char *mat, const char *lights, int size, const char *extra)
{
    char json[4096];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 4], \"target\": [0, 0, 0], \"fov_y\": 35},"
             " \"lights\": [%s],"
             " \"objects\": [{\"name\": \"ball\", \"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1,"
             " \"subdivisions\": 4}, \"material\": %s %s}],"
             " \"render\": {\"width\": %d, \"height\": %d}}",
             lights, mat, extra ? extra : "", size, size);
    return scene_from(json);
}

static lucent_status render(lucent_scene *sc, const lucent_tracer_desc *td, int spp, uint64_t seed, lucent_pool *pool,
                            lucent_trace_result *r)
{
    lucent_tracer *tr = NULL;
    lucent_status s = lucent_tracer_create(sc, td, &tr);
    if (s == LUCENT_OK) s = lucent_tracer_render(tr, &(lucent_trace_desc){.spp = spp, .seed = seed, .pool = pool}, r);
    lucent_tracer_destroy(tr);
    return s;
}

/* ---- furnace ---- */

typedef struct furnace_stats {
    double mean_z, chi2_dof, max_z, pooled_z;
    int pixels;
} furnace_stats;

/* z-scores of every fully covered pixel's channels against L, from the tracer's standard errors. */
static furnace_stats furnace_check(const lucent_trace_result *r, double L)
{
    furnace_stats f = {0};
    double sum = 0, var = 0;
    int n = 0;
    for (int p = 0; p < r->image->width * r->image->height; p++) {
        if (r->coverage->data[p] < 1.0f) continue;
        for (int c = 0; c < 3; c++) {
            double m = r->image->data[3 * p + c], v = r->variance->data[3 * p + c];
            double z = v > 0 ? (m - L) / sqrt(v) : (m == L ? 0 : 1e9);
            f.mean_z += z, f.chi2_dof += z * z, f.max_z = fmax(f.max_z, z);
            sum += m, var += v, n++;
        }
    }
    f.pixels = n / 3;
    if (n) f.mean_z /= n, f.chi2_dof /= n, f.pooled_z = (sum / n - L) / (sqrt(var) / n);
    return f;
}

static void furnace_case_desc(const char *mat, const char *extra, const lucent_tracer_desc *td, int spp,
                              furnace_stats *f)
{
    lucent_scene *sc = sphere_scene(mat, "{\"type\": \"environment\", \"intensity\": 0.7}", 24, extra);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result r = {0};
    CHECK(sc != NULL);
    if (sc) CHECK_OK(render(sc, td, spp, 3, pool, &r));
    if (r.image) *f = furnace_check(&r, 0.7);
    CHECK(r.nonfinite == 0);
    lucent_trace_result_free(&r);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

static void furnace_case(const char *mat, const char *extra, furnace_stats *f)
{
    furnace_case_desc(mat, extra, NULL, 256 / SLOW, f);
}

/* The equilibrium L holds: the pooled mean over the object within 4 standard errors of L, and the
 * pixels' z-scores spread as a unit normal (chi2 per degree of freedom between 0.7 and 1.5). */
static void check_equilibrium(const char *label, const furnace_stats *f)
{
    printf("  %s: %d pixels, mean z %.3f, chi2/dof %.3f, pooled z %.2f\n", label, f->pixels, f->mean_z, f->chi2_dof,
           f->pooled_z);
    CHECK(f->pixels > 200);
    CHECK_MSG(fabs(f->pooled_z) < 4, "%s: pooled z %.2f: the mean over the object is not L", label, f->pooled_z);
    CHECK_MSG(f->chi2_dof > 0.7 && f->chi2_dof < 1.5, "%s: chi2/dof %.3f", label, f->chi2_dof);
}

/* Physics: no absorption, index matched, a uniform environment: radiance is L everywhere. The
 * medium is chromatic in sigma_s and g, so the hero-channel weights are exercised. */
TEST(furnace_index_matched_non_absorbing)
{
    furnace_stats f = {0};
    furnace_case("{\"units\": \"mm^-1\", \"sigma_a\": 0, \"sigma_s\": [1, 3, 8], \"g\": [0, 0.4, 0.8], \"eta\": 1}",
                 NULL, &f);
    check_equilibrium("index matched", &f);
}

/* Adaptive sampling keeps the estimate unbiased: pixels get samples by the relative variance a
 * separate pilot measures, so the equilibrium L still holds, pixel by pixel. */
TEST(furnace_adaptive)
{
    furnace_stats f = {0};
    furnace_case_desc(
        "{\"units\": \"mm^-1\", \"sigma_a\": 0, \"sigma_s\": [1, 3, 8], \"g\": [0, 0.4, 0.8], \"eta\": 1}", NULL,
        &(lucent_tracer_desc){.adaptive = true}, 64 / SLOW, &f);
    check_equilibrium("adaptive, index matched", &f);
}

/* Physics: a smooth dielectric (Fresnel, total internal reflection) conserves energy, so the same
 * equilibrium holds for eta 1.3 (radiance eta^2 L inside, L outside). */
TEST(furnace_smooth_dielectric_non_absorbing)
{
    furnace_stats f = {0};
    furnace_case("{\"units\": \"mm^-1\", \"sigma_a\": 0, \"sigma_s\": [1, 2, 4], \"g\": 0.3, \"eta\": 1.3}",
                 ", \"roughness\": 0", &f);
    check_equilibrium("smooth eta 1.3", &f);
}

/* Physics: absorption (or the energy a single-scattering microfacet boundary loses) only removes
 * light: no pixel above L beyond noise, and the object's mean below L. */
TEST(furnace_absorbing_or_rough_never_more)
{
    furnace_stats f = {0};
    furnace_case("{\"units\": \"mm^-1\", \"sigma_a\": [0.05, 0.2, 1], \"sigma_s\": [1, 2, 4], \"g\": 0, \"eta\": 1}",
                 NULL, &f);
    printf("  absorbing, matched: max z %.2f, pooled z %.1f\n", f.max_z, f.pooled_z);
    CHECK(f.max_z < 5.0 && f.pooled_z < -5.0);
    furnace_case("{\"units\": \"mm^-1\", \"sigma_a\": 0, \"sigma_s\": [1, 2, 4], \"g\": 0, \"eta\": 1.3}",
                 ", \"roughness\": 0.3", &f);
    printf("  rough eta 1.3, non-absorbing: max z %.2f, pooled z %.1f\n", f.max_z, f.pooled_z);
    CHECK(f.max_z < 5.0 && f.pooled_z < 0);
}

/* ---- agreement with the independent light-traced sphere ---- */

/* The equator of a Skin1 sphere of radius R (rough boundary, alpha 0.3, eta 1.3) lit by a unit
 * directional light from +x, seen from +z: the tracer's pixels (a camera 1000 R away, one row of
 * pixels 1% of R high, so the view is parallel to within 1e-3 rad) against lucent_cdrf_sphere_run.
 * Like quantities: the simulation averages over bands of theta and a cone of view directions within
 * CONE of +z, weighting each band by sin(theta) C(theta), C the cone's projected solid angle; the
 * tracer's pixels of a band are weighted by sin(theta) (their share of the band's projected area
 * is sin(theta) d theta already), which matches to first order in the cone. The second order is
 * not negligible on the dark side: with a cone of 0.2 rad the simulation's green at 120-140 degrees
 * is 2-3% above its value with 0.1 rad (25.6M and 102M photons), which the tracer matches within
 * 0.3%; so the cone here is 0.1 rad (its effect about a quarter of that, below the standard errors).
 * Only bands between 20 and 160 degrees are compared (at the limbs the pixels are few and the view
 * grazing). The simulation scores no light reflected at first entry, so the tracer runs
 * subsurface_only. */
enum { AGREE_BINS = 18, AGREE_WIDTH = 201 };
#define AGREE_CONE 0.1

typedef struct agree_bin {
    double mean[3], se[3];
} agree_bin;

static void equator_bins(const lucent_trace_result *r, double R, agree_bin *bins)
{
    for (int b = 0; b < AGREE_BINS; b++) {
        double ta = M_PI * b / AGREE_BINS, tb = M_PI * (b + 1) / AGREE_BINS, sw = 0, s[3] = {0}, v[3] = {0};
        for (int x = 0; x < AGREE_WIDTH; x++) {
            double X = ((x + 0.5) / AGREE_WIDTH * 2.1 - 1.05) * R;
            if (fabs(X) >= R) continue;
            double th = acos(X / R), w = sin(th);
            if (th < ta || th >= tb) continue;
            sw += w;
            for (int c = 0; c < 3; c++) {
                s[c] += w * lucent_image_get(r->image, x, 0, c);
                v[c] += w * w * lucent_image_get(r->variance, x, 0, c);
            }
        }
        for (int c = 0; c < 3; c++)
            bins[b].mean[c] = sw > 0 ? s[c] / sw : 0, bins[b].se[c] = sw > 0 ? sqrt(v[c]) / sw : 0;
    }
}

static lucent_scene *equator_scene(double R)
{
    char json[1024];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, %g], \"target\": [0, 0, 0], \"fov_y\": 1},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [-1, 0, 0], \"intensity\": 1}],"
             " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": %g, \"subdivisions\": 6},"
             " \"material\": \"skin1\", \"roughness\": 0.3}],"
             " \"render\": {\"width\": %d, \"height\": 1}}",
             10 * R, R, AGREE_WIDTH);
    lucent_scene *sc = scene_from(json);
    if (!sc) return NULL;
    /* 1000 R away with a field of view of one row 2.1 R / width high: beyond what files allow */
    sc->camera.position[2] = 1000 * R;
    sc->camera.fov_y = 2 * atan(0.5 * 2.1 / AGREE_WIDTH / 1000) * 180 / M_PI;
    return sc;
}

typedef struct agreement {
    double chi2, zmax, pooled, pooled_se;
    int n;
} agreement;

/* z-scores of the tracer's bands against the simulation's, 20 to 160 degrees. */
static agreement compare_bands(const agree_bin *bins, const lucent_cdrf_sphere_result *m)
{
    agreement a = {0};
    double num = 0, den = 0;
    for (int b = 2; b < AGREE_BINS - 2; b++)
        for (int c = 0; c < 3; c++) {
            double se2 = bins[b].se[c] * bins[b].se[c] + m->radiance_se[c][b] * m->radiance_se[c][b];
            double z = (bins[b].mean[c] - m->radiance[c][b]) / sqrt(se2);
            a.chi2 += z * z, a.zmax = fmax(a.zmax, fabs(z)), a.n++;
            /* pooled relative difference, weighted by inverse variance */
            double rel = bins[b].mean[c] / m->radiance[c][b] - 1, rse2 = se2 / (m->radiance[c][b] * m->radiance[c][b]);
            num += rel / rse2, den += 1 / rse2;
        }
    a.pooled = num / den, a.pooled_se = 1 / sqrt(den);
    return a;
}

static void check_agreement(const char *what, const lucent_trace_result *r, double R,
                            const lucent_cdrf_sphere_result *m)
{
    agree_bin bins[AGREE_BINS];
    if (!r->image) return;
    equator_bins(r, R, bins);
    agreement a = compare_bands(bins, m);
    printf("  %s: %d bands x channels, chi2 %.1f (p = 0.001 at 72.6 for 42), max |z| %.2f, pooled relative "
           "difference %+.4f +- %.4f\n",
           what, a.n, a.chi2, a.zmax, a.pooled, a.pooled_se);
    CHECK(a.n == 42);
    CHECK_MSG(a.chi2 < 72.6, "%s: chi2 %.1f over %d: the tracer and the simulation disagree", what, a.chi2, a.n);
    CHECK_MSG(fabs(a.pooled) < 3.5 * a.pooled_se, "%s: a common scale error of %+.4f (+- %.4f)", what, a.pooled,
              a.pooled_se);
}

TEST(agrees_with_the_light_traced_sphere)
{
    const double R = 2;
    lucent_scene *sc = equator_scene(R);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result r = {0}, ra = {0};
    lucent_cdrf_sphere_result m;
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(render(sc, &(lucent_tracer_desc){.subsurface_only = true}, 1200 / SLOW, 5, pool, &r));
    CHECK_OK(render(sc, &(lucent_tracer_desc){.subsurface_only = true, .adaptive = true}, 240 / SLOW, 6, pool, &ra));
    CHECK_OK(lucent_cdrf_sphere_run(&(lucent_cdrf_sphere_desc){.material = &sc->objects[0].material,
                                                               .radius = R,
                                                               .roughness = 0.3,
                                                               .photons = 4000000 / SLOW,
                                                               .bins = AGREE_BINS,
                                                               .cone = AGREE_CONE,
                                                               .seed = 9,
                                                               .pool = pool},
                                    &m));
    check_agreement("uniform", &r, R, &m);
    check_agreement("adaptive", &ra, R, &m);
    lucent_trace_result_free(&r), lucent_trace_result_free(&ra);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* ---- determinism and convergence ---- */

static lucent_scene *small_lit_scene(void)
{
    return sphere_scene("\"skin1\"",
                        "{\"type\": \"directional\", \"direction\": [-0.6, -0.3, -0.7], \"intensity\": 2},"
                        " {\"type\": \"environment\", \"intensity\": 0.1}",
                        20, NULL);
}

static bool same_image(const lucent_image *a, const lucent_image *b)
{
    return a && b && a->width == b->width && a->height == b->height && a->channels == b->channels &&
           memcmp(a->data, b->data, lucent_image_value_count(a) * sizeof(float)) == 0;
}

/* The chunks (tiles x sample passes) draw from streams of the seed alone, and each pixel adds its
 * samples in order, so one thread, two threads and two calls of half the samples agree bit for bit. */
TEST(same_seed_same_image_on_one_and_two_threads)
{
    lucent_scene *sc = small_lit_scene();
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result one = {0}, two = {0}, split = {0}, other = {0};
    lucent_tracer *tr = NULL;
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(render(sc, NULL, 8, 21, NULL, &one));
    CHECK_OK(render(sc, NULL, 8, 21, pool, &two));
    CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 5, .seed = 21, .pool = pool}, &split));
    lucent_trace_result_free(&split);
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 3, .pool = pool}, &split));
    CHECK_OK(render(sc, NULL, 8, 22, pool, &other));
    CHECK(same_image(one.image, two.image) && same_image(one.variance, two.variance));
    CHECK(same_image(one.coverage, two.coverage));
    CHECK_MSG(split.spp == 8 && same_image(one.image, split.image), "5 + 3 samples differ from 8");
    CHECK_MSG(!same_image(one.image, other.image), "another seed gives the same image");
    /* adaptive: the allocation is computed between passes from the pilot's sums, the same way */
    lucent_trace_result_free(&one), lucent_trace_result_free(&two);
    const lucent_tracer_desc adaptive = {.adaptive = true};
    CHECK_OK(render(sc, &adaptive, 8, 21, NULL, &one));
    CHECK_OK(render(sc, &adaptive, 8, 21, pool, &two));
    CHECK_MSG(same_image(one.image, two.image) && same_image(one.variance, two.variance) && one.samples == two.samples,
              "adaptive: 1 and 2 threads differ");
    CHECK_MSG(one.samples > 8 * 20 * 20 && one.spp == 8, "adaptive: %llu samples in 8 passes",
              (unsigned long long)one.samples);
    lucent_tracer_destroy(tr);
    lucent_trace_result_free(&one), lucent_trace_result_free(&two);
    lucent_trace_result_free(&split), lucent_trace_result_free(&other);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* render.interreflection off ends a path where it meets a surface from outside after its first: on one
 * convex sphere no path ever does, so the image is the same bit for bit (the same seed draws the same
 * numbers); beside a second sphere, every sample keeps a subset of its contributions (all >= 0), so no
 * pixel gains, and the light the second sphere sends onto the first is gone: the two images differ. */
TEST(interreflection_off_removes_only_light_between_surfaces)
{
    lucent_pool *pool = lucent_pool_create(2);
    lucent_scene *one = small_lit_scene();
    lucent_trace_result on = {0}, off = {0};
    CHECK_OK(render(one, NULL, 4, 3, pool, &on));
    if (one) one->render.trace.interreflection = false;
    CHECK_OK(render(one, NULL, 4, 3, pool, &off));
    CHECK_MSG(same_image(on.image, off.image), "one convex sphere: the images differ");
    lucent_trace_result_free(&on), lucent_trace_result_free(&off);
    lucent_scene_destroy(one);
    lucent_scene *two =
        scene_from("{\"camera\": {\"position\": [0, 0, 6], \"target\": [0.5, 0, 0], \"fov_y\": 40},"
                   " \"lights\": [{\"type\": \"directional\", \"direction\": [-1, -0.2, -0.4], \"intensity\": 2}],"
                   " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 3},"
                   " \"material\": \"skin1\", \"roughness\": 0.3},"
                   " {\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 3},"
                   " \"transform\": {\"translate\": [2.05, 0, 0]}, \"material\": \"skin1\", \"roughness\": 0.3}],"
                   " \"render\": {\"width\": 24, \"height\": 16}}");
    CHECK(two != NULL);
    if (two) {
        CHECK_OK(render(two, NULL, 4, 3, pool, &on));
        two->render.trace.interreflection = false;
        CHECK_OK(render(two, NULL, 4, 3, pool, &off));
        double sum_on = 0, sum_off = 0;
        int gained = 0;
        for (size_t i = 0; on.image && off.image && i < lucent_image_value_count(on.image); i++) {
            sum_on += on.image->data[i], sum_off += off.image->data[i];
            gained += off.image->data[i] > on.image->data[i] * (1 + 1e-6f) + 1e-12f;
        }
        CHECK_MSG(gained == 0, "%d values gained light without interreflection", gained);
        CHECK_MSG(sum_off < sum_on * 0.999, "two spheres: %.6g without light between them, %.6g with", sum_off, sum_on);
        printf("     two spheres side by side: the image without light between them holds %.4f of the full one\n",
               sum_off / sum_on);
        lucent_trace_result_free(&on), lucent_trace_result_free(&off);
    }
    lucent_scene_destroy(two);
    lucent_pool_destroy(pool);
}

/* ---- distance-bounded flights and next-event roulette at deep vertices ---- */

/* A dense, nearly non-absorbing sphere (16 to 20 mean free paths in radius, albedo 0.997, like marble's
 * scale ratio) with a rough boundary, lit by LIGHTS. */
static lucent_scene *dense_lit(const char *lights, int size)
{
    return sphere_scene("{\"units\": \"mm^-1\", \"sigma_a\": [0.05, 0.08, 0.1], \"sigma_s\": [20, 18, 16], "
                        "\"g\": 0, \"eta\": 1.5}",
                        lights, size, ", \"roughness\": 0.3");
}

/* The dense sphere lit by a sun from the side and a dim environment. */
static lucent_scene *dense_scene(int size)
{
    return dense_lit("{\"type\": \"directional\", \"direction\": [-1, -0.2, -0.3], \"intensity\": 2},"
                     " {\"type\": \"environment\", \"intensity\": 0.1}",
                     size);
}

/* A flight that ends inside a sphere holding no surface cannot have crossed one: skipping its ray
 * query must change no decision, so (with next-event estimation at every vertex) the image is the
 * same bit for bit, with fewer ray queries. */
TEST(distance_bounded_flights_change_nothing)
{
    lucent_scene *sc = dense_scene(16);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result plain = {0}, bounded = {0};
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(render(sc, &(lucent_tracer_desc){.plain_flights = true, .nee_every_vertex = true}, 4, 5, pool, &plain));
    CHECK_OK(render(sc, &(lucent_tracer_desc){.nee_every_vertex = true}, 4, 5, pool, &bounded));
    printf("  per path: plain %.1f ray queries, bounded %.1f ray and %.2f distance queries, %.0f%% of vertices "
           "reached without a ray query\n",
           (double)plain.cost.rays / plain.cost.paths, (double)bounded.cost.rays / bounded.cost.paths,
           (double)bounded.cost.points / bounded.cost.paths,
           100.0 * bounded.cost.free_flights / (bounded.cost.scatters + bounded.cost.bounces));
    CHECK_MSG(same_image(plain.image, bounded.image) && same_image(plain.variance, bounded.variance),
              "distance-bounded flights changed the image");
    CHECK(plain.cost.points == 0 && plain.cost.free_flights == 0);
    CHECK(bounded.cost.free_flights > bounded.cost.scatters / 4 && bounded.cost.rays < plain.cost.rays);
    CHECK(plain.cost.scatters == bounded.cost.scatters && plain.cost.nee == plain.cost.scatters);
    lucent_trace_result_free(&plain), lucent_trace_result_free(&bounded);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* The distance from p to segment ab, and to triangle abc by projection onto its plane (inside: the
 * plane's distance; outside: the nearest of the three edges). An independent formula: the tracer's
 * (embree.c) walks the Voronoi regions of the triangle instead. */
static double segment_distance(v3 p, v3 a, v3 b)
{
    v3 ab = v3_sub(b, a);
    double t = fmin(1.0, fmax(0.0, v3_dot(v3_sub(p, a), ab) / v3_dot(ab, ab)));
    return v3_length(v3_sub(p, v3_madd(a, ab, t)));
}

static double brute_triangle_distance(v3 p, v3 a, v3 b, v3 c)
{
    v3 n = v3_normalize(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    double h = v3_dot(v3_sub(p, a), n);
    v3 q = v3_madd(p, n, -h);
    bool in = v3_dot(v3_cross(v3_sub(b, a), v3_sub(q, a)), n) >= 0 &&
              v3_dot(v3_cross(v3_sub(c, b), v3_sub(q, b)), n) >= 0 &&
              v3_dot(v3_cross(v3_sub(a, c), v3_sub(q, c)), n) >= 0;
    if (in) return fabs(h);
    return fmin(segment_distance(p, a, b), fmin(segment_distance(p, b, c), segment_distance(p, c, a)));
}

static double brute_distance(const lucent_scene *sc, v3 p)
{
    double d = INFINITY;
    for (int o = 0; o < sc->object_count; o++) {
        const lucent_mesh *m = sc->objects[o].mesh;
        for (size_t f = 0; f < m->face_count; f++) {
            const uint32_t *v = m->faces + 3 * f;
            d = fmin(d, brute_triangle_distance(p, v3_load(m->positions + 3 * v[0]), v3_load(m->positions + 3 * v[1]),
                                                v3_load(m->positions + 3 * v[2])));
        }
    }
    return d;
}

/* A torus and a ball that cuts into it, for the distance tests: the scene (*sc) and its ray-tracing
 * geometry (NULL when either failed, which fails the test). */
static tr_geometry *torus_and_ball(lucent_scene **sc)
{
    *sc = scene_from(
        "{\"camera\": {\"position\": [0, 0, 9], \"target\": [0, 0, 0], \"fov_y\": 35}, \"lights\": [{\"type\": "
        "\"environment\", \"intensity\": 1}],"
        " \"objects\": [{\"name\": \"ring\", \"mesh\": {\"primitive\": \"torus\", \"major_radius\": 2, \"radius\": "
        "0.6},"
        " \"material\": \"Marble\"}, {\"name\": \"ball\", \"mesh\": {\"primitive\": \"icosphere\", \"radius\": 0.8,"
        " \"subdivisions\": 3}, \"material\": \"Marble\", \"transform\": {\"translate\": [0.3, 0.2, 0.1]}}],"
        " \"render\": {\"width\": 8, \"height\": 8}}");
    CHECK(*sc != NULL);
    int objects[2] = {0, 1};
    tr_geometry *g = NULL;
    if (*sc) CHECK_OK(tr_geometry_create(*sc, objects, 2, &g));
    return g;
}

/* The distance query (tr_distance_bound) against brute force over every
 * triangle of a torus and a sphere, at random points inside and outside: the distance found equals
 * the brute-force one (never more: the sphere it gives must hold no surface), its nearest point lies
 * at that distance, a search limited to the distance of a known surface point finds the same, and a
 * search limited below the distance finds nothing nearer. The depth lattice's distances come from it. */
TEST(distance_bound_is_the_distance)
{
    lucent_scene *sc;
    tr_geometry *g = torus_and_ball(&sc);
    lucent_rng rng;
    lucent_rng_init(11, 0, &rng);
    double worst = 0, worst_known = 0, worst_point = 0;
    int found_none = 0, more = 0;
    for (int i = 0; g && i < 2000; i++) {
        v3 x = v3_make(6 * lucent_rng_uniform(&rng) - 3, 6 * lucent_rng_uniform(&rng) - 3,
                       2 * lucent_rng_uniform(&rng) - 1);
        double truth = brute_distance(sc, x), rmax = 1.5, want = fmin(truth, rmax);
        v3 s;
        double d = tr_distance_bound(g, x, rmax, &s);
        more += d > want * (1 + 1e-12);
        worst = fmax(worst, fabs(d - want));
        if (truth < rmax) worst_point = fmax(worst_point, fabs(v3_length(v3_sub(x, s)) - d));
        if (truth < rmax) { /* limited to a known surface point: the nearest itself, pushed out a little */
            double known = v3_length(v3_sub(x, s)) * 1.01 + 1e-6;
            worst_known = fmax(worst_known, fabs(tr_distance_bound(g, x, known, NULL) - truth));
            found_none += tr_distance_bound(g, x, 0.5 * truth, NULL) < 0.5 * truth;
        }
    }
    printf("  2000 points: |found - brute force| <= %.1e mm, limited to a known point %.1e mm, nearest point %.1e mm\n",
           worst, worst_known, worst_point);
    CHECK_MSG(more == 0, "%d distances above brute force", more);
    CHECK(worst < 1e-9 && worst_known < 1e-9 && worst_point < 1e-9);
    CHECK_MSG(found_none == 0, "%d searches found a surface nearer than the nearest", found_none);
    tr_geometry_destroy(g);
    lucent_scene_destroy(sc);
}

/* The depth lattice (depth.c) against brute force on the same torus and ball: the distance to the
 * nearest surface is 1-Lipschitz, so its bound at a point may never exceed the distance there (the
 * safe sphere must hold no surface), and, with the nearest lattice vertex at most h sqrt(3) / 2
 * away, it lies within h sqrt(3) of the distance (of the cap, within h sqrt(3) / 2) over the
 * bounds the lattice was made for. Points beyond every cell get 0. */
TEST(depth_lattice_bounds_the_distance)
{
    lucent_scene *sc;
    tr_geometry *g = torus_and_ball(&sc);
    const double lo[3] = {-2.6, -2.6, -0.6}, hi[3] = {2.6, 2.6, 0.6}, h = 0.1, cap = 0.5;
    tr_depth *z = g ? tr_depth_create(lo, hi, h, cap) : NULL;
    CHECK(z != NULL);
    lucent_rng rng;
    lucent_rng_init(12, 0, &rng);
    int above = 0, loose = 0, outside = 0;
    double worst_gap = 0;
    for (int i = 0; z && i < 3000; i++) {
        v3 x = v3_make(6 * lucent_rng_uniform(&rng) - 3, 6 * lucent_rng_uniform(&rng) - 3,
                       2 * lucent_rng_uniform(&rng) - 1);
        double b = tr_depth_bound(z, g, x);
        if (fabs(x.x) > 2.6 + 2 * h || fabs(x.y) > 2.6 + 2 * h || fabs(x.z) > 0.6 + 2 * h) { /* beyond every cell */
            outside += b != 0;
            continue;
        }
        double truth = brute_distance(sc, x), floor = fmin(truth - h * sqrt(3.0), cap - 0.5 * h * sqrt(3.0));
        above += b > truth;
        if (fabs(x.x) > 2.6 || fabs(x.y) > 2.6 || fabs(x.z) > 0.6) continue; /* maybe in no cell */
        loose += b < floor - 1e-6;
        worst_gap = fmax(worst_gap, fmin(truth, cap) - b);
    }
    printf("  3000 points, spacing %.2f, cap %.2f: bound up to %.3f below the distance (allowed %.3f)\n", h, cap,
           worst_gap, h * sqrt(3.0));
    CHECK_MSG(above == 0, "%d bounds above the distance", above);
    CHECK_MSG(loose == 0, "%d bounds looser than the lattice allows", loose);
    CHECK_MSG(outside == 0, "%d points outside the lattice got a bound", outside);
    /* a spacing far too fine for memory grows (no overflow of the vertex count) and still bounds
     * from below; bounds that are not finite make no lattice */
    tr_depth *fine = g ? tr_depth_create(lo, hi, 1e-9, cap) : NULL;
    int fine_above = 0;
    for (int i = 0; fine && i < 200; i++) {
        v3 x = v3_make(5 * lucent_rng_uniform(&rng) - 2.5, 5 * lucent_rng_uniform(&rng) - 2.5,
                       lucent_rng_uniform(&rng) - 0.5);
        fine_above += tr_depth_bound(fine, g, x) > brute_distance(sc, x);
    }
    CHECK(fine != NULL && fine_above == 0);
    const double bad[3] = {NAN, 0, 0};
    CHECK(tr_depth_create(bad, hi, h, cap) == NULL);
    tr_depth_destroy(fine);
    tr_depth_destroy(z);
    tr_geometry_destroy(g);
    lucent_scene_destroy(sc);
}

/* A direction uniform over the sphere (Archimedes: z uniform in [-1, 1]). */
static v3 uniform_direction(lucent_rng *rng)
{
    double z = 1.0 - 2.0 * lucent_rng_uniform(rng), phi = 2.0 * M_PI * lucent_rng_uniform(rng), r = sqrt(1.0 - z * z);
    return v3_make(r * cos(phi), r * sin(phi), z);
}

/* The first surface of sc along x + t w, t > 0, over every triangle (Moller and Trumbore 1997): an
 * independent intersection, not Embree's. */
static double brute_ray(const lucent_scene *sc, v3 x, v3 w)
{
    double best = INFINITY;
    for (int o = 0; o < sc->object_count; o++) {
        const lucent_mesh *m = sc->objects[o].mesh;
        for (size_t f = 0; f < m->face_count; f++) {
            const uint32_t *v = m->faces + 3 * f;
            v3 a = v3_load(m->positions + 3 * v[0]), e1 = v3_sub(v3_load(m->positions + 3 * v[1]), a),
               e2 = v3_sub(v3_load(m->positions + 3 * v[2]), a), pv = v3_cross(w, e2);
            double det = v3_dot(e1, pv);
            if (fabs(det) < 1e-300) continue;
            v3 tv = v3_sub(x, a), qv = v3_cross(tv, e1);
            double u = v3_dot(tv, pv) / det, vv = v3_dot(w, qv) / det, t = v3_dot(e2, qv) / det;
            if (u >= 0 && vv >= 0 && u + vv <= 1 && t > 0) best = fmin(best, t);
        }
    }
    return best;
}

/* The lattice's free run (sphere tracing through the known vertices, depth.c), which ends the exit
 * roulette's connections before their ray (nee.c), against brute-force rays on the torus and ball:
 * before any vertex is known it goes nowhere (it fills none); once every vertex is known it never
 * passes the first surface, and where it stops short of its goal with steps too small, that point
 * lies within the lattice's bound of a surface (h sqrt(3) plus the smallest step, 0.05 h). */
TEST(free_run_stops_before_the_first_surface)
{
    lucent_scene *sc;
    tr_geometry *g = torus_and_ball(&sc);
    const double lo[3] = {-2.6, -2.6, -0.6}, hi[3] = {2.6, 2.6, 0.6}, h = 0.1, cap = 0.5;
    tr_depth *z = g ? tr_depth_create(lo, hi, h, cap) : NULL;
    CHECK(z != NULL);
    lucent_rng rng;
    lucent_rng_init(13, 0, &rng);
    int moved_unknown = 0, past = 0, far = 0, stalled = 0, capped = 0, left = 0;
    double longest = 0, reach = h * sqrt(3.0) + 0.05 * h;
    for (int i = 0; z && i < 200; i++)
        moved_unknown += tr_depth_free_run(z, v3_make(0, 2, 0), uniform_direction(&rng), 0.0, INFINITY, 0.0) != 0.0;
    for (double x = lo[0]; z && x <= hi[0] + h; x += 0.5 * h) /* every vertex known */
        for (double y = lo[1]; y <= hi[1] + h; y += 0.5 * h)
            for (double zz = lo[2]; zz <= hi[2] + h; zz += 0.5 * h) tr_depth_bound(z, g, v3_make(x, y, zz));
    for (int i = 0; z && i < 1500; i++) {
        v3 x = v3_make(5 * lucent_rng_uniform(&rng) - 2.5, 5 * lucent_rng_uniform(&rng) - 2.5,
                       lucent_rng_uniform(&rng) - 0.5);
        v3 w = uniform_direction(&rng);
        double s = brute_ray(sc, x, w), t = tr_depth_free_run(z, x, w, 0.0, INFINITY, 0.0);
        past += t > s;
        longest = fmax(longest, t);
        if (tr_depth_free_run(z, x, w, t, INFINITY, 0.0) > t) { /* stopped by the count of steps */
            capped++;
            continue;
        }
        v3 end = v3_madd(x, w, t);
        if (fabs(end.x) > 2.6 || fabs(end.y) > 2.6 || fabs(end.z) > 0.6) { /* out of the lattice: no bound */
            left++;
            continue;
        }
        stalled++;
        far += brute_distance(sc, end) > reach;
    }
    printf("  1500 rays: %d stopped near a surface, %d out of the lattice, %d by the count of steps, longest run "
           "%.2f mm; %d past the first surface\n",
           stalled, left, capped, longest, past);
    CHECK_MSG(moved_unknown == 0, "%d runs moved on a lattice with no vertex known", moved_unknown);
    CHECK_MSG(past == 0, "%d runs passed the first surface", past);
    CHECK_MSG(far == 0, "%d runs stopped further than %.3f from any surface", far, reach);
    CHECK(stalled > 750 && longest > 0.5);
    tr_depth_destroy(z);
    tr_geometry_destroy(g);
    lucent_scene_destroy(sc);
}

/* chi2 per degree of freedom and the pooled z of the differences b - a of two independent estimates
 * over the fully covered pixels' channels (from their standard errors); *n the pixel channels. */
static void difference_stats(const lucent_trace_result *a, const lucent_trace_result *b, double *chi2_dof,
                             double *pooled_z, int *n)
{
    double chi2 = 0, diff = 0, var = 0;
    *n = 0;
    for (int p = 0; a->image && b->image && p < a->image->width * a->image->height; p++) {
        if (a->coverage->data[p] < 1.0f || b->coverage->data[p] < 1.0f) continue;
        for (int c = 0; c < 3; c++) {
            double d = (double)b->image->data[3 * p + c] - a->image->data[3 * p + c];
            double v = (double)a->variance->data[3 * p + c] + b->variance->data[3 * p + c];
            if (!(v > 0)) continue;
            chi2 += d * d / v, diff += d, var += v, (*n)++;
        }
    }
    *chi2_dof = *n ? chi2 / *n : 0, *pooled_z = var > 0 ? diff / sqrt(var) : 0;
}

enum { BATCHES = 8 };

/* BATCHES independent renders of spp samples each (seeds seed0, seed0 + 1, ...) with tracer desc td. */
static void render_batches(lucent_scene *sc, const lucent_tracer_desc *td, int spp, uint64_t seed0, lucent_pool *pool,
                           lucent_trace_result batch[BATCHES])
{
    for (int b = 0; b < BATCHES; b++) CHECK_OK(render(sc, td, spp, seed0 + (uint64_t)b, pool, &batch[b]));
}

/* r's sum over the pixels fully covered in every batch of a and of b (a pooled estimate). */
static double batch_sum(const lucent_trace_result *r, const lucent_trace_result *a, const lucent_trace_result *b)
{
    double sum = 0;
    for (int p = 0; r->image && p < r->image->width * r->image->height; p++) {
        bool in = true;
        for (int k = 0; k < BATCHES; k++) in &= a[k].coverage->data[p] >= 1.0f && b[k].coverage->data[p] >= 1.0f;
        for (int c = 0; c < 3 && in; c++) sum += r->image->data[3 * p + c];
    }
    return sum;
}

/* The mean over BATCHES of the batches' pooled sums (batch_sum) and the standard error of that mean
 * from their spread. A photon's connections land in many pixels, so the pixels of a light-path image
 * are correlated and the sum of their variances understates the pooled sum's (the pooled z of light
 * paths against camera paths had an RMS of 3.5 over six seed pairs, 2.1 for camera paths against
 * themselves); the spread of independent batches does not. */
static void pooled_over_batches(const lucent_trace_result *r, const lucent_trace_result *a,
                                const lucent_trace_result *b, double *mean, double *se)
{
    double s1 = 0, s2 = 0;
    for (int k = 0; k < BATCHES; k++) {
        double v = batch_sum(&r[k], a, b);
        s1 += v, s2 += v * v;
    }
    *mean = s1 / BATCHES;
    *se = sqrt(fmax(0.0, s2 / BATCHES - *mean * *mean) / (BATCHES - 1));
}

/* Folds the batches into batch[0]: the mean image and the variance of that mean, the coverage all of
 * them reach, and the summed costs (for the per-pixel chi2 of difference_stats). */
static void merge_batches(lucent_trace_result batch[BATCHES])
{
    lucent_trace_result *m = &batch[0];
    size_t n = m->image ? (size_t)m->image->width * (size_t)m->image->height : 0;
    for (int k = 1; k < BATCHES; k++) {
        for (size_t i = 0; batch[k].image && i < 3 * n; i++)
            m->image->data[i] += batch[k].image->data[i], m->variance->data[i] += batch[k].variance->data[i];
        for (size_t p = 0; batch[k].image && p < n; p++)
            m->coverage->data[p] = fminf(m->coverage->data[p], batch[k].coverage->data[p]);
        m->cost.paths += batch[k].cost.paths, m->cost.scatters += batch[k].cost.scatters;
        m->cost.photons += batch[k].cost.photons, m->cost.nee += batch[k].cost.nee;
        m->cost.entry_ended += batch[k].cost.entry_ended;
    }
    for (size_t i = 0; i < 3 * n; i++) m->image->data[i] /= BATCHES, m->variance->data[i] /= (float)(BATCHES * BATCHES);
}

/* Two estimators' batches compared: b's pooled sum over a's (ratio), its standard error from the
 * batches' spread (se, relative) and z; then, with both merged (merge_batches), the chi2 per degree of
 * freedom of the pixels' differences and the pooled z from the per-pixel variances (z_pixels) over
 * n pixel channels. */
typedef struct batch_comparison {
    double ratio, se, z, chi2, z_pixels;
    int n;
} batch_comparison;

static batch_comparison compare_batches(lucent_trace_result a[BATCHES], lucent_trace_result b[BATCHES])
{
    batch_comparison c;
    double ma, sea, mb, seb;
    pooled_over_batches(a, a, b, &ma, &sea);
    pooled_over_batches(b, a, b, &mb, &seb);
    double se = sqrt(sea * sea + seb * seb);
    c.ratio = mb / ma, c.se = se / ma, c.z = (mb - ma) / se;
    merge_batches(a), merge_batches(b);
    difference_stats(&a[0], &b[0], &c.chi2, &c.z_pixels, &c.n);
    return c;
}

/* Russian roulette on the next-event estimate of deep vertices (made with probability P, weighted by
 * 1 / P) leaves the estimate unbiased: against the plain estimator (every vertex, every flight
 * queried), independent seeds, the pixels' differences are unit normal in their standard errors
 * (chi2 per degree of freedom between 0.7 and 1.5), and the pooled difference of 8 independent
 * batches each is within 4.5 of its standard error (Student's t, 14 degrees of freedom: p = 0.0005
 * two-sided). Over batches, because the dense sphere's path weights are heavy-tailed: the per-pixel
 * variances' pooled z had an RMS of 1.7 over six seed pairs where a unit normal has 1. */
TEST(deep_nee_roulette_is_unbiased)
{
    lucent_scene *sc = dense_scene(32);
    if (sc) sc->render.trace.light_paths = LUCENT_LIGHT_PATHS_OFF; /* the camera paths' roulette (light paths: below) */
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result plain[BATCHES] = {{0}}, rr[BATCHES] = {{0}};
    CHECK(sc != NULL);
    if (!sc) return;
    int spp = 96 / SLOW / BATCHES;
    render_batches(sc, &(lucent_tracer_desc){.plain_flights = true, .nee_every_vertex = true}, spp, 7, pool, plain);
    render_batches(sc, NULL, spp, 1007, pool, rr);
    batch_comparison c = compare_batches(plain, rr);
    printf("  %d pixel channels: chi2/dof %.3f; %d batches each of %d spp: roulette / plain %.4f +- %.4f (z %.2f; "
           "the per-pixel variances give z %.2f); next-event estimates at %.0f%% of volume vertices\n",
           c.n, c.chi2, BATCHES, spp, c.ratio, c.se, c.z, c.z_pixels, 100.0 * rr[0].cost.nee / rr[0].cost.scatters);
    CHECK(c.n > 600);
    CHECK_MSG(c.chi2 > 0.7 && c.chi2 < 1.5, "chi2/dof %.3f", c.chi2);
    CHECK_MSG(fabs(c.z) < 4.5, "pooled z over batches %.2f", c.z);
    CHECK_MSG(rr[0].cost.nee < rr[0].cost.scatters / 2, "the roulette skipped too few deep vertices");
    for (int k = 0; k < BATCHES; k++) lucent_trace_result_free(&plain[k]), lucent_trace_result_free(&rr[k]);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* Renders sc in BATCHES independent batches of total_spp / BATCHES samples per pixel with light paths
 * (auto) and without (off), and checks
 * that the two estimate the same image: chi2 per degree of freedom of the batches' merged means
 * between 0.7 and 1.5, the pooled difference within 4.5 of its standard error from the batches'
 * spread, and photons traced only with light paths. */
static double check_light_paths_agree(lucent_scene *sc, int total_spp, lucent_pool *pool)
{
    lucent_trace_result cams[BATCHES] = {{0}}, lps[BATCHES] = {{0}};
    int spp = total_spp / SLOW / BATCHES > 0 ? total_spp / SLOW / BATCHES : 1;
    sc->render.trace.light_paths = LUCENT_LIGHT_PATHS_OFF;
    render_batches(sc, NULL, spp, 11, pool, cams);
    sc->render.trace.light_paths = LUCENT_LIGHT_PATHS_AUTO;
    render_batches(sc, NULL, spp, 1011, pool, lps);
    batch_comparison c = compare_batches(cams, lps);
    const lucent_trace_result *cam = &cams[0], *lp = &lps[0];
    printf("  %d pixel channels: chi2/dof %.3f; %d batches each of %d spp: light paths / camera paths %.4f +- %.4f "
           "(z %.2f; the per-pixel variances give z %.2f); %.2f light paths and %.1f scatterings per camera path "
           "(camera paths alone: %.1f); %.1f%% of the photons ended at entry\n",
           c.n, c.chi2, BATCHES, spp, c.ratio, c.se, c.z, c.z_pixels, (double)lp->cost.photons / (double)lp->cost.paths,
           (double)lp->cost.scatters / (double)lp->cost.paths, (double)cam->cost.scatters / (double)cam->cost.paths,
           100.0 * (double)lp->cost.entry_ended / (double)(lp->cost.photons ? lp->cost.photons : 1));
    double ended = (double)lp->cost.entry_ended / (double)(lp->cost.photons ? lp->cost.photons : 1);
    CHECK(c.n > 600);
    CHECK_MSG(c.chi2 > 0.7 && c.chi2 < 1.5, "chi2/dof %.3f", c.chi2);
    CHECK_MSG(fabs(c.z) < 4.5, "pooled z over batches %.2f", c.z);
    CHECK_MSG(lp->cost.photons > 0 && cam->cost.photons == 0, "light paths: %llu photons with, %llu without",
              (unsigned long long)lp->cost.photons, (unsigned long long)cam->cost.photons);
    for (int k = 0; k < BATCHES; k++) lucent_trace_result_free(&cams[k]), lucent_trace_result_free(&lps[k]);
    return ended;
}

/* Light paths (photons from the lights connected to the camera through the boundary) and camera paths
 * estimate the same image: on a dense sphere lit by a delta sun, a sun disc and the environment, the
 * light paths' share plus the camera paths' rest against camera paths alone (light_paths off),
 * independent seeds: the pixels' differences are unit normal in their standard errors, and the pooled
 * difference of 8 independent batches each is within 4.5 of its standard error (Student's t with 14
 * degrees of freedom: p = 0.0005 two-sided). The light paths' image depends on the seed and the
 * passes only (1 and 2 threads, 5 + 3 and 8 passes: bit for bit). */
TEST(light_paths_agree_with_camera_paths)
{
    lucent_scene *sc = dense_lit("{\"type\": \"directional\", \"direction\": [-1, -0.2, -0.3], \"intensity\": 2},"
                                 " {\"type\": \"directional\", \"direction\": [0.3, 0.5, -1], \"intensity\": 1,"
                                 " \"angular_radius\": 0.1},"
                                 " {\"type\": \"environment\", \"intensity\": 0.1}",
                                 32);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result one = {0}, split = {0};
    CHECK(sc != NULL);
    if (!sc) return;
    check_light_paths_agree(sc, 160, pool);
    lucent_tracer *tr = NULL;
    CHECK_OK(render(sc, NULL, 8, 12, NULL, &one));
    CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 5, .seed = 12, .pool = pool}, &split));
    lucent_trace_result_free(&split);
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 3, .pool = pool}, &split));
    CHECK_MSG(same_image(one.image, split.image) && same_image(one.variance, split.variance),
              "light paths: 1 thread and 8 passes differ from 2 threads and 5 + 3");
    lucent_tracer_destroy(tr);
    lucent_trace_result_free(&one), lucent_trace_result_free(&split);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* check_light_paths_agree on the dense sphere lit by LIGHTS at total_spp samples per pixel. */
static void dense_light_paths_agree(const char *lights, int total_spp)
{
    lucent_scene *sc = dense_lit(lights, 32);
    lucent_pool *pool = lucent_pool_create(2);
    CHECK(sc != NULL);
    if (sc) check_light_paths_agree(sc, total_spp, pool);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* The same for point lights: one outside the scene's bounding sphere (photons into the cone that
 * holds it) and one inside it, 0.7 mm off the surface (photons in every direction). 480 samples per
 * pixel: the pooled ratio's standard error is about 0.55%, so that a 5% error in the photons' power
 * is 9 of it (at 160, 1.2%: a deliberate 5% error gave z 3.5). */
TEST(light_paths_agree_for_point_lights)
{
    dense_light_paths_agree("{\"type\": \"point\", \"position\": [-3, 1, 2], \"intensity\": 20},"
                            " {\"type\": \"point\", \"position\": [0, 1.7, 0.3], \"intensity\": 0.5}",
                            480);
}

/* The same for sphere lights (a photon's direction uniform in the cone toward the scene grown by the
 * light's radius, its start on the light's disc perpendicular to it, lifted onto the light): one far
 * off, and one whose surface reaches into the scene's bounding sphere. */
TEST(light_paths_agree_for_sphere_lights)
{
    dense_light_paths_agree("{\"type\": \"sphere\", \"position\": [-3, 1, 2], \"radius\": 0.5, \"intensity\": 20},"
                            " {\"type\": \"sphere\", \"position\": [0, 1.9, 0.3], \"radius\": 0.2, \"intensity\": 0.5}",
                            480);
}

/* Each light's share of the photons follows what its photons bring (docs/trace.md, "Each light's share
 * of the photons"): the dense ball lit by two suns of equal power, one from the camera's side and one
 * from behind. The first pass draws by power: half each. A later pass gives light l the share
 * 0.2 p_l + 0.8 sqrt(M_l) / sum_k sqrt(M_k) of its photons (p_l its part of the power, M_l the mean of
 * its photons' squared connections so far), computed here from the moments the film kept; the next
 * pass's counts must follow it within 4.5 binomial standard deviations (the strata of light_paths.c
 * make them exact to within one; drawn independently they would spread binomially). And physics orders them: the
 * light from behind leaves the ball mostly where the camera does not see it, so it gets less than its
 * half. */
TEST(light_shares_follow_what_each_light_brings)
{
    lucent_scene *sc = dense_lit("{\"type\": \"directional\", \"direction\": [0.1, 0.1, -1], \"intensity\": 1},"
                                 " {\"type\": \"directional\", \"direction\": [0.1, 0.1, 1], \"intensity\": 1}",
                                 32);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_tracer *tr = NULL;
    lucent_trace_result r = {0};
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .seed = 3, .pool = pool}, &r));
    const tr_film *f = tr->film;
    double n1[2] = {(double)f->light_n[0], (double)f->light_n[1]}, root[2];
    double total = n1[0] + n1[1];
    CHECK_MSG(tr->light_count == 2 && total > 500, "%d lights, %.0f photons", tr->light_count, total);
    CHECK_MSG(fabs(n1[0] - 0.5 * total) < 4.5 * sqrt(0.25 * total), "first pass: %.0f of %.0f photons from the first",
              n1[0], total);
    for (int i = 0; i < 2; i++) root[i] = sqrt(f->light_m2[i] / n1[i]);
    double share[2];
    /* p_l = 1/2: two suns of the same irradiance through the same disc (E pi R^2 each) */
    for (int i = 0; i < 2; i++) share[i] = 0.2 * 0.5 + 0.8 * root[i] / (root[0] + root[1]);
    lucent_trace_result_free(&r);
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .pool = pool}, &r));
    double d[2] = {(double)f->light_n[0] - n1[0], (double)f->light_n[1] - n1[1]}, n2 = d[0] + d[1];
    printf("  pass 1: %.0f / %.0f photons; shares from its moments %.3f / %.3f; pass 2: %.0f / %.0f\n", n1[0], n1[1],
           share[0], share[1], d[0], d[1]);
    CHECK_MSG(fabs(d[1] - share[1] * n2) < 4.5 * sqrt(n2 * share[1] * (1 - share[1])),
              "second pass: %.0f of %.0f photons from behind, expected %.1f", d[1], n2, share[1] * n2);
    CHECK_MSG(share[1] < 0.4, "the light from behind's share %.3f", share[1]);
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* The entry roulette (docs/trace.md, "The entry roulette"): on the dense ball lit by suns of equal
 * power from the camera's side and from behind, the photons from behind arrive where the camera does
 * not see what they bring, and once the cells there are measured they go on with probability below 1
 * (weighted by its inverse). The image must still be the camera paths' (check_light_paths_agree: 8
 * independent batches, each a tracer that learns its own probabilities), and the roulette must engage
 * (4.4% of all photons end at entry; without the weight 1 / q the ratio falls to 0.960, z -4.9). */
TEST(entry_roulette_leaves_the_image_unchanged)
{
    lucent_scene *sc = dense_lit("{\"type\": \"directional\", \"direction\": [0.1, 0.1, -1], \"intensity\": 1},"
                                 " {\"type\": \"directional\", \"direction\": [0.1, 0.1, 1], \"intensity\": 1}",
                                 32);
    lucent_pool *pool = lucent_pool_create(2);
    CHECK(sc != NULL);
    /* 12 passes per batch in every build (the grid measures a cell from its 32nd photon that went on,
     * after a few passes at 32 x 32): not divided by SLOW like the others */
    double ended = sc ? check_light_paths_agree(sc, 96 * SLOW, pool) : 0;
    CHECK_MSG(ended > 0.02, "the entry roulette ended %.1f%% of the photons", 100 * ended);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* A light of intensity 0 beside the sun: it is no camera-side light, and a camera path that enters
 * the dense ball stays on the camera side to its end. Before, such a path walked on for the dark
 * light and, after its first reflection inside, counted the sun too, which the light paths had
 * counted already (measured on a marble ball: 291 against 206 with light paths off). */
TEST(light_paths_agree_beside_a_dark_light)
{
    dense_light_paths_agree("{\"type\": \"directional\", \"direction\": [-1, -0.2, -0.3], \"intensity\": 2},"
                            " {\"type\": \"directional\", \"direction\": [1, 0, -0.5], \"intensity\": 0}",
                            96);
}

/* A scene of two balls, one dense (served by the light paths under auto) and one not (albedo 0.67 to
 * 0.91): the light paths must connect to the camera only out of the dense one, since camera paths
 * enter the other with every light. Before that was so, the second ball's light was counted by both,
 * twice its value (measured: 94.7 against 48.1 over its half of the image), so the pooled ratio
 * was far outside its error. */
TEST(light_paths_leave_unserved_objects_to_camera_paths)
{
    lucent_scene *sc =
        scene_from("{\"camera\": {\"position\": [0, 0, 6], \"target\": [0, 0, 0], \"fov_y\": 35},"
                   " \"lights\": [{\"type\": \"directional\", \"direction\": [-1, -0.2, -0.3], \"intensity\": 2},"
                   " {\"type\": \"environment\", \"intensity\": 0.1}],"
                   " \"objects\": [{\"name\": \"dense\", \"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1,"
                   " \"subdivisions\": 4}, \"material\": {\"units\": \"mm^-1\", \"sigma_a\": [0.05, 0.08, 0.1],"
                   " \"sigma_s\": [20, 18, 16], \"g\": 0, \"eta\": 1.5}, \"roughness\": 0.3,"
                   " \"transform\": {\"translate\": [-1.1, 0, 0]}},"
                   " {\"name\": \"thin\", \"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 4},"
                   " \"material\": {\"units\": \"mm^-1\", \"sigma_a\": [1, 2, 4], \"sigma_s\": [10, 8, 8], \"g\": 0,"
                   " \"eta\": 1.5}, \"roughness\": 0.3, \"transform\": {\"translate\": [1.1, 0, 0]}}],"
                   " \"render\": {\"width\": 64, \"height\": 32}}");
    lucent_pool *pool = lucent_pool_create(2);
    CHECK(sc != NULL);
    if (sc) check_light_paths_agree(sc, 96, pool);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* The sum over the image of the radiance a small light gives a sphere of matter that only reflects
 * (sigma_a 1000 / mm: what refracts in is absorbed within a micron), camera paths only. */
static double reflected_sum(const char *light, uint64_t seed, lucent_pool *pool)
{
    lucent_scene *sc = sphere_scene("{\"units\": \"mm^-1\", \"sigma_a\": 1000, \"sigma_s\": 0.001, \"g\": 0, "
                                    "\"eta\": 1.5}",
                                    light, 32, ", \"roughness\": 0.3");
    lucent_trace_result r = {0};
    double sum = 0;
    if (sc) sc->render.trace.light_paths = LUCENT_LIGHT_PATHS_OFF;
    if (sc) CHECK_OK(render(sc, NULL, 64, seed, pool, &r));
    for (int i = 0; r.image && i < 3 * r.image->width * r.image->height; i++) sum += r.image->data[i];
    lucent_trace_result_free(&r);
    lucent_scene_destroy(sc);
    return sum;
}

/* A sphere light of intensity I that lies wholly above a surface point's horizon gives it the
 * irradiance of a point light of intensity I at its centre, I cos / d^2 (the sphere's radiance
 * I / (pi r^2) over the solid angle it subtends, pi sin^2 a, sin a = r / d): at radius 0.01 mm, 3.7 mm
 * away, the reflection of the two is the same within the noise and the BSDF's change across the
 * light's 0.15 degrees (below 1e-4). A shadow ray set off the surface used to be cut at the sampled
 * point's distance to the light, so that the light it was aimed at blocked it: the sphere light gave
 * 0.76 of the point light's reflection. Two seeds each: the noise of a sum is its spread. */
TEST(sphere_light_gives_a_point_lights_irradiance)
{
    lucent_pool *pool = lucent_pool_create(2);
    const char *point = "{\"type\": \"point\", \"position\": [-3, 1, 2], \"intensity\": 20}";
    const char *sphere = "{\"type\": \"sphere\", \"position\": [-3, 1, 2], \"radius\": 0.01, \"intensity\": 20}";
    double p1 = reflected_sum(point, 1, pool), p2 = reflected_sum(point, 2, pool);
    double s1 = reflected_sum(sphere, 1, pool), s2 = reflected_sum(sphere, 2, pool);
    double ratio = (s1 + s2) / (p1 + p2), spread = fabs(p1 - p2) / (p1 + p2) + fabs(s1 - s2) / (s1 + s2);
    printf("  reflected: point light %.4f, %.4f; sphere light %.4f, %.4f; ratio %.5f (seeds' spread %.5f)\n", p1, p2,
           s1, s2, ratio, spread);
    CHECK(p1 > 0 && s1 > 0);
    CHECK_MSG(fabs(ratio - 1) < fmax(4 * spread, 1e-3), "sphere / point %.5f", ratio);
    lucent_pool_destroy(pool);
}

/* Mean over the object's pixels and channels of (a - b)^2 / 2: the squared error of one estimate,
 * from two independent ones (E[(a - b)^2] = 2 var). */
static double squared_error(const lucent_trace_result *a, const lucent_trace_result *b)
{
    double sum = 0;
    int n = 0;
    for (int p = 0; p < a->image->width * a->image->height; p++) {
        if (a->coverage->data[p] < 1.0f) continue;
        for (int c = 0; c < 3; c++) {
            double d = a->image->data[3 * p + c] - b->image->data[3 * p + c];
            sum += 0.5 * d * d, n++;
        }
    }
    return sum / n;
}

/* Unbiased Monte Carlo: the error falls as spp^-1/2. Slope of log error against log spp over
 * 4 .. 256 spp, each squared error the mean of PAIRS independent pairs of estimates, on a sphere lit
 * from the camera's side (light tails: no dark regions); over 8 seed sets the slope was -0.50 with a
 * spread of 0.025, so -0.5 +- 0.1 tests the law, not luck. */
enum { PAIRS = 4 };
TEST(error_falls_as_one_over_sqrt_spp)
{
    lucent_scene *sc = sphere_scene(
        "\"skin1\"", "{\"type\": \"directional\", \"direction\": [0.2, -0.2, -1], \"intensity\": 2}", 24, NULL);
    lucent_pool *pool = lucent_pool_create(2);
    CHECK(sc != NULL);
    if (!sc) return;
    const int spp[3] = {4, 32 / SLOW, 256 / SLOW};
    double lx[3], ly[3];
    for (int i = 0; i < 3; i++) {
        double e2 = 0;
        for (int k = 0; k < PAIRS; k++) {
            lucent_trace_result a = {0}, b = {0};
            uint64_t seed = 100 + 10 * i + 2 * k;
            CHECK_OK(render(sc, NULL, spp[i], seed, pool, &a));
            CHECK_OK(render(sc, NULL, spp[i], seed + 1, pool, &b));
            if (a.image && b.image) e2 += squared_error(&a, &b) / PAIRS;
            lucent_trace_result_free(&a), lucent_trace_result_free(&b);
        }
        lx[i] = log(spp[i]), ly[i] = 0.5 * log(e2);
    }
    double mx = (lx[0] + lx[1] + lx[2]) / 3, my = (ly[0] + ly[1] + ly[2]) / 3, sxy = 0, sxx = 0;
    for (int i = 0; i < 3; i++) sxy += (lx[i] - mx) * (ly[i] - my), sxx += (lx[i] - mx) * (lx[i] - mx);
    double slope = sxy / sxx;
    printf("  RMS errors %.4g, %.4g, %.4g at %d, %d, %d spp: slope %.3f\n", exp(ly[0]), exp(ly[1]), exp(ly[2]), spp[0],
           spp[1], spp[2], slope);
    CHECK_MSG(fabs(slope + 0.5) < 0.1, "slope %.3f, not -0.5", slope);
    lucent_pool_destroy(pool);
    lucent_scene_destroy(sc);
}

/* The frame is lucent_camera_ray's, the GL renderer's: a sphere of radius R at distance D on the view
 * axis covers the pixels within (H / 2) tan(asin(R / D)) / tan(fov_y / 2) of the image centre (the
 * cone tangent to the sphere through the pinhole). Off-centre cameras are the scene module's tests. */
TEST(framing_matches_the_camera_projection)
{
    lucent_scene *sc = sphere_scene("\"skin1\"", "{\"type\": \"environment\"}", 48, NULL);
    lucent_trace_result r = {0};
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(render(sc, NULL, 4, 1, NULL, &r));
    double rpx = 24 * tan(asin(1.0 / 4.0)) / tan(0.5 * 35 * M_PI / 180);
    int wrong = 0;
    for (int y = 0; y < 48 && r.coverage; y++)
        for (int x = 0; x < 48; x++) {
            double d = hypot(x + 0.5 - 24, y + 0.5 - 24), c = r.coverage->data[y * 48 + x];
            if ((d < rpx - 0.75 && c < 1) || (d > rpx + 0.75 && c > 0)) wrong++;
        }
    printf("  silhouette radius %.2f pixels: %d pixels off it\n", rpx, wrong);
    CHECK(wrong == 0);
    lucent_trace_result_free(&r);
    lucent_scene_destroy(sc);
}

/* ---- what the tracer refuses, and bounds ---- */

TEST(refuses_delta_lights_through_smooth_boundaries)
{
    const char *smooth = ", \"roughness\": 0";
    lucent_scene *sc = sphere_scene("\"skin1\"", "{\"type\": \"directional\", \"direction\": [0, 0, -1]}", 8, smooth);
    lucent_tracer *tr = NULL;
    CHECK(sc != NULL);
    if (sc)
        CHECK_ERR(lucent_tracer_create(sc, NULL, &tr), LUCENT_ERR_UNSUPPORTED, "lights[0]", "angular_radius 0",
                  "objects[0] \"ball\"", "smooth boundary", "cannot converge");
    CHECK(tr == NULL);
    lucent_scene_destroy(sc);
    sc = sphere_scene("\"skin1\"",
                      "{\"type\": \"environment\"}, {\"type\": \"point\", \"position\": [0, 3, 3], \"intensity\": 5}",
                      8, smooth);
    if (sc) CHECK_ERR(lucent_tracer_create(sc, NULL, &tr), LUCENT_ERR_UNSUPPORTED, "lights[1]", "a point light");
    lucent_scene_destroy(sc);
    /* What converges: a sun with a disc, a rough boundary, an index-matched one, no delta light. */
    const char *ok[][2] = {
        {"{\"type\": \"directional\", \"direction\": [0, 0, -1], \"angular_radius\": 0.5}", smooth},
        {"{\"type\": \"directional\", \"direction\": [0, 0, -1]}", ", \"roughness\": 0.01"},
        {"{\"type\": \"environment\"}, {\"type\": \"sphere\", \"position\": [0, 3, 3], \"radius\": 0.5}", smooth},
    };
    for (int i = 0; i < 3; i++) {
        sc = sphere_scene("\"skin1\"", ok[i][0], 8, ok[i][1]);
        if (sc) CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
        lucent_tracer_destroy(tr), tr = NULL;
        lucent_scene_destroy(sc);
    }
    sc = sphere_scene("{\"units\": \"mm^-1\", \"sigma_a\": 0.1, \"sigma_s\": 1, \"g\": 0, \"eta\": 1}",
                      "{\"type\": \"point\", \"position\": [0, 3, 3]}", 8, smooth);
    if (sc) CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

/* Removes every fifth face: the medium is open, paths leave through the holes. */
static void punch_holes(lucent_mesh *m)
{
    size_t kept = 0;
    for (size_t f = 0; f < m->face_count; f++)
        if (f % 5 != 0) memmove(m->faces + 3 * kept++, m->faces + 3 * f, 3 * sizeof *m->faces);
    m->face_count = kept;
}

/* A non-absorbing medium (Russian roulette never ends its paths) in open meshes: the walk ends when
 * it leaves through a hole, or at max_bounces / max_scatter. The call returns, with finite pixels. */
TEST(meshes_with_holes_terminate)
{
    lucent_scene *sc = sphere_scene("{\"units\": \"mm^-1\", \"sigma_a\": 0, \"sigma_s\": 5, \"g\": 0.5, \"eta\": 1.4}",
                                    "{\"type\": \"directional\", \"direction\": [-0.5, -0.5, -0.7]}, "
                                    "{\"type\": \"environment\", \"intensity\": 0.2}",
                                    16, NULL);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_trace_result r = {0};
    CHECK(sc != NULL);
    if (!sc) return;
    punch_holes(sc->objects[0].mesh);
    CHECK_OK(render(sc, NULL, 8, 1, pool, &r));
    lucent_image_stats st;
    if (r.image) lucent_image_stats_compute(r.image, &st);
    printf("  open sphere: %llu paths escaped through holes, %llu truncated\n", (unsigned long long)r.escaped,
           (unsigned long long)r.truncated);
    CHECK(r.image && st.nonfinite[0] + st.nonfinite[1] + st.nonfinite[2] == 0 && r.escaped > 0);
    lucent_trace_result_free(&r);
    lucent_scene_destroy(sc);
    /* The scanned dragon at its coarsest resolution has real holes (fetched by make setup). */
    const char *dragon = LUCENT_SOURCE_DIR "/data/meshes/dragon_vrip_res4.ply.gz";
    FILE *f = fopen(dragon, "rb");
    if (f) {
        fclose(f);
        char json[1024];
        snprintf(json, sizeof json,
                 "{\"camera\": {\"position\": [0, 120, 250], \"target\": [0, 120, 0], \"fov_y\": 40},"
                 " \"lights\": [{\"type\": \"directional\", \"direction\": [0.5, -0.4, -0.7]}],"
                 " \"objects\": [{\"mesh\": \"%s\", \"mm_per_unit\": 1000, \"material\": \"marble\"}],"
                 " \"render\": {\"width\": 24, \"height\": 24, \"max_scatter\": 20000}}",
                 dragon);
        sc = scene_from(json);
        if (sc) CHECK_OK(render(sc, NULL, 2, 1, pool, &r));
        printf("  dragon res4 (marble): %llu escaped, %llu truncated\n", (unsigned long long)r.escaped,
               (unsigned long long)r.truncated);
        lucent_trace_result_free(&r);
        lucent_scene_destroy(sc);
    } else {
        printf("  (no %s: run make setup for the dragon case)\n", dragon);
    }
    lucent_pool_destroy(pool);
}

/* A point cloud has no surface to trace: the tracer leaves it out, so a scene with a cloud inside
 * the ball's bounds (the same bounds, the same photons) gives the ball's image bit for bit. */
TEST(point_clouds_are_skipped)
{
    const char *cloud = test_path("cloud.ply");
    FILE *f = fopen(cloud, "w");
    CHECK(f != NULL);
    if (!f) return;
    fprintf(f, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\nend_header\n"
               "0 0 0 0 0 1\n0.1 0 0 0 0 1\n0 0.1 0 0 0 1\n");
    fclose(f);
    const char *light = "{\"type\": \"directional\", \"direction\": [0, 0, -1]}";
    char extra[1200];
    snprintf(extra, sizeof extra, "}, {\"points\": \"%s\", \"material\": \"skin1\"", cloud);
    lucent_scene *a = sphere_scene("\"marble\"", light, 12, NULL), *b = sphere_scene("\"marble\"", light, 12, extra);
    lucent_trace_result ra = {0}, rb = {0};
    CHECK(a && b);
    if (b) CHECK(b->object_count == 2 && b->objects[1].points && b->objects[1].mesh->face_count == 0);
    if (a && b) CHECK_OK(render(a, NULL, 4, 7, NULL, &ra));
    if (a && b) CHECK_OK(render(b, NULL, 4, 7, NULL, &rb));
    if (ra.image && rb.image) CHECK(!memcmp(ra.image->data, rb.image->data, (size_t)12 * 12 * 3 * sizeof(float)));
    lucent_trace_result_free(&ra), lucent_trace_result_free(&rb);
    lucent_scene_destroy(a), lucent_scene_destroy(b);
}

TEST(bad_input_is_named)
{
    lucent_tracer *tr = NULL;
    lucent_trace_result r;
    CHECK_ERR(lucent_tracer_create(NULL, NULL, &tr), LUCENT_ERR_INVALID_ARGUMENT, "no scene");
    lucent_scene *sc = small_lit_scene();
    CHECK(sc != NULL);
    if (!sc) return;
    CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    CHECK_ERR(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = -1}, &r), LUCENT_ERR_INVALID_ARGUMENT, "spp");
    CHECK_ERR(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .time_limit = NAN}, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "time_limit");
    CHECK_ERR(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .target_error = -1}, &r),
              LUCENT_ERR_INVALID_ARGUMENT, "target_error");
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .seed = 4}, &r));
    lucent_trace_result_free(&r);
    CHECK_ERR(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1, .seed = 5}, &r), LUCENT_ERR_INVALID_ARGUMENT,
              "seed 4", "seed 5", "lucent_tracer_reset");
    lucent_tracer_reset(tr);
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 2, .seed = 5}, &r));
    CHECK(r.spp == 2 && r.seed == 5);
    lucent_trace_result_free(&r);
    /* a time limit stops early, a target error too */
    CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = 1000000, .time_limit = 0.05}, &r));
    CHECK(r.spp >= 1 && r.spp < 1000000); /* how many passes fit in 0.05 s depends on the machine */
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

/* Issue 32 item 8: the guiding field's pre-pass. Its inside shares (a ray per row of points, stopping at the
 * object's grid) give each object's volume, against the mesh's own volume by the divergence theorem (sum of
 * p0 . (p1 x p2) / 6), whatever other objects stand in the rays' way; and past its deadline it starts no
 * photon chunk and no object, so the objects walk unguided (main built every object's field regardless). */
static double mesh_volume(const lucent_mesh *m)
{
    double v = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        v3 p[3];
        for (int k = 0; k < 3; k++) p[k] = v3_load(m->positions + 3 * (size_t)m->faces[3 * f + k]);
        v += v3_dot(p[0], v3_cross(p[1], p[2])) / 6;
    }
    return v;
}

TEST(guiding_field_inside_shares_and_deadline)
{
    lucent_scene *sc = scene_from(
        "{\"camera\": {\"position\": [0, 0, 8], \"target\": [0, 0, 0], \"fov_y\": 40},"
        " \"lights\": [{\"type\": \"directional\", \"direction\": [-0.6, -0.3, -0.7], \"intensity\": 2}],"
        " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 1, \"subdivisions\": 3}, \"material\": "
        "\"skin1\"},"
        "  {\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 0.6, \"subdivisions\": 3}, \"material\": \"skin1\","
        "   \"transform\": {\"translate\": [1.75, 0.2, 0]}},"
        "  {\"mesh\": {\"primitive\": \"icosphere\", \"radius\": 0.5, \"subdivisions\": 2}, \"material\": \"skin1\","
        "   \"transform\": {\"translate\": [-1.7, 0, 0.3]}}],"
        " \"render\": {\"width\": 16, \"height\": 16}}");
    CHECK(sc != NULL);
    if (!sc) return;
    lucent_tracer *tr = NULL;
    CHECK_OK(lucent_tracer_create(sc, NULL, &tr));
    if (!tr) return lucent_scene_destroy(sc);
    CHECK(tr->object_count == 3);
    CHECK_OK(tr_field_build(tr, NULL, lucent_clock_seconds() - 1)); /* a deadline already past */
    for (int o = 0; tr->fields && o < tr->object_count; o++)
        CHECK_MSG(tr->fields[o].grad == NULL, "object %d has a field built past the deadline", o);
    tr_field_destroy(tr);
    CHECK_OK(tr_field_build(tr, NULL, 0));
    for (int o = 0; tr->fields && o < tr->object_count; o++) {
        const tr_field *f = &tr->fields[o];
        CHECK(f->grad != NULL);
        size_t n = (size_t)f->n[0] * f->n[1] * f->n[2];
        float *in = malloc(n * sizeof *in);
        if (!in) continue;
        tr_field_inside_share(tr, o, f, in);
        double sum = 0;
        for (size_t c = 0; c < n; c++) sum += in[c];
        double got = sum * f->cell * f->cell * f->cell;
        double want = mesh_volume(sc->objects[tr->objects[o].scene_index].mesh);
        /* 8 points per cell of 1/14 of the diameter: the boundary cells' quadrature, under 1% (0.25% seen) */
        CHECK_MSG(fabs(got / want - 1) < 0.01, "object %d: inside volume %g mm^3, the mesh's %g", o, got, want);
        printf("  object %d: inside volume %.4f mm^3, the mesh's %.4f\n", o, got, want);
        free(in);
    }
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

TEST_MAIN(TEST_ENTRY(guiding_field_inside_shares_and_deadline), TEST_ENTRY(furnace_index_matched_non_absorbing),
          TEST_ENTRY(furnace_adaptive), TEST_ENTRY(furnace_smooth_dielectric_non_absorbing),
          TEST_ENTRY(furnace_absorbing_or_rough_never_more), TEST_ENTRY(agrees_with_the_light_traced_sphere),
          TEST_ENTRY(same_seed_same_image_on_one_and_two_threads),
          TEST_ENTRY(interreflection_off_removes_only_light_between_surfaces),
          TEST_ENTRY(error_falls_as_one_over_sqrt_spp), TEST_ENTRY(framing_matches_the_camera_projection),
          TEST_ENTRY(refuses_delta_lights_through_smooth_boundaries), TEST_ENTRY(meshes_with_holes_terminate),
          TEST_ENTRY(point_clouds_are_skipped), TEST_ENTRY(bad_input_is_named),
          TEST_ENTRY(distance_bounded_flights_change_nothing), TEST_ENTRY(distance_bound_is_the_distance),
          TEST_ENTRY(depth_lattice_bounds_the_distance), TEST_ENTRY(free_run_stops_before_the_first_surface),
          TEST_ENTRY(deep_nee_roulette_is_unbiased), TEST_ENTRY(light_paths_agree_with_camera_paths),
          TEST_ENTRY(light_paths_agree_for_point_lights), TEST_ENTRY(light_paths_agree_for_sphere_lights),
          TEST_ENTRY(light_paths_leave_unserved_objects_to_camera_paths),
          TEST_ENTRY(light_paths_agree_beside_a_dark_light), TEST_ENTRY(light_shares_follow_what_each_light_brings),
          TEST_ENTRY(entry_roulette_leaves_the_image_unchanged),
          TEST_ENTRY(sphere_light_gives_a_point_lights_irradiance))
