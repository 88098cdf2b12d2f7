/* Engine packs (lucent/pack.h, docs/pack.md): the bake, the screen's numbers, the tables (EXR, 16-bit
 * PNG, CSV), constants.json, and the calls that write the shaders, the glTF and the README. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/vec3.h"
#include "engine/internal.h"
#include "lucent/image.h"

static const char *const k_engines[] = {"glsl", "gles", "vulkan", "hlsl", "json"};

const char *lucent_pack_engine_name(lucent_pack_engine e)
{
    return e >= 0 && e < LUCENT_PACK_ENGINE_COUNT ? k_engines[e] : "unknown";
}

lucent_status lucent_pack_engine_find(const char *name, lucent_pack_engine *dest)
{
    for (int e = 0; e < LUCENT_PACK_ENGINE_COUNT; e++)
        if (!strcasecmp(name, k_engines[e])) return *dest = (lucent_pack_engine)e, LUCENT_OK;
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "unknown engine '%s' (glsl, gles, vulkan, hlsl, json)", name);
}

lucent_pack_desc lucent_pack_defaults(void)
{
    return (lucent_pack_desc){.screen_width = 1920,
                              .screen_height = 1080,
                              .fov_y = 45,
                              .object_height_mm = 1800,
                              .lut_width = 64,
                              .lut_height = 64,
                              .kappa_max = 1,
                              .roughness = 0.3};
}

static lucent_status resolve(const lucent_pack_desc *in, lucent_pack_desc *d)
{
    lucent_pack_desc def = lucent_pack_defaults();
    *d = *in;
#define DEF(field)                                                                                                     \
    if (!d->field) d->field = def.field
    DEF(screen_width);
    DEF(screen_height);
    DEF(fov_y);
    DEF(object_height_mm);
    DEF(lut_width);
    DEF(lut_height);
    DEF(kappa_max);
    DEF(roughness);
#undef DEF
    if (!d->out || !d->out[0]) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: no output folder");
    if (!(d->engine >= 0 && d->engine < LUCENT_PACK_ENGINE_COUNT))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: engine %d: no such engine", (int)d->engine);
    if (d->screen_width < 1 || d->screen_height < 1 || d->screen_width > 65536 || d->screen_height > 65536)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: screen %dx%d: each must be in 1..65536",
                            d->screen_width, d->screen_height);
    if (!(d->fov_y > 0 && d->fov_y < 180))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: fov_y %g: must be in (0, 180) degrees", d->fov_y);
    if (!(d->object_height_mm > 0 && d->object_height_mm < 1e12) || !(d->distance_mm >= 0 && d->distance_mm < 1e12))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: object height %g mm, distance %g mm: must be > 0",
                            d->object_height_mm, d->distance_mm);
    if (d->lut_width < 2 || d->lut_height < 2 || d->lut_width > 4096 || d->lut_height > 4096)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: LUT %dx%d: each must be in 2..4096", d->lut_width,
                            d->lut_height);
    if (!(d->kappa_max > 0 && d->kappa_max < 1e12))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: kappa_max %g: must be > 0", d->kappa_max);
    if (d->fit_photons > 1000000000000ull || d->fit_model_photons > 1000000000000ull)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: fit photons %llu, model photons %llu: at most 1e12",
                            (unsigned long long)d->fit_photons, (unsigned long long)d->fit_model_photons);
    if (!(d->roughness > 0 && d->roughness <= 1))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: roughness %g: must be in (0, 1]", d->roughness);
    return LUCENT_OK;
}

/* ---- text files ---- */

typedef struct text {
    char *data;
    size_t size;
    FILE *f;
} text;

static lucent_status text_open(text *t)
{
    *t = (text){0};
    return (t->f = open_memstream(&t->data, &t->size)) ? LUCENT_OK
                                                       : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "pack: out of memory");
}

static void join(const pack_ctx *p, const char *name, char *dest, size_t size)
{
    snprintf(dest, size, "%s/%s", p->d.out, name);
}

