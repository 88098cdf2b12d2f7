/* `lucent pack`: everything an engine needs for one material, in one folder (issue 16 item 3, issue 30
 * items 3 and 4). Parsing and printing only: the pack is the library's (lucent/pack.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/kernel.h"
#include "lucent/pack.h"

static const char k_usage[] =
    "usage: lucent pack MATERIAL --engine glsl|gles|vulkan|hlsl|json [options]\n"
    "\n"
    "Writes into one folder (--out, default MATERIAL-ENGINE) what an engine needs to render\n"
    "MATERIAL as `lucent render` does, and prints the kernel's width in pixels on the screen:\n"
    "  README.md               the passes in order, their buffers, the kernel width, thickness and\n"
    "                          curvature at run time, the composition with the specular\n"
    "  taps.glsl|.hlsl|.json   the separable kernel's taps (offsets in mm; lucent kernel's export)\n"
    "  blur.frag.glsl|blur.hlsl  a complete 1-D blur pass: kernel width from depth and field of\n"
    "                          view, Jimenez's follow-surface depth test (shader engines)\n"
    "  cdrf.glsl|cdrf.hlsl     the CDRF shading snippet reading the LUT (shader engines)\n"
    "  translucency.glsl|.hlsl T(s) as a constant table and its lookup (shader engines)\n"
    "  cdrf-lut.exr, .png      RGB float and 16-bit: columns cos theta in [-1, 1], rows curvature in\n"
    "                          [0, kappa_max] 1/mm from the top row; channel c is the CDRF of\n"
    "                          sigma = sigma0_c kappa (Kubo Eq. 1-4)\n"
    "  transmittance.csv, .png T(s) per channel, s in mm\n"
    "  constants.json          every number above, the material and the screen\n"
    "  material.gltf           a glTF 2.0 scene: a mesh in the material (KHR_materials_transmission,\n"
    "                          _volume, _diffuse_transmission, _ior, the draft _volume_scatter, the\n"
    "                          exact medium under extras.lucent), a camera and a key light\n"
    "README.md also holds each engine's parameters fitted to MATERIAL (as `lucent fit`: Unreal,\n"
    "Unity HDRP, Blender, OpenPBR, Godot, glTF, each with its error against the Monte Carlo truth).\n"
    "MATERIAL is a preset name (see 'lucent materials'), FILE.json or FILE.json#NAME.\n"
    "\n"
    "options:\n"
    "  --engine E          glsl (GLSL 4.50), gles (GLSL ES 3.00, WebGL2), vulkan (Vulkan GLSL for\n"
    "                      SPIR-V), hlsl (shader model 5) or json (data only)\n"
    "  --screen WxH        the screen in pixels (default 1920x1080)\n"
    "  --fov DEG           vertical field of view in degrees (default 45)\n"
    "  --object-height H   the object's height (default 1.8m; with its unit: m, cm or mm); the printed\n"
    "                      width is for the object filling the screen's height; the glTF's mesh\n"
    "  --distance D        instead: the object's depth from the camera (with its unit: m, cm or mm)\n"
    "  --mesh FILE         the glTF's mesh (PLY, OBJ, ...; centred, scaled to --object-height;\n"
    "                      default: a sphere)\n"
    "  --set KEY=VALUE     a render setting (docs/scenes.md): kernel, taps, profile,\n"
    "                      transmittance, cdrf_variant, ... (default: the renderer's)\n"
    "  --kappa-max K       the LUT's largest curvature, 1/mm (default 1: a sphere of 1 mm)\n"
    "  --lut-size WxH      the LUT's size (default 64x64)\n"
    "  --sigma0-photons N  photons per channel and sphere of the sigma0 fit (default 40000)\n"
    "  --transmit-photons N  photons per channel and thickness of T(s) (default 20000)\n"
    "  --fit-photons N     the README's engine fit: the truth's photons per channel (default:\n"
    "                      lucent fit's: 200000, and the bake's Rd for T, cached)\n"
    "  --fit-model-photons N  the random-walk and glTF models' photons (default 50000)\n"
    "  --no-fit            leave the engine fit out of the README\n"
    "  --out DIR           the folder (created; default MATERIAL-ENGINE)\n"
    "  --cache DIR         where sigma0 fits and slab tables are kept (as lucent render)\n"
    "  --no-cache          do not read or write that cache\n"
    "\n"
    "example:\n"
    "  lucent pack marble --engine glsl --screen 1920x1080 --fov 45 --object-height 0.3m --out out/marble-pack\n";

enum { MAX_SETS = 32 };

typedef struct options {
    const char *spec, *out, *cache, *mesh;
    const char *sets[MAX_SETS];
    int set_count, lut_w, lut_h;
    lucent_pack_engine engine;
    cli_view view;
    double kappa_max;
    int sigma0_photons, transmit_photons; /* 0: the bake's defaults (the renderer's) */
    int fit_photons, fit_model_photons;   /* 0: lucent fit's defaults */
    bool no_cache, have_engine, no_fit;
} options;

