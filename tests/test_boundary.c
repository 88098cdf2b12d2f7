/* Tests of the path tracer's boundary on flat parts (lucent_boundary_run, src/profile/boundary_mc.c)
 * and of the bake part made from it (LUCENT_BAKE_BOUNDARY). Expected values: Giovanelli 1955's
 * half-space (published), energy conservation, Beer-Lambert through a matched slab (closed form),
 * Helmholtz reciprocity (a physical law), and the factors' definitions. The tables against the path
 * tracer itself: test_gl_boundary. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "gl/reference/reference.h"
#include "lucent/bake.h"
#include "lucent/profile.h"
#include "lucent/trace.h"
#include "test.h"

#if defined(__SANITIZE_ADDRESS__)
#define SLOW 4 /* sanitizer builds run about ten times slower: a quarter of the work */
#else
#define SLOW 1
#endif

enum { N = LUCENT_BOUNDARY_BINS };

static lucent_material grey(double sigma_a, double sigma_s, double eta)
{
    lucent_material m;
    memset(&m, 0, sizeof m);
    snprintf(m.name, sizeof m.name, "grey");
    for (int c = 0; c < 3; c++) m.sigma_a[c] = sigma_a, m.sigma_s[c] = sigma_s;
    m.eta = eta;
    return m;
}

/* The cosine-weighted solid angle of bin b over pi: hi^2 - lo^2. */
static double bin_weight(int b) { return (2.0 * b + 1.0) / (N * N); }

static lucent_boundary_result *run(const lucent_material *m, double roughness, double thickness, uint64_t photons,
                                   lucent_pool *pool)
{
    lucent_boundary_result *r = malloc(sizeof *r);
    CHECK(r != NULL);
    if (!r) return NULL;
    lucent_boundary_desc d = {
        .material = m, .roughness = roughness, .thickness = thickness, .photons = photons, .pool = pool};
    CHECK_OK(lucent_boundary_run(&d, r));
    return r;
}

/* Giovanelli 1955 (n 1.5, g 0, albedo 0.9, normal incidence): Rsp + Rd = 0.2600, Rsp 0.04, so
 * Rd = 0.2200 (4 digits), the value test_bake holds the MCML walk to. The smooth face's row of the
 * normal incidence bin (0 to 14.4 degrees) integrated over exit, within 3 standard errors plus 0.001
 * for the bin's width (Rd changes by less over 14 degrees; Fresnel's reflectance by 0.0003). */
TEST(smooth_half_space_matches_giovanelli)
{
    lucent_material m = grey(0.1, 0.9, 1.5);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *r = run(&m, 0, 0, 6000, pool);
    for (int c = 0; r && c < 3; c++) {
        double err = r->reflect_total_se[c][N - 1], rd = r->reflect_total[c][N - 1];
        printf("     channel %d: Rd %.4f +- %.4f (Giovanelli 0.2200), specular %.4f (Fresnel 0.0400)\n", c, rd, err,
               r->specular[c][N - 1]);
        CHECK_MSG(fabs(rd - 0.2200) <= 3 * err + 0.001, "Rd %.4f +- %.4f", rd, err);
        CHECK_NEAR(r->specular[c][N - 1], 0.0401, 0.0003);
    }
    free(r);
    lucent_pool_destroy(pool);
}

/* Energy: light that enters a half-space comes back or is absorbed, so with a smooth face the
 * reflectance of each incidence bin plus its specular albedo plus the absorbed fraction is 1. A rough
 * face's single-scattering microfacets lose what their masking stops (as the path tracer's do): less
 * than 1. (A little absorption keeps the walks short.) */