static lucent_status text_write(text *t, pack_ctx *p, const char *name)
{
    char path[4200];
    join(p, name, path, sizeof path);
    lucent_status s = fclose(t->f) == 0 ? lucent_write_file(path, t->data, t->size)
                                        : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    free(t->data);
    *t = (text){0};
    if (s == LUCENT_OK) p->r.file_count++;
    return s;
}

typedef void (*writer)(FILE *f, const pack_ctx *p);

static lucent_status write_text(pack_ctx *p, const char *name, writer w)
{
    text t;
    lucent_status s = text_open(&t);
    if (s != LUCENT_OK) return s;
    w(t.f, p);
    return text_write(&t, p, name);
}

/* ---- tables ---- */

static void taps_file(FILE *f, const pack_ctx *p) { fputs(p->taps_text, f); }

static void transmittance_csv(FILE *f, const pack_ctx *p)
{
    fprintf(f, "s_mm,t_r,t_g,t_b\n");
    for (int j = 0; j < LUCENT_BAKE_TRANSMIT_SIZE; j++)
        fprintf(f, "%.9g,%.9g,%.9g,%.9g\n", p->b->transmit_range * j / (LUCENT_BAKE_TRANSMIT_SIZE - 1),
                p->b->transmittance[3 * j], p->b->transmittance[3 * j + 1], p->b->transmittance[3 * j + 2]);
}

/* Kubo's CDRF (Eq. 1-4) at sigma = sigma0_c kappa: column i cos theta = -1 + 2 i / (w - 1), row j (from
 * the top) kappa = kappa_max j / (h - 1). */
static lucent_status cdrf_lut(const pack_ctx *p, lucent_image **dest)
{
    lucent_cdrf_variant v = (lucent_cdrf_variant)p->rs->cdrf.variant;
    int w = p->d.lut_width, h = p->d.lut_height;
    lucent_status s = lucent_image_create(w, h, 3, dest);
    for (int j = 0; s == LUCENT_OK && j < h; j++) {
        double kappa = p->d.kappa_max * j / (h - 1);
        for (int i = 0; i < w; i++) {
            double theta = acos(fmin(fmax(-1 + 2.0 * i / (w - 1), -1), 1));
            for (int c = 0; c < 3; c++)
                lucent_image_set(*dest, i, j, c,
                                 (float)lucent_cdrf_eval(v, theta, lucent_cdrf_sigma(p->b->sigma0[c], kappa)));
        }
    }
    return s;
}

static lucent_status write_image(pack_ctx *p, const char *name, const lucent_image *img, bool png16)
{
    char path[4200];
    join(p, name, path, sizeof path);
    lucent_image_write_desc wd = lucent_image_write_defaults();
    if (png16) wd.png_bits = 16, wd.png_linear = true;
    lucent_status s = lucent_image_write(path, img, &wd);
    if (s == LUCENT_OK) p->r.file_count++;
    return s;
}

/* The LUT as EXR (float) and as 16-bit linear PNG of value / scale, scale the LUT's largest value
 * rounded up to a power of two (at least 1), for engines without EXR. */
static lucent_status lut_files(pack_ctx *p)
{
    lucent_image *lut = NULL, *scaled = NULL;
    lucent_status s = cdrf_lut(p, &lut);
    if (s == LUCENT_OK) s = write_image(p, "cdrf-lut.exr", lut, false);
    double most = 0;
    for (int j = 0; s == LUCENT_OK && j < p->d.lut_height; j++)
        for (int i = 0; i < p->d.lut_width; i++)
            for (int c = 0; c < 3; c++) most = fmax(most, lucent_image_get(lut, i, j, c));
    p->lut_png_scale = 1;
    while (p->lut_png_scale < most && p->lut_png_scale < 1e30) p->lut_png_scale *= 2;
    if (s == LUCENT_OK) s = lucent_image_create(p->d.lut_width, p->d.lut_height, 3, &scaled);
    for (int j = 0; s == LUCENT_OK && j < p->d.lut_height; j++)
        for (int i = 0; i < p->d.lut_width; i++)
            for (int c = 0; c < 3; c++)
                lucent_image_set(scaled, i, j, c, (float)(lucent_image_get(lut, i, j, c) / p->lut_png_scale));
    if (s == LUCENT_OK) s = write_image(p, "cdrf-lut.png", scaled, true);
    lucent_image_destroy(scaled);
    lucent_image_destroy(lut);
    lucent_image *t = NULL;
    if (s == LUCENT_OK) s = lucent_image_create(LUCENT_BAKE_TRANSMIT_SIZE, 1, 3, &t);
    for (int j = 0; s == LUCENT_OK && j < LUCENT_BAKE_TRANSMIT_SIZE; j++)
        for (int c = 0; c < 3; c++) lucent_image_set(t, j, 0, c, p->b->transmittance[3 * j + c]);
    if (s == LUCENT_OK) s = write_image(p, "transmittance.png", t, true);
    lucent_image_destroy(t);
    return s;
}