static int usage(const char *fmt, const char *v) { return cli_usage_error("pack", fmt, v ? v : ""); }

static int parse_valued(options *o, const char *name, const char *v)
{
    if (!v) return usage("%s needs a value", name);
    if (!strcmp(name, "--engine")) {
        o->have_engine = true;
        return lucent_pack_engine_find(v, &o->engine) == LUCENT_OK
                   ? CLI_OK
                   : usage("unknown engine '%s' (glsl, gles, vulkan, hlsl, json)", v);
    }
    if (!strcmp(name, "--lut-size"))
        return cli_parse_size(v, &o->lut_w, &o->lut_h) && o->lut_w >= 2 && o->lut_h >= 2 && o->lut_w <= 4096 &&
                       o->lut_h <= 4096
                   ? CLI_OK
                   : usage("--lut-size needs WxH, 2..4096 each, got '%s'", v);
    if (!strcmp(name, "--kappa-max"))
        return cli_parse_double(v, &o->kappa_max) && o->kappa_max > 0
                   ? CLI_OK
                   : usage("--kappa-max needs a number > 0 (1/mm), got '%s'", v);
    if (!strcmp(name, "--sigma0-photons") || !strcmp(name, "--transmit-photons"))
        return cli_parse_int(v, name[2] == 's' ? &o->sigma0_photons : &o->transmit_photons) &&
                       (name[2] == 's' ? o->sigma0_photons : o->transmit_photons) > 0
                   ? CLI_OK
                   : usage("%s needs a whole number > 0", name);
    if (!strcmp(name, "--fit-photons") || !strcmp(name, "--fit-model-photons")) {
        int *dest = name[6] == 'p' ? &o->fit_photons : &o->fit_model_photons;
        return cli_parse_int(v, dest) && *dest > 0 ? CLI_OK : usage("%s needs a whole number > 0", name);
    }
    if (!strcmp(name, "--set")) {
        if (o->set_count == MAX_SETS) return usage("at most 32 --set%s", "");
        o->sets[o->set_count++] = v;
        return CLI_OK;
    }
    if (!strcmp(name, "--cache")) return (o->cache = v), CLI_OK;
    if (!strcmp(name, "--mesh")) return (o->mesh = v), CLI_OK;
    return (o->out = v), CLI_OK; /* --out */
}

static int parse_args(int argc, char **argv, options *o)
{
    static const char *const valued[] = {
        "--engine",          "--lut-size",       "--set",  "--cache",       "--out",
        "--kappa-max",       "--sigma0-photons", "--mesh", "--fit-photons", "--fit-model-photons",
        "--transmit-photons"};
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int matched = -1;
        for (int n = 0; n < (int)(sizeof valued / sizeof valued[0]) && matched < 0; n++)
            if (cli_option(argc, argv, &i, valued[n], &v)) matched = n;
        int view = matched < 0 ? cli_view_option("pack", argc, argv, &i, &o->view) : -1;
        if (view == CLI_USAGE) return CLI_USAGE;
        if (view == CLI_OK) continue;
        if (matched >= 0) {
            int rc = parse_valued(o, valued[matched], v);
            if (rc != CLI_OK) return rc;
        } else if (!strcmp(argv[i], "--no-cache")) {
            o->no_cache = true;
        } else if (!strcmp(argv[i], "--no-fit")) {
            o->no_fit = true;
        } else if (argv[i][0] == '-') {
            return usage("unknown option '%s'", argv[i]);
        } else if (o->spec) {
            return usage("expected one material, got '%s' too", argv[i]);
        } else {
            o->spec = argv[i];
        }
    }
    if (!o->spec) return usage("expected a material%s", "");
    if (!o->have_engine) return usage("--engine is required (glsl, gles, vulkan, hlsl or json)%s", "");
    return CLI_OK;
}