TEST(half_space_keeps_energy)
{
    lucent_material m = grey(0.01, 1, 1.4);
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *smooth = run(&m, 0, 0, 300, pool), *rough = run(&m, 0.5, 0, 300, pool);
    for (int i = 2; smooth && rough && i < N; i += 7) {
        /* the sum's standard error is at most the sum of its terms' (they correlate) */
        double es = smooth->reflect_total_se[0][i] + smooth->specular_se[0][i] + smooth->absorbed_se[0][i];
        double er = rough->reflect_total_se[0][i] + rough->specular_se[0][i] + rough->absorbed_se[0][i];
        double s = smooth->reflect_total[0][i] + smooth->specular[0][i] + smooth->absorbed[0][i];
        double r = rough->reflect_total[0][i] + rough->specular[0][i] + rough->absorbed[0][i];
        printf("     incidence cosine %.2f: smooth %.4f +- %.4f, rough (0.5) %.4f +- %.4f\n",
               lucent_boundary_bin_cosine(i), s, es, r, er);
        CHECK_MSG(fabs(s - 1) <= 3 * es, "smooth: %.4f", s);
        CHECK_MSG(r < 1 - 3 * er, "rough: %.4f", r);
    }
    free(smooth), free(rough);
    lucent_pool_destroy(pool);
}

/* A matched (eta 1), non-scattering slab: light at cosine mu leaves the far face unscattered, in its
 * own direction, with probability exp(-sigma_a s / mu) (Beer-Lambert), nothing reflected. Per
 * incidence bin the cosine-weighted mean of that over the bin (the light is drawn so within it), by
 * quadrature, within 3 binomial standard errors of the photon count; all of it within the incidence
 * bin and its neighbours (the exit kernel resolves an angle to 0.35 degrees inside) and of order 0. */
TEST(matched_slab_follows_beer_lambert)
{
    enum { PHOTONS = 2000 };
    lucent_material m = grey(0.5, 0, 1.0);
    lucent_boundary_result *r = run(&m, 0, 1.0, PHOTONS, NULL);
    for (int i = 0; r && i < N; i++) {
        double lo = (double)i / N, hi = (i + 1.0) / N, expect = 0;
        enum { Q = 200 };
        for (int k = 0; k < Q; k++) { /* uniform in mu^2 */
            double mu = sqrt(lo * lo + (k + 0.5) / Q * (hi * hi - lo * lo));
            expect += exp(-0.5 / mu) / Q;
        }
        double t = r->transmit_total[0][i], near = 0, order0 = 0, tol = 3 * sqrt(expect * (1 - expect) / PHOTONS);
        for (int o = i - 1; o <= i + 1; o++)
            if (o >= 0 && o < N) near += r->transmit[0][i][o] * bin_weight(o);
        for (int o = 0; o < N; o++) order0 += r->transmit_order[0][0][i][o] * bin_weight(o);
        CHECK_MSG(fabs(t - expect) <= tol + 1e-12, "bin %d: %g vs %g (tolerance %g)", i, t, expect, tol);
        CHECK_MSG(fabs(near - t) <= 1e-9 * (1 + t) && fabs(order0 - t) <= 1e-9 * (1 + t), "bin %d: %g, %g of %g", i,
                  near, order0, t);
        CHECK(r->reflect_total[0][i] == 0 && r->specular[0][i] == 0);
    }
    free(r);
}

/* Helmholtz reciprocity: light and viewer both outside, f(mu_i, mu_o) = f(mu_o, mu_i) (the boundary's
 * BSDF keeps the generalised reciprocity of Walter et al. 2007). The table and its transpose are
 * independent estimates; their differences over the combined standard error have mean square about
 * 1 (with 8 batches the error estimates spread, so the bound is 2). */