/* ---- constants.json ---- */

static void json_triple(FILE *f, const char *key, const double v[3])
{
    fprintf(f, "  \"%s\": [%.9g, %.9g, %.9g],\n", key, v[0], v[1], v[2]);
}

static void constants_json(FILE *f, const pack_ctx *p)
{
    const lucent_taps *t = p->b->taps;
    const lucent_material *m = p->m;
    const lucent_render_settings *rs = p->rs;
    fprintf(f, "{\n  \"lucent\": \"%s\",\n  \"material\": \"%s\",\n  \"engine\": \"%s\",\n", LUCENT_VERSION_STRING,
            m->name, lucent_pack_engine_name(p->d.engine));
    json_triple(f, "sigma_a_per_mm", m->sigma_a);
    json_triple(f, "sigma_s_per_mm", m->sigma_s);
    json_triple(f, "sigma_t_per_mm", p->derived.sigma_t);
    json_triple(f, "albedo", p->derived.albedo);
    json_triple(f, "g", m->g);
    fprintf(f, "  \"eta\": %.9g,\n", m->eta);
    json_triple(f, "diffuse_rd", p->derived.rd);
    fprintf(
        f, "  \"kernel\": {\"model\": \"%s\", \"rank\": %d, \"taps\": %d, \"profile\": \"%s\", \"radius_mm\": %.9g},\n",
        lucent_kernel_model_name((lucent_kernel_model)rs->ssss.kernel), t->rank, t->count, rs->ssss.profile,
        p->r.radius_mm);
    fprintf(f,
            "  \"screen\": {\"width_px\": %d, \"height_px\": %d, \"fov_y_deg\": %.9g, \"depth_mm\": %.9g, "
            "\"pixels_per_mm_at_1mm\": %.9g, \"pixels_per_mm\": %.9g, \"kernel_width_px\": %.9g},\n",
            p->d.screen_width, p->d.screen_height, p->d.fov_y, p->r.depth_mm, p->r.pixels_per_mm_at_1mm,
            p->r.pixels_per_mm, p->r.width_px);
    fprintf(f,
            "  \"cdrf\": {\"variant\": \"%s\", \"sigma0_mm\": [%.9g, %.9g, %.9g], \"kd\": [%.9g, %.9g, %.9g], "
            "\"lut\": \"cdrf-lut.exr\", \"lut_png\": \"cdrf-lut.png\", \"lut_png_scale\": %.9g, \"lut_width\": %d, "
            "\"lut_height\": %d, \"kappa_max_per_mm\": %.9g, \"columns\": \"cos theta from -1 to 1\", "
            "\"rows\": \"kappa from 0 (top row) to kappa_max\"},\n",
            lucent_cdrf_variant_name((lucent_cdrf_variant)rs->cdrf.variant), p->b->sigma0[0], p->b->sigma0[1],
            p->b->sigma0[2], p->b->kd[0], p->b->kd[1], p->b->kd[2], p->lut_png_scale, p->d.lut_width, p->d.lut_height,
            p->d.kappa_max);
    fprintf(f,
            "  \"translucency\": {\"model\": \"%s\", \"range_mm\": %.9g, \"samples\": %d, \"table\": "
            "\"transmittance.csv\", \"table_png\": \"transmittance.png\"},\n",
            lucent_transmittance_name(rs->translucency.transmittance), p->b->transmit_range, LUCENT_BAKE_TRANSMIT_SIZE);
    fprintf(f, "  \"gltf\": {\"file\": \"material.gltf\", \"thickness_m\": %.9g, \"roughness_alpha\": %.9g}\n}\n",
            p->r.thickness_m, p->d.roughness);
}

