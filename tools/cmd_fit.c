/* `lucent fit`: each engine's subsurface parameters fitted to a material's truth (lucent/engine.h),
 * printed and written as PREFIX.json and PREFIX.md. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char k_usage[] =
    "usage: lucent fit MATERIAL [--layers LIST] [--engines LIST] [options]\n"
    "\n"
    "Fits each engine's subsurface model, computed from the engine's own definition, to the\n"
    "material's truth: Lucent's Monte Carlo profile R(r) of a half-space lit by a thin beam and its\n"
    "total diffuse reflectance T. The fit matches T (the engine's albedo or colour) and minimises\n"
    "the sum over R, G, B of e_p^2, e_p the relative RMS of r R(r) over the radii holding 99% of T.\n"
    "Per engine it\n"
    "prints the parameters in the engine's names and units, e_p, the CIEDE2000 difference of T\n"
    "(D65), what the model cannot express, and the hand mapping (radius = 1/sigma_tr, colour = T)\n"
    "for comparison; and writes PREFIX.json, PREFIX.md and PREFIX.svg (r R(r) of the truth and of\n"
    "each model, one panel per channel). MATERIAL is a preset, FILE.json or\n"
    "FILE.json#NAME. See docs/engines.md.\n"
    "\n"
    "engines:\n"
    "  unreal-burley     Unreal Engine 5 Subsurface Profile, Burley (Mean Free Path)\n"
    "  unreal-separable  Unreal's legacy separable profile (Subsurface/Falloff Color, Scatter Radius)\n"
    "  unity-hdrp        Unity HDRP Diffusion Profile (Scattering Color x Multiplier, Transmission Tint)\n"
    "  blender3-burley   Blender 3.x Principled BSDF, Christensen-Burley\n"
    "  blender3-rw       Blender 3.x Principled BSDF, Random Walk\n"
    "  blender4-burley   Blender 4.x Principled BSDF (Subsurface Weight, Radius, Scale)\n"
    "  openpbr           OpenPBR 1.x subsurface_*\n"
    "  godot             Godot 4 StandardMaterial3D subsurf_scatter_* and transmittance\n"
    "  gltf              glTF 2.0 KHR_materials_volume, _transmission, _diffuse_transmission and the\n"
    "                    draft KHR_materials_volume_scatter (the pack's mapping: the error of the\n"
    "                    medium a reader of the draft builds; without the draft, no scattering)\n"
    "\n"
    "options:\n"
    "  --engines LIST     engines to fit (default: all)\n"
    "  --layers LIST      a layered slab, top first: MATERIAL:THICKNESS_MM,...; the last may be\n"
    "                     'inf' (a half-space); MATERIAL may then be left out\n"
    "  --photons N        the truth's Monte Carlo photons per channel: N for the profile, 2 N for\n"
    "                     T (default: 200000, and the bake's 400000 for T, kept in the cache)\n"
    "  --model-photons N  photons per channel of the random-walk models' Monte Carlo (default 50000)\n"
    "  --seed S           Monte Carlo seed (default 1)\n"
    "  --transmittance    also fit the transmittance (HDRP's tint, Godot's colour and depth) to the\n"
    "                     Monte Carlo slab (homogeneous materials)\n"
    "  --no-hand          leave out the hand mapping\n"
    "  --out PREFIX|DIR/  output prefix (default: NAME-fit); ending in '/': a folder\n"
    "  --cache DIR        the disk cache of Monte Carlo results (default: $LUCENT_CACHE_DIR or\n"
    "                     ~/.cache/lucent); --no-cache: none\n"
    "  -h, --help         show this help\n"
    "\n"
    "examples:\n"
    "  lucent fit skin1 --out out/skin1-fit\n"
    "  lucent fit marble --engines unreal-burley,blender3-burley --transmittance\n"
    "  lucent fit --layers skin1:0.25,skin2:inf --out out/skin-layers-fit\n";

typedef struct options {
    const char *spec, *layers_text, *out, *cache;
    bool no_cache, no_hand, transmittance;
    lucent_material material;
    lucent_layer layers[LUCENT_ENGINE_MAX_LAYERS];
    int layer_count;
    lucent_engine_id engines[LUCENT_ENGINE_COUNT];
    int engine_count;
    uint64_t photons, model_photons, seed;
} options;

static int parse_engines(const char *list, options *o)
{
    char buf[512];
    snprintf(buf, sizeof buf, "%s", list);
    o->engine_count = 0;
    for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        if (o->engine_count == LUCENT_ENGINE_COUNT) return cli_usage_error("fit", "--engines: too many engines");
        if (lucent_engine_parse(t, &o->engines[o->engine_count]) != LUCENT_OK)
            return cli_usage_error("fit", "--engines: %s", lucent_last_error());
        o->engine_count++;
    }
    return o->engine_count ? CLI_OK : cli_usage_error("fit", "--engines needs engine names");
}

static bool parse_u64(const char *text, uint64_t *dest, bool positive)
{
    double v;
    if (!text || !cli_parse_double(text, &v) || v < (positive ? 1 : 0) || v > 1e12 || v != floor(v)) return false;
    *dest = (uint64_t)v;
    return true;
}

static int parse_option(int argc, char **argv, int *i, options *o)
{
    const char *v;
    if (cli_option(argc, argv, i, "--engines", &v))
        return v ? parse_engines(v, o) : cli_usage_error("fit", "--engines needs engine names");
    if (cli_option(argc, argv, i, "--layers", &v))
        return (o->layers_text = v) ? CLI_OK : cli_usage_error("fit", "--layers needs MATERIAL:THICKNESS,...");
    if (cli_option(argc, argv, i, "--photons", &v))
        return parse_u64(v, &o->photons, true) ? CLI_OK : cli_usage_error("fit", "--photons needs a whole number > 0");
    if (cli_option(argc, argv, i, "--model-photons", &v))
        return parse_u64(v, &o->model_photons, true)
                   ? CLI_OK
                   : cli_usage_error("fit", "--model-photons needs a whole number > 0");
    if (cli_option(argc, argv, i, "--seed", &v))
        return parse_u64(v, &o->seed, false) ? CLI_OK : cli_usage_error("fit", "--seed needs a whole number >= 0");
    if (cli_option(argc, argv, i, "--out", &v))
        return (o->out = v) ? CLI_OK : cli_usage_error("fit", "--out needs a prefix");
    if (cli_option(argc, argv, i, "--cache", &v))
        return (o->cache = v) ? CLI_OK : cli_usage_error("fit", "--cache needs a folder");
    if (!strcmp(argv[*i], "--no-cache")) return o->no_cache = true, CLI_OK;
    if (!strcmp(argv[*i], "--no-hand")) return o->no_hand = true, CLI_OK;
    if (!strcmp(argv[*i], "--transmittance")) return o->transmittance = true, CLI_OK;
    if (argv[*i][0] == '-' && argv[*i][1]) return cli_usage_error("fit", "unknown option '%s'", argv[*i]);
    if (o->spec) return cli_usage_error("fit", "one material at a time (got '%s' and '%s')", o->spec, argv[*i]);
    o->spec = argv[*i];
    return CLI_OK;
}

static void print_param(const lucent_engine_param *p)
{
    printf("    %-44s ", p->name);
    if (p->count == 0)
        printf("%s", p->text);
    else if (p->count == 1)
        printf("%.4g", p->value[0]);
    else
        printf("(%.4g, %.4g, %.4g)", p->value[0], p->value[1], p->value[2]);
    printf("%s%s\n", p->unit[0] ? " " : "", p->unit);
}

static void print_errors(const char *what, const lucent_engine_fit_result *r)
{
    printf("  %-7s e_p %5.1f%% (R %.1f%%, G %.1f%%, B %.1f%%), delta E2000 %.2f", what, 100 * r->profile_error_rms,
           100 * r->profile_error[0], 100 * r->profile_error[1], 100 * r->profile_error[2], r->delta_e);
    if (isfinite(r->transmit_error)) printf(", transmittance %.1f%%", 100 * r->transmit_error);
    printf("\n");
}

static void print_report(const lucent_engine_report *rep)
{
    const lucent_engine_target *t = &rep->target;
    printf("%s: T = (%.4f, %.4f, %.4f), r99 = (%.3g, %.3g, %.3g) mm, the truth's noise (%.1f%%, %.1f%%, %.1f%%)\n",
           t->material.name, t->rd[0], t->rd[1], t->rd[2], t->r99[0], t->r99[1], t->r99[2], 100 * t->noise[0],
           100 * t->noise[1], 100 * t->noise[2]);
    for (int i = 0; i < rep->count; i++) {
        const lucent_engine_fit_result *r = &rep->fits[i];
        printf("\n%s (%s)\n", lucent_engine_title(r->engine), lucent_engine_name(r->engine));
        for (int k = 0; k < r->param_count; k++) print_param(&r->params[k]);
        print_errors("fitted", r);
        if (rep->hand[i].param_count) print_errors("hand", &rep->hand[i]);
        if (r->cannot[0]) printf("  cannot express: %s\n", r->cannot);
    }
}

static lucent_status prepare(options *o)
{
    lucent_status s = LUCENT_OK;
    if (o->layers_text) s = cli_parse_layers(o->layers_text, o->layers, LUCENT_ENGINE_MAX_LAYERS, &o->layer_count);
    if (s == LUCENT_OK && o->spec)
        s = lucent_material_resolve(o->spec, &o->material);
    else if (s == LUCENT_OK)
        o->material = o->layers[0].material;
    return s;
}

static int run(options *o)
{
    char cache_buf[1024], prefix[512], name[256], paths[3][600];
    const char *cdir = cli_cache_dir(o->cache, o->no_cache, cache_buf, sizeof cache_buf);
    snprintf(name, sizeof name, "%s-fit", o->layer_count ? "layers" : o->material.name);
    for (char *p = name; *p; p++)
        if (*p == '/' || *p == ' ') *p = '_';
    cli_out_prefix(o->out, name, prefix, sizeof prefix);
    snprintf(paths[0], sizeof paths[0], "%s.json", prefix);
    snprintf(paths[1], sizeof paths[1], "%s.md", prefix);
    snprintf(paths[2], sizeof paths[2], "%s.svg", prefix);
    char file[1024];
    const char *ins[1] = {cli_spec_file(o->spec, file, sizeof file)}, *outs[3] = {paths[0], paths[1], paths[2]};
    static const char *const flags[3] = {"--out (JSON)", "--out (Markdown)", "--out (SVG)"};
    int rc = cli_check_outputs("fit", ins, 1, outs, flags, 3);
    if (rc != CLI_OK) return rc;
    lucent_cache *cache = NULL;
    if (cdir && lucent_cache_create(cdir, &cache) != LUCENT_OK) return cli_fail();
    lucent_engine_report_desc d = {.target = {.material = o->layer_count ? NULL : &o->material,
                                              .layers = o->layer_count ? o->layers : NULL,
                                              .layer_count = o->layer_count,
                                              .photons = o->photons,
                                              .total_photons = 2 * o->photons,
                                              .seed = o->seed,
                                              .transmittance = o->transmittance,
                                              .pool = cli_pool(),
                                              .cache = cache},
                                   .engines = o->engines,
                                   .engine_count = o->engine_count,
                                   .hand = !o->no_hand,
                                   .fit = {.model_photons = o->model_photons, .pool = cli_pool()}};
    lucent_engine_report rep;
    lucent_status s = lucent_engine_report_run(&d, &rep);
    if (s == LUCENT_OK) {
        print_report(&rep);
        s = lucent_engine_report_write_json(paths[0], &rep);
        if (s == LUCENT_OK) cli_wrote("wrote %s", paths[0]);
        if (s == LUCENT_OK) s = lucent_engine_report_write_markdown(paths[1], &rep);
        if (s == LUCENT_OK) cli_wrote("wrote %s", paths[1]);
        if (s == LUCENT_OK) s = lucent_engine_report_write_svg(paths[2], &rep);
        if (s == LUCENT_OK) cli_wrote("wrote %s", paths[2]);
        lucent_engine_report_free(&rep);
    }
    lucent_cache_destroy(cache);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}

int cmd_fit(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.seed = 1};
    int rc = CLI_OK;
    for (int i = 1; i < argc && rc == CLI_OK; i++) rc = parse_option(argc, argv, &i, &o);
    if (rc == CLI_OK && !o.spec && !o.layers_text) rc = cli_usage_error("fit", "expected a material (or --layers)");
    if (rc == CLI_OK && o.transmittance && o.layers_text)
        rc = cli_usage_error("fit", "--transmittance goes with a homogeneous material, not --layers");
    if (rc != CLI_OK) return rc;
    if (prepare(&o) != LUCENT_OK) return cli_fail();
    return run(&o);
}