TEST(rough_half_space_is_reciprocal)
{
    lucent_material m;
    CHECK_OK(lucent_material_preset_find("skin1", &m));
    lucent_pool *pool = lucent_pool_create(2);
    lucent_boundary_result *r = run(&m, 0.3, 0, 1500, pool);
    for (int c = 0; r && c < 3; c++) {
        double chi2 = 0, worst = 0;
        int n = 0;
        for (int i = 0; i < N; i++)
            for (int o = i + 1; o < N; o++) {
                double z = (r->reflect[c][i][o] - r->reflect[c][o][i]) /
                           sqrt(pow(r->reflect_se[c][i][o], 2) + pow(r->reflect_se[c][o][i], 2));
                chi2 += z * z, n++, worst = fmax(worst, fabs(z));
            }
        printf("     channel %d: mean square of (f - f^T) / se %.2f over %d pairs, largest |z| %.1f\n", c, chi2 / n, n,
               worst);
        CHECK_MSG(chi2 / n < 2, "channel %d: %.2f", c, chi2 / n);
    }
    free(r);
    lucent_pool_destroy(pool);
}

/* The bake part: the albedo is the hemispherical albedo of the table, the exit curve integrates to 1,
 * every column of the entry factor too, and albedo x A x E gives the table back (its symmetric
 * estimate); baked again from the cache bit for bit; another roughness is another bake. */
TEST(bake_part_factors_the_table)
{
    lucent_material m;
    CHECK_OK(lucent_material_preset_find("skin1", &m));
    lucent_pool *pool = lucent_pool_create(2);
    lucent_cache *cache = NULL;
    CHECK_OK(lucent_cache_create(test_path("cache/boundary"), &cache));
    lucent_bake_desc d = {.what = LUCENT_BAKE_BOUNDARY, .roughness = 0.3, .boundary_photons = 300, .pool = pool};
    lucent_baked a = {0}, b = {0};
    CHECK_OK(lucent_material_bake(&m, &d, cache, &a));
    CHECK(a.have == LUCENT_BAKE_BOUNDARY && !a.boundary_cached && a.boundary_roughness == 0.3);
    for (int c = 0; c < 3; c++) {
        double e = 0;
        for (int o = 0; o < N; o++) e += a.boundary[(N * N + o) * 3 + c] * bin_weight(o);
        CHECK_NEAR(e, 1, 1e-5);
        for (int o = 0; o < N; o += 5) {
            double s = 0;
            for (int i = 0; i < N; i++) s += a.boundary[(i * N + o) * 3 + c] * bin_weight(i);
            CHECK_NEAR(s, 1, 1e-5);
        }
        CHECK(a.boundary_albedo[c] > 0.05 && a.boundary_albedo[c] < 0.5);
    }
    CHECK(a.boundary_albedo[0] > a.boundary_albedo[1] && a.boundary_albedo[1] > a.boundary_albedo[2]); /* skin */
    CHECK_OK(lucent_material_bake(&m, &d, cache, &b));
    CHECK(b.boundary_cached && !memcmp(a.boundary, b.boundary, sizeof a.boundary));
    d.roughness = 0.1;
    CHECK_OK(lucent_material_bake(&m, &d, cache, &b));
    CHECK(!b.boundary_cached && b.boundary_roughness == 0.1 && memcmp(a.boundary, b.boundary, sizeof a.boundary));
    d.roughness = 2;
    CHECK_ERR(lucent_material_bake(&m, &d, cache, &b), LUCENT_ERR_INVALID_ARGUMENT, "Skin1", "roughness");
    lucent_baked_free(&a), lucent_baked_free(&b);
    lucent_cache_destroy(cache);
    lucent_pool_destroy(pool);
}

/* ---- the half-space: the real-time methods against the path tracer ---- */

/* A box 2000 x 2000 x 500 mm, its top face at z = 0 (the half-space for these materials: Skin1's
 * diffusion length is 3.7 mm, marble's 8.5), as an OBJ in the test's folder. */
static const char *box_obj(void)
{
    const char *path = test_path("halfspace-box.obj");
    FILE *f = fopen(path, "w");
    CHECK(f != NULL);
    if (!f) return path;
    fputs("v -1000 -1000 -500\nv 1000 -1000 -500\nv 1000 1000 -500\nv -1000 1000 -500\n"
          "v -1000 -1000 0\nv 1000 -1000 0\nv 1000 1000 0\nv -1000 1000 0\n"
          "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\nf 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\n"
          "f 4 1 5\nf 4 5 8\n",
          f);
    fclose(f);
    return path;
}