/* ---- the glTF's mesh ---- */

/* The mesh centred on its bounding box and scaled so that its height (y extent; the largest extent
 * of a flat one) is height_mm; NULL src: an icosphere of that diameter. */
static lucent_status pack_mesh(const lucent_mesh *src, double height_mm, lucent_mesh **dest)
{
    if (!src)
        return lucent_mesh_primitive(
            &(lucent_primitive_desc){.kind = LUCENT_PRIMITIVE_ICOSPHERE, .radius = height_mm / 2, .subdivisions = 3},
            dest);
    lucent_status s = lucent_mesh_create(src->vertex_count, src->face_count, dest);
    if (s != LUCENT_OK) return s;
    lucent_mesh *m = *dest;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t v = 0; v < src->vertex_count; v++)
        for (int k = 0; k < 3; k++)
            lo[k] = fmin(lo[k], src->positions[3 * v + k]), hi[k] = fmax(hi[k], src->positions[3 * v + k]);
    double extent = hi[1] - lo[1] > 0 ? hi[1] - lo[1] : fmax(hi[0] - lo[0], hi[2] - lo[2]);
    if (!(extent > 0 && isfinite(extent))) {
        lucent_mesh_destroy(m), *dest = NULL;
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "pack: the mesh has no extent");
    }
    for (size_t v = 0; v < src->vertex_count; v++)
        for (int k = 0; k < 3; k++)
            m->positions[3 * v + k] = (src->positions[3 * v + k] - 0.5 * (lo[k] + hi[k])) * height_mm / extent;
    memcpy(m->faces, src->faces, 3 * src->face_count * sizeof *m->faces);
    lucent_mesh_compute_normals(m);
    return LUCENT_OK;
}

/* The mean chord length of a closed body, 4 V / A (Cauchy), in mm; for an open or flat mesh whose
 * volume says nothing, the height. */
static double mean_chord(const lucent_mesh *m, double height_mm)
{
    double volume = 0, area = 0;
    for (size_t f = 0; f < m->face_count; f++) {
        const uint32_t *t = m->faces + 3 * f;
        v3 a = v3_load(m->positions + 3 * t[0]), b = v3_load(m->positions + 3 * t[1]),
           c = v3_load(m->positions + 3 * t[2]);
        volume += v3_dot(a, v3_cross(b, c)) / 6;
        area += 0.5 * v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
    }
    double chord = 4 * volume / area;
    return chord > 0 && chord <= 2 * height_mm ? chord : height_mm;
}

/* ---- the pack ---- */

static lucent_status write_all(pack_ctx *p, const lucent_mesh *mesh)
{
    static const lucent_kernel_format formats[] = {LUCENT_KERNEL_GLSL, LUCENT_KERNEL_GLSL, LUCENT_KERNEL_GLSL,
                                                   LUCENT_KERNEL_HLSL, LUCENT_KERNEL_JSON};
    static const char *const tap_names[] = {"taps.glsl", "taps.glsl", "taps.glsl", "taps.hlsl", "taps.json"};
    lucent_pack_engine e = p->d.engine;
    char label[160], *taps = NULL, path[4200];
    snprintf(label, sizeof label, "%s, %s rank %d", p->m->name,
             lucent_kernel_model_name((lucent_kernel_model)p->rs->ssss.kernel), p->b->taps->rank);
    lucent_status s = lucent_taps_export(p->b->taps, formats[e], label, &taps);
    p->taps_text = taps;
    if (s == LUCENT_OK) s = lucent_mkdir_p(p->d.out);
    if (s == LUCENT_OK) s = write_text(p, tap_names[e], taps_file);
    bool hlsl = e == LUCENT_PACK_HLSL;
    if (s == LUCENT_OK && e != LUCENT_PACK_JSON) {
        s = write_text(p, hlsl ? "blur.hlsl" : "blur.frag.glsl", pack_blur);
        if (s == LUCENT_OK) s = write_text(p, hlsl ? "cdrf.hlsl" : "cdrf.glsl", pack_cdrf);
        if (s == LUCENT_OK) s = write_text(p, hlsl ? "translucency.hlsl" : "translucency.glsl", pack_translucency);
    }
    if (s == LUCENT_OK) s = write_text(p, "transmittance.csv", transmittance_csv);
    if (s == LUCENT_OK) s = lut_files(p);
    join(p, "material.gltf", path, sizeof path);
    if (s == LUCENT_OK && (s = pack_gltf(p, mesh, path)) == LUCENT_OK) p->r.file_count++;
    if (s == LUCENT_OK) s = write_text(p, "constants.json", constants_json);
    if (s == LUCENT_OK) s = write_text(p, "README.md", pack_readme);
    free(taps);
    p->taps_text = NULL;
    return s;
}

