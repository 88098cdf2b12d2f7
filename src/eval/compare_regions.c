/* compare's regions: each object pixel classed by the surface seen through it (the tracer's probe),
 * the lights, the view and the mesh's curvature; and each method's error per region. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/vec3.h"
#include "eval/internal.h"
#include "lucent/mesh.h"

static const char *const k_region_names[LUCENT_COMPARE_REGION_COUNT] = {
    "lit", "terminator", "attached shadow", "cast shadow", "grazing view", "convex", "silhouette band"};

const char *lucent_compare_region_name(int region)
{
    return region >= 0 && region < LUCENT_COMPARE_REGION_COUNT ? k_region_names[region] : NULL;
}

/* The cosine of 75 degrees: the lit side ends and the terminator band begins (75 to 105 degrees, the
 * band docs/compare.md measured the methods in). */
#define COS75 0.25881904510252074

/* Per object of the scene, its mesh's mean curvature per vertex (NULL: not needed or no mesh). */
typedef struct curvatures {
    lucent_curvature *c;
    int count;
} curvatures;

static void curvatures_free(curvatures *cv)
{
    for (int i = 0; cv->c && i < cv->count; i++) lucent_curvature_free(&cv->c[i]);
    free(cv->c);
}

static lucent_status curvatures_make(const lucent_scene *scene, const lucent_trace_probe *probe, lucent_pool *pool,
                                     curvatures *dest)
{
    *dest = (curvatures){.c = calloc((size_t)(scene->object_count > 0 ? scene->object_count : 1), sizeof *dest->c),
                         .count = scene->object_count};
    if (!dest->c) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    bool *seen = calloc((size_t)(scene->object_count > 0 ? scene->object_count : 1), sizeof *seen);
    if (!seen) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (size_t i = 0; i < (size_t)probe->width * (size_t)probe->height; i++)
        if (probe->object[i] >= 0 && probe->object[i] < scene->object_count) seen[probe->object[i]] = true;
    lucent_status s = LUCENT_OK;
    for (int o = 0; o < scene->object_count && s == LUCENT_OK; o++) {
        const lucent_mesh *m = scene->objects[o].mesh;
        if (!seen[o] || !m || !m->face_count) continue;
        /* the meshes are in world millimetres already: curvature in mm^-1 */
        s = lucent_mesh_curvature(m, &(lucent_curvature_desc){.mm_per_unit = 1, .pool = pool, .fast = 1}, &dest->c[o]);
    }
    free(seen);
    return s;
}

/* The shading normal and the mean curvature at pixel i, from the mesh's vertices and the hit's
 * barycentrics (the geometric normal where the mesh has no normals). */
static void surface_at(const lucent_scene *scene, const curvatures *cv, const lucent_trace_probe *p, size_t i, v3 *n,
                       double *mean)
{
    *n = v3_make(p->normal[3 * i], p->normal[3 * i + 1], p->normal[3 * i + 2]);
    *mean = 0;
    int o = p->object[i], t = p->triangle[i];
    const lucent_mesh *m = o >= 0 && o < scene->object_count ? scene->objects[o].mesh : NULL;
    if (!m || t < 0 || (size_t)t >= m->face_count) return;
    double w[3] = {1.0 - p->bary[2 * i] - p->bary[2 * i + 1], p->bary[2 * i], p->bary[2 * i + 1]};
    v3 s = v3_make(0, 0, 0);
    for (int k = 0; k < 3; k++) {
        uint32_t v = m->faces[3 * (size_t)t + (size_t)k];
        if (m->normals) s = v3_madd(s, v3_load(m->normals + 3 * (size_t)v), w[k]);
        if (cv->c[o].mean) *mean += w[k] * cv->c[o].mean[v];
    }
    v3 sn = v3_normalize(s);
    if (v3_dot(sn, sn) > 0.5) *n = sn;
}

/* Whether pixel (x, y) lies within 3 pixels of one that the object does not cover (coverage < 0.5). */
static bool near_outline(const lucent_image *coverage, int x, int y)
{
    for (int dy = -3; dy <= 3; dy++)
        for (int dx = -3; dx <= 3; dx++) {
            if (dx * dx + dy * dy > 9) continue;
            int u = x + dx, v = y + dy;
            if (u < 0 || v < 0 || u >= coverage->width || v >= coverage->height) return true;
            if (lucent_image_get(coverage, u, v, 0) < 0.5f) return true;
        }
    return false;
}