enum { HS_W = 12, HS_H = 64, HS_BINS = 5 };
static const double k_hs_edges[HS_BINS + 1] = {0, 20, 40, 60, 70, 80}; /* degrees of the view from the normal */

/* Per bin of view angle and channel: the sum of the tracer's radiance (subsurface only: the specular
 * highlight is the same GGX reflection in both renderers, tested in test_gl_render) and its variance,
 * and the sum of what the real-time methods show, the CPU reference of their surface pass
 * (gl_ref_shade, Lambert: on a flat, uniformly lit face every method's blur or curvature changes
 * nothing) with the boundary's tables baked by the renderer's bake. */
typedef struct hs_bins {
    double tracer[HS_BINS][3], var[HS_BINS][3], gl[HS_BINS][3];
    int pixels[HS_BINS];
} hs_bins;

static void halfspace_case(const char *material, double roughness, const double light[3], int spp, uint64_t photons,
                           lucent_pool *pool, lucent_cache *cache, hs_bins *out)
{
    /* the camera 40 mm above the face looking 42 degrees from straight down: views from 2 to 82 degrees */
    char json[2048];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, 40], \"target\": [0, 36.0, 0], \"fov_y\": 80},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [%.17g, %.17g, %.17g], \"intensity\": 1}],"
             " \"objects\": [{\"mesh\": \"%s\", \"material\": \"%s\", \"roughness\": %.17g}],"
             " \"render\": {\"width\": %d, \"height\": %d, \"light_paths\": \"off\"}}",
             light[0], light[1], light[2], box_obj(), material, roughness, HS_W, HS_H);
    memset(out, 0, sizeof *out);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "halfspace.json", NULL, NULL, &sc));
    if (!sc) return;
    lucent_tracer *tr = NULL;
    lucent_trace_result r = {0};
    CHECK_OK(lucent_tracer_create(sc, &(lucent_tracer_desc){.subsurface_only = true}, &tr));
    if (tr) CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = spp, .seed = 7, .pool = pool}, &r));
    lucent_baked b = {0};
    const lucent_scene_object *o = &sc->objects[0];
    CHECK_OK(lucent_material_bake(
        &o->material,
        &(lucent_bake_desc){
            .what = LUCENT_BAKE_BOUNDARY, .roughness = roughness, .boundary_photons = photons, .pool = pool},
        cache, &b));
    gl_ref_material m = {.roughness = roughness, .eta = o->material.eta, .boundary = b.boundary};
    memcpy(m.albedo, b.boundary_albedo, sizeof m.albedo);
    for (int y = 0; r.image && y < HS_H; y++)
        for (int x = 0; x < HS_W; x++) {
            double org[3], dir[3];
            lucent_camera_ray(&sc->camera, HS_W, HS_H, x + 0.5, y + 0.5, org, dir);
            double deg = acos(-dir[2]) * 180 / M_PI, t = -org[2] / dir[2];
            int k = 0;
            while (k < HS_BINS && deg >= k_hs_edges[k + 1]) k++;
            if (k == HS_BINS || deg < k_hs_edges[0]) continue;
            gl_ref_point p = {.position = {org[0] + t * dir[0], org[1] + t * dir[1], 0}, .normal = {0, 0, 1}};
            double d[3], sp[3];
            gl_ref_shade(sc, LUCENT_METHOD_LAMBERT, LUCENT_CDRF_KUBO, NULL, 3, &m, &p, d, sp);
            size_t i = (size_t)y * HS_W + (size_t)x;
            for (int c = 0; c < 3; c++) {
                out->tracer[k][c] += r.image->data[3 * i + c];
                out->var[k][c] += r.variance->data[3 * i + c];
                out->gl[k][c] += d[c];
            }
            out->pixels[k]++;
        }
    lucent_baked_free(&b);
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