lucent_status lucent_pack(const lucent_material *m, const lucent_pack_desc *desc, lucent_pack_result *result)
{
    pack_ctx p = {.m = m};
    lucent_render_settings rs = desc && desc->settings ? *desc->settings : lucent_render_settings_defaults();
    lucent_pack_desc zero = {0};
    lucent_status s = resolve(desc ? desc : &zero, &p.d);
    if (s == LUCENT_OK) s = lucent_material_validate(m);
    if (s == LUCENT_OK) s = lucent_render_settings_check(&rs);
    if (s != LUCENT_OK) return s;
    p.rs = &rs;
    lucent_material_derive(m, &p.derived);
    lucent_baked b = {0};
    lucent_bake_desc bd = {.what = LUCENT_BAKE_TAPS | LUCENT_BAKE_TRANSMITTANCE | LUCENT_BAKE_SIGMA0,
                           .settings = &rs,
                           .sigma0_photons = p.d.sigma0_photons,
                           .transmit_photons = p.d.transmit_photons,
                           .pool = p.d.pool};
    lucent_mesh *mesh = NULL;
    s = pack_mesh(p.d.mesh, p.d.object_height_mm, &mesh); /* before the bake: a bad mesh fails at once */
    if (s == LUCENT_OK) s = lucent_material_bake(m, &bd, p.d.cache, &b);
    lucent_engine_report fit = {0};
    if (s == LUCENT_OK && !p.d.no_fit) {
        lucent_engine_report_desc fd = {.target = {.material = m,
                                                   .photons = p.d.fit_photons,
                                                   .total_photons = 2 * p.d.fit_photons,
                                                   .pool = p.d.pool,
                                                   .cache = p.d.cache},
                                        .fit = {.model_photons = p.d.fit_model_photons, .pool = p.d.pool}};
        s = lucent_engine_report_run(&fd, &fit);
        if (s != LUCENT_OK)
            s = lucent_error_context(s, "pack: the engines' fitted parameters (no_fit leaves them out)");
        p.fit = &fit;
    }
    if (s == LUCENT_OK) {
        p.b = &b;
        p.r.radius_mm = lucent_taps_radius(b.taps);
        p.r.depth_mm = p.d.distance_mm > 0 ? p.d.distance_mm : lucent_screen_depth_mm(p.d.object_height_mm, p.d.fov_y);
        p.r.pixels_per_mm = lucent_screen_pixels_per_mm(p.d.screen_height, p.d.fov_y, p.r.depth_mm);
        p.r.pixels_per_mm_at_1mm = lucent_screen_pixels_per_mm(p.d.screen_height, p.d.fov_y, 1);
        p.r.width_px = 2 * p.r.radius_mm * p.r.pixels_per_mm;
        p.r.thickness_m = mean_chord(mesh, p.d.object_height_mm) / 1000;
        s = write_all(&p, mesh);
    }
    lucent_mesh_destroy(mesh);
    lucent_baked_free(&b);
    lucent_engine_report_free(&fit);
    if (s == LUCENT_OK && result) *result = p.r;
    return s;
}