/* The light bits of pixel i: lit, terminator, attached shadow, cast shadow (as the region order). */
static unsigned light_bits(const lucent_scene *scene, const lucent_trace_probe *p, const bool *on, size_t i, v3 pos,
                           v3 n)
{
    bool lit = false, term = false, cast = false, any = false, all_behind = true;
    for (int k = 0; k < scene->light_count && k < p->light_count; k++) {
        const lucent_light *l = &scene->lights[k];
        if ((on && !on[k]) || l->type == LUCENT_LIGHT_ENVIRONMENT || !(l->intensity > 0)) continue;
        v3 w = l->type == LUCENT_LIGHT_DIRECTIONAL ? v3_normalize(v3_neg(v3_load(l->direction)))
                                                   : v3_normalize(v3_sub(v3_load(l->position), pos));
        double c = v3_dot(n, w);
        bool free = p->unoccluded[i * (size_t)p->light_count + (size_t)k];
        any = true;
        lit |= c > COS75 && free;
        term |= fabs(c) <= COS75;
        cast |= c > COS75 && !free;
        all_behind &= c < -COS75;
    }
    if (!any) return 0;
    if (lit) return 1u << LUCENT_COMPARE_REGION_LIT;
    if (term) return 1u << LUCENT_COMPARE_REGION_TERMINATOR;
    if (cast) return 1u << LUCENT_COMPARE_REGION_CAST_SHADOW;
    return all_behind ? 1u << LUCENT_COMPARE_REGION_ATTACHED_SHADOW : 0;
}

lucent_status lucent_compare_regions(const lucent_scene *scene, const lucent_trace_probe *probe,
                                     const lucent_image *coverage, const float *mask, const bool *lights_on,
                                     lucent_pool *pool, uint8_t *dest)
{
    size_t n = (size_t)probe->width * (size_t)probe->height;
    memset(dest, 0, n);
    if (coverage->width != probe->width || coverage->height != probe->height)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: regions: the coverage is %dx%d, the probe %dx%d",
                            coverage->width, coverage->height, probe->width, probe->height);
    curvatures cv;
    lucent_status s = curvatures_make(scene, probe, pool, &cv);
    v3 eye = v3_load(scene->camera.position);
    for (size_t i = 0; s == LUCENT_OK && i < n; i++) {
        if ((mask && !(mask[i] > 0.5f)) || probe->object[i] < 0) continue;
        int x = (int)(i % (size_t)probe->width), y = (int)(i / (size_t)probe->width);
        v3 pos = v3_make(probe->position[3 * i], probe->position[3 * i + 1], probe->position[3 * i + 2]), nrm;
        double mean;
        surface_at(scene, &cv, probe, i, &nrm, &mean);
        unsigned bits = light_bits(scene, probe, lights_on, i, pos, nrm);
        if (v3_dot(nrm, v3_normalize(v3_sub(eye, pos))) < COS75) bits |= 1u << LUCENT_COMPARE_REGION_GRAZING;
        if (mean >= 1.0 / LUCENT_COMPARE_CONVEX_RADIUS_MM) bits |= 1u << LUCENT_COMPARE_REGION_CONVEX;
        if (near_outline(coverage, x, y)) bits |= 1u << LUCENT_COMPARE_REGION_SILHOUETTE;
        dest[i] = (uint8_t)bits;
    }
    curvatures_free(&cv);
    return s;
}

lucent_status lucent_compare_region_measure(const uint8_t *bits, int region, const float *mask,
                                            const lucent_image *reference, const lucent_image *variance,
                                            const lucent_image *image, lucent_compare_region_values *dest)
{
    *dest = (lucent_compare_region_values){
        .rel_rms = NAN, .ratio = NAN, .error_share = NAN, .energy = NAN, .reference_noise = NAN};
    if (image->width != reference->width || image->height != reference->height || image->channels < 3 ||
        reference->channels < 3 ||
        (variance &&
         (variance->width != reference->width || variance->height != reference->height || variance->channels < 3)))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "compare: region: images of different sizes");
    double e2 = 0, r2 = 0, sm = 0, sr = 0, e2_all = 0, r2_all = 0, v = 0;
    uint64_t pixels = 0;
    for (size_t i = 0; i < (size_t)reference->width * (size_t)reference->height; i++) {
        if (mask && !(mask[i] > 0.5f)) continue;
        bool in = bits[i] & (1u << region);
        pixels += in;
        for (int c = 0; c < 3; c++) {
            double r = reference->data[i * (size_t)reference->channels + (size_t)c],
                   m = image->data[i * (size_t)image->channels + (size_t)c], d = (m - r) * (m - r);
            e2_all += d, r2_all += r * r;
            if (!in) continue;
            e2 += d, r2 += r * r, sm += m, sr += r;
            if (variance) v += variance->data[i * (size_t)variance->channels + (size_t)c];
        }
    }
    dest->pixels = pixels;
    if (!pixels) return LUCENT_OK;
    dest->rel_rms = r2 > 0 ? sqrt(e2 / r2) : NAN;
    dest->ratio = sr != 0 ? sm / sr : NAN;
    dest->error_share = e2_all > 0 ? e2 / e2_all : 0;
    dest->energy = r2_all > 0 ? r2 / r2_all : NAN;
    dest->reference_noise = variance && r2 > 0 ? sqrt(v / r2) : NAN;
    return LUCENT_OK;
}