/* The acceptance of issue 31: the real-time methods' light on a half-space within 3% of the path
 * tracer's per bin of view angle up to 80 degrees, for a translucent (Skin1) and a dense (marble)
 * material, roughness 0.01, 0.2 or 0.3, and 0.5, light along the normal and at 60 degrees. The bound is
 * 3% plus 2.5 standard errors of the comparison: the tracer's (its per-pixel variance, printed per bin)
 * and the baked table's (its relative standard error at this photon count, measured: 1.2% for Skin1 at
 * 2000 photons per incidence bin, 2% for marble at 2000, the table's rows scaled together). With 8000
 * photons per incidence bin and 64 spp (table se about 1%, a scratch run) the ratios were marble 0.949-1.038
 * (0.01, 0.2, 0.5) and Skin1 0.997-1.032 (0.3): blue about 2% high in every bin. */
TEST(halfspace_agrees_with_the_tracer)
{
    static const struct {
        const char *material;
        double roughness, light_deg, table_se;
        int spp;
        uint64_t photons;
    } cases[] = {{"skin1", 0.01, 0, 0.012, 64, 2000}, {"skin1", 0.3, 0, 0.012, 64, 2000},
                 {"skin1", 0.5, 0, 0.012, 64, 2000},  {"skin1", 0.3, 60, 0.012, 64, 2000},
                 {"marble", 0.01, 0, 0.02, 32, 2000}, {"marble", 0.2, 0, 0.02, 32, 2000},
                 {"marble", 0.5, 0, 0.02, 32, 2000},  {"marble", 0.2, 60, 0.02, 32, 2000}};
    lucent_pool *pool = lucent_pool_create(2);
    lucent_cache *cache = NULL; /* the two lights of a material and roughness share one table */
    CHECK_OK(lucent_cache_create(test_path("cache/halfspace"), &cache));
    double worst = 0;
    for (size_t k = 0; k < sizeof cases / sizeof cases[0]; k++) {
        if (SLOW > 1 && k != 1 && k != 5) continue; /* under the sanitizers one case per material */
        double a = cases[k].light_deg * M_PI / 180, light[3] = {0, -sin(a), -cos(a)};
        hs_bins h;
        uint64_t photons = cases[k].photons / SLOW;
        halfspace_case(cases[k].material, cases[k].roughness, light, cases[k].spp / SLOW, photons, pool, cache, &h);
        double table_se = cases[k].table_se * sqrt((double)SLOW);
        printf("     %s roughness %.2f light %2.0f deg, GL / tracer per view bin (R G B):", cases[k].material,
               cases[k].roughness, cases[k].light_deg);
        for (int j = 0; j < HS_BINS; j++) {
            printf(" %2.0f-%2.0f:", k_hs_edges[j], k_hs_edges[j + 1]);
            for (int c = 0; c < 3; c++) {
                double ratio = h.gl[j][c] / h.tracer[j][c], se = hypot(sqrt(h.var[j][c]) / h.tracer[j][c], table_se);
                printf(" %.3f+-%.3f", ratio, se);
                worst = fmax(worst, fabs(ratio - 1) / se);
                CHECK_MSG(h.pixels[j] > 0 && fabs(ratio - 1) <= 0.03 + 2.5 * se,
                          "%s %.2f light %.0f, %.0f-%.0f deg, channel %d: GL / tracer %.4f (se %.4f)",
                          cases[k].material, cases[k].roughness, cases[k].light_deg, k_hs_edges[j], k_hs_edges[j + 1],
                          c, ratio, se);
            }
        }
        printf("\n");
    }
    printf("     largest |GL / tracer - 1| over its standard error: %.2f\n", worst);
    lucent_cache_destroy(cache);
    lucent_pool_destroy(pool);
}

/* ---- a sphere: the curved parts' factor against the path tracer ---- */