/* ---- the command ---- */

static lucent_status apply_sets(const options *o, lucent_render_settings *rs)
{
    for (int i = 0; i < o->set_count; i++) {
        char key[128];
        const char *eq = strchr(o->sets[i], '=');
        size_t n = eq ? (size_t)(eq - o->sets[i]) : 0;
        if (!eq || n == 0 || n >= sizeof key)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--set '%s': expected KEY=VALUE", o->sets[i]);
        memcpy(key, o->sets[i], n);
        key[n] = '\0';
        const lucent_setting *st = lucent_setting_find(key, NULL);
        if (!st)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "--set: no render setting '%s' (docs/scenes.md)", key);
        lucent_status s = lucent_setting_set(rs, st, eq + 1);
        if (s != LUCENT_OK) return s;
    }
    return lucent_render_settings_check(rs);
}

static lucent_status run(const options *o)
{
    lucent_material m;
    lucent_render_settings rs = lucent_render_settings_defaults();
    lucent_status s = lucent_material_resolve(o->spec, &m);
    if (s == LUCENT_OK) s = lucent_skin_resolve(&m); /* a skin: its equivalent medium (docs/skin.md) */
    char buf[4096], dir[4096];
    if (o->out || s != LUCENT_OK)
        snprintf(dir, sizeof dir, "%s", o->out ? o->out : "");
    else
        snprintf(dir, sizeof dir, "%s-%s", m.name, lucent_pack_engine_name(o->engine));
    if (s == LUCENT_OK) s = lucent_output_check_folder(dir); /* before the bake */
    if (s == LUCENT_OK) s = apply_sets(o, &rs);
    lucent_mesh *mesh = NULL;
    if (s == LUCENT_OK && o->mesh) s = lucent_mesh_load(o->mesh, NULL, &mesh);
    lucent_cache *cache = NULL;
    const char *cdir = cli_cache_dir(o->cache, o->no_cache, buf, sizeof buf);
    if (s == LUCENT_OK && cdir) s = lucent_cache_create(cdir, &cache);
    const cli_view *w = &o->view;
    lucent_pack_desc d = {.engine = o->engine,
                          .out = dir,
                          .screen_width = w->width,
                          .screen_height = w->height,
                          .fov_y = w->fov,
                          .object_height_mm = w->object_height_mm,
                          .distance_mm = w->distance_mm,
                          .settings = &rs,
                          .lut_width = o->lut_w,
                          .lut_height = o->lut_h,
                          .kappa_max = o->kappa_max,
                          .sigma0_photons = (uint64_t)o->sigma0_photons,
                          .transmit_photons = (uint64_t)o->transmit_photons,
                          .mesh = mesh,
                          .cache = cache,
                          .pool = cli_pool(),
                          .fit_photons = (uint64_t)o->fit_photons,
                          .fit_model_photons = (uint64_t)o->fit_model_photons,
                          .no_fit = o->no_fit};
    lucent_pack_result r;
    if (s == LUCENT_OK) s = lucent_pack(&m, &d, &r);
    if (s == LUCENT_OK) {
        cli_print_kernel_width(stdout, r.radius_mm, w);
        cli_wrote("wrote %s/ (%d files)", dir, r.file_count);
    }
    lucent_mesh_destroy(mesh);
    lucent_cache_destroy(cache);
    return s;
}

int cmd_pack(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.view = cli_view_defaults(), .kappa_max = 1, .lut_w = 64, .lut_h = 64};
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    return run(&o) == LUCENT_OK ? CLI_OK : cli_fail();
}