enum { SP_W = 96, SP_H = 4, SP_BINS = 5 };
static const double k_sp_edges[SP_BINS + 1] = {10, 40, 70, 90, 110, 130}; /* theta, degrees from the light */

/* A Skin1 sphere of radius R seen along -z, lit along -x (the light from +x): the strip of SP_H rows
 * about its equator, theta from 0 (the lit limb) to 180 (the dark limb) across the image. Per bin of
 * theta and channel the tracer's radiance (subsurface only) and variance, and the real-time methods'
 * (the CPU reference of the surface pass with the curved parts' factor of the baked spheres, exact
 * normal and curvature 1 / R). */
static void sphere_case(double radius, int spp, uint64_t photons, lucent_pool *pool, double tracer[][3],
                        double var[][3], double gl[][3])
{
    double dist = 10 * radius, half = 1.1 * radius / dist * SP_H / SP_W, fov = 2 * atan(half) * 180 / M_PI;
    char json[1024];
    snprintf(json, sizeof json,
             "{\"camera\": {\"position\": [0, 0, %.17g], \"target\": [0, 0, 0], \"fov_y\": %.17g},"
             " \"lights\": [{\"type\": \"directional\", \"direction\": [-1, 0, 0], \"intensity\": 1}],"
             " \"objects\": [{\"mesh\": {\"primitive\": \"icosphere\", \"radius\": %.17g, \"subdivisions\": 6},"
             " \"material\": \"skin1\"}], \"render\": {\"width\": %d, \"height\": %d}}",
             dist, fov, radius, SP_W, SP_H);
    memset(tracer, 0, SP_BINS * sizeof *tracer), memset(var, 0, SP_BINS * sizeof *var);
    memset(gl, 0, SP_BINS * sizeof *gl);
    lucent_scene *sc = NULL;
    CHECK_OK(lucent_scene_parse(json, "sphere.json", NULL, NULL, &sc));
    if (!sc) return;
    lucent_tracer *tr = NULL;
    lucent_trace_result r = {0};
    CHECK_OK(lucent_tracer_create(sc, &(lucent_tracer_desc){.subsurface_only = true}, &tr));
    if (tr) CHECK_OK(lucent_tracer_render(tr, &(lucent_trace_desc){.spp = spp, .seed = 3, .pool = pool}, &r));
    const lucent_scene_object *o = &sc->objects[0];
    lucent_baked b = {0};
    CHECK_OK(lucent_material_bake(&o->material,
                                  &(lucent_bake_desc){.what = LUCENT_BAKE_SPHERES,
                                                      .roughness = o->roughness,
                                                      .boundary_photons = 2000,
                                                      .sphere_photons = photons,
                                                      .pool = pool},
                                  NULL, &b));
    gl_ref_material m = {.roughness = o->roughness,
                         .eta = o->material.eta,
                         .boundary = b.boundary,
                         .spheres = b.spheres,
                         .sphere_r0 = b.sphere_r0};
    memcpy(m.albedo, b.boundary_albedo, sizeof m.albedo);
    for (int y = 0; r.image && y < SP_H; y++)
        for (int x = 0; x < SP_W; x++) {
            size_t i = (size_t)y * SP_W + (size_t)x;
            double org[3], dir[3], bq, cq, disc;
            lucent_camera_ray(&sc->camera, SP_W, SP_H, x + 0.5, y + 0.5, org, dir);
            bq = org[0] * dir[0] + org[1] * dir[1] + org[2] * dir[2];
            cq = org[0] * org[0] + org[1] * org[1] + org[2] * org[2] - radius * radius, disc = bq * bq - cq;
            if (disc <= 0 || r.coverage->data[i] < 1) continue;
            double t = -bq - sqrt(disc);
            gl_ref_point p = {.curvature = 1 / radius};
            for (int c = 0; c < 3; c++) p.position[c] = org[c] + t * dir[c], p.normal[c] = p.position[c] / radius;
            double deg = acos(fmin(fmax(p.normal[0], -1), 1)) * 180 / M_PI;
            int k = 0;
            while (k < SP_BINS && deg >= k_sp_edges[k + 1]) k++;
            if (k == SP_BINS || deg < k_sp_edges[0]) continue;
            double d[3], sp[3];
            gl_ref_shade(sc, LUCENT_METHOD_CDRF, LUCENT_CDRF_KUBO, NULL, 3, &m, &p, d, sp);
            for (int c = 0; c < 3; c++) {
                tracer[k][c] += r.image->data[3 * i + c], var[k][c] += r.variance->data[3 * i + c];
                gl[k][c] += d[c];
            }
        }
    lucent_baked_free(&b);
    lucent_trace_result_free(&r);
    lucent_tracer_destroy(tr);
    lucent_scene_destroy(sc);
}

/* Issue 31's curved parts: the light of a Skin1 sphere along its equator against the tracer, radius 4
 * and 16 mm (the factor's table is baked from spheres of the same physics at other radii, read at
 * 1 / R between them). Printed per bin; the bound is 8% of the bin's light, or 3% of the brightest
 * bin's where that is more (past the terminator, where the light falls a hundredfold within 20
 * degrees and the table's 5-degree bins are read linearly), plus 2.5 standard errors of the tracer
 * and 3% for the tables' noise. Before the curved parts the methods were 0.56-0.80 of the tracer from
 * 65 to 95 degrees on a 10 mm sphere (bench_equator), and without the exit's lean down the surface
 * (beta) 0.84-0.93 on the lit side of the 4 mm sphere. */
TEST(sphere_agrees_with_the_tracer)
{
    static const double radii[2] = {4, 16};
    lucent_pool *pool = lucent_pool_create(2);
    for (int k = 0; k < 2; k++) {
        double tracer[SP_BINS][3], var[SP_BINS][3], gl[SP_BINS][3];
        sphere_case(radii[k], 48 / SLOW, 6000 / SLOW, pool, tracer, var, gl);
        printf("     Skin1 sphere R %.0f mm, GL / tracer per theta bin (R G B):", radii[k]);
        double peak[3] = {0, 0, 0};
        for (int j = 0; j < SP_BINS; j++)
            for (int c = 0; c < 3; c++) peak[c] = fmax(peak[c], tracer[j][c]);
        for (int j = 0; j < SP_BINS; j++) {
            printf(" %3.0f-%3.0f:", k_sp_edges[j], k_sp_edges[j + 1]);
            for (int c = 0; c < 3; c++) {
                double ratio = gl[j][c] / tracer[j][c], se = hypot(sqrt(var[j][c]) / tracer[j][c], 0.03 * sqrt(SLOW));
                double bound = fmax(0.08, 0.03 * peak[c] / tracer[j][c]) + 2.5 * se;
                printf(" %.3f", ratio);
                CHECK_MSG(fabs(ratio - 1) <= bound, "R %.0f, %.0f-%.0f deg, channel %d: GL / tracer %.3f (bound %.3f)",
                          radii[k], k_sp_edges[j], k_sp_edges[j + 1], c, ratio, bound);
            }
        }
        printf("\n");
    }
    lucent_pool_destroy(pool);
}

/* The sheet tables' unscattered light against the textbook slab: a non-scattering sheet with smooth faces
 * lit along its normal passes T^2 e^(-sigma s) / (1 - R^2 e^(-2 sigma s)) (Beer-Lambert through the slab,
 * Fresnel's normal-incidence R = ((eta - 1) / (eta + 1))^2 and T = 1 - R at both faces, the beam's internal
 * reflections summed as a geometric series), all of it along the normal (exit bin 0) and of order 0: no
 * diffuse rest. Matched faces (eta 1) give e^(-sigma s) exactly. Tolerance: 3 binomial standard errors of
 * the photon count (the entry face's reflect-or-refract choice is the only random step) and 1e-9. */
TEST(smooth_sheet_follows_fresnel_and_beer_lambert)
{
    enum { PHOTONS = 20000 };
    static const double etas[2] = {1.0, 1.4};
    lucent_sheet_result *r = malloc(sizeof *r);
    for (int e = 0; r && e < 2; e++) {
        lucent_material m = grey(0.5, 0, etas[e]);
        CHECK_OK(lucent_sheet_run(&(lucent_sheet_desc){.material = &m, .thickness = 1.0, .photons = PHOTONS}, r));
        double R = pow((etas[e] - 1) / (etas[e] + 1), 2), a = exp(-0.5 * 1.0);
        double expect = (1 - R) * (1 - R) * a / (1 - R * R * a * a);
        double tol = 3 * sqrt(expect * (1 - expect) / PHOTONS) + 1e-9, off_axis = 0, rest = 0;
        for (int c = 0; c < 3; c++) {
            for (int b = 1; b < LUCENT_SHEET_BINS; b++) off_axis += r->lobe[c][b];
            for (int b = 0; b < LUCENT_SHEET_BINS; b++) rest += r->diffuse[c][b];
            CHECK_MSG(fabs(r->total[c] - expect) <= tol, "eta %g channel %d: %.5f, expected %.5f (tolerance %.5f)",
                      etas[e], c, r->total[c], expect, tol);
            CHECK_MSG(r->lobe[c][0] > 0 && fabs(r->unscattered[c][0] - r->lobe[c][0]) <= 1e-12 * r->lobe[c][0],
                      "eta %g channel %d: bin 0 holds %g, unscattered %g", etas[e], c, r->lobe[c][0],
                      r->unscattered[c][0]);
        }
        CHECK_MSG(off_axis == 0 && rest == 0, "eta %g: %g off the normal, %g scattered", etas[e], off_axis, rest);
        printf("     eta %.1f: transmitted %.5f %.5f %.5f, expected %.5f\n", etas[e], r->total[0], r->total[1],
               r->total[2], expect);
    }
    free(r);
}

TEST(bad_input_is_named)
{
    lucent_material m = grey(0.1, 1, 1.4);
    lucent_boundary_result *r = malloc(sizeof *r);
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = &m, .roughness = 1.5}, r),
              LUCENT_ERR_INVALID_ARGUMENT, "grey", "roughness");
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = &m, .thickness = -1}, r),
              LUCENT_ERR_INVALID_ARGUMENT, "grey", "thickness");
    CHECK_ERR(lucent_boundary_run(&(lucent_boundary_desc){.material = NULL}, r), LUCENT_ERR_INVALID_ARGUMENT,
              "no material");
    free(r);
    lucent_sheet_result *t = malloc(sizeof *t);
    CHECK_ERR(lucent_sheet_run(&(lucent_sheet_desc){.material = &m, .thickness = 0}, t), LUCENT_ERR_INVALID_ARGUMENT,
              "grey", "thickness");
    CHECK_ERR(lucent_sheet_run(&(lucent_sheet_desc){.material = &m, .thickness = 1, .roughness = -0.1}, t),
              LUCENT_ERR_INVALID_ARGUMENT, "grey", "sheet tables", "roughness");
    CHECK_ERR(lucent_sheet_run(&(lucent_sheet_desc){.material = NULL, .thickness = 1}, t), LUCENT_ERR_INVALID_ARGUMENT,
              "no material");
    free(t);
}

TEST_MAIN(TEST_ENTRY(smooth_half_space_matches_giovanelli), TEST_ENTRY(half_space_keeps_energy),
          TEST_ENTRY(matched_slab_follows_beer_lambert), TEST_ENTRY(rough_half_space_is_reciprocal),
          TEST_ENTRY(bake_part_factors_the_table), TEST_ENTRY(halfspace_agrees_with_the_tracer),
          TEST_ENTRY(sphere_agrees_with_the_tracer), TEST_ENTRY(smooth_sheet_follows_fresnel_and_beer_lambert),
          TEST_ENTRY(bad_input_is_named))
