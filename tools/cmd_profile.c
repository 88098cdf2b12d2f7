/* `lucent profile`: radial diffuse reflectance profiles R_d(r) of a material, from the Monte
 * Carlo simulation or the analytic models, written as JSON, CSV and an SVG chart like
 * Freude 2014, Figure 6.1 (linear near zero, logarithmic over the whole range). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/eval.h"
#include "lucent/mc.h"
#include "lucent/profile.h"

static const char k_usage[] =
    "usage: lucent profile MATERIAL [--model M | --compare M1,M2,...] [options]\n"
    "\n"
    "Computes the radial diffuse reflectance profile R_d(r) (mm^-2, r in mm) of a material\n"
    "lit by a thin beam at normal incidence, per RGB channel, and writes PREFIX.json,\n"
    "PREFIX.csv (radii, values, standard errors) and PREFIX.svg (linear near zero, log over the\n"
    "whole range). MATERIAL is a preset name (see 'lucent materials'), FILE.json or\n"
    "FILE.json#NAME.\n"
    "\n"
    "models:\n"
    "  mc             Monte Carlo transport (MCML physics; standard errors from batches)\n"
    "  dipole         classical dipole (Jensen et al. 2001)\n"
    "  better-dipole  d'Eon 2012\n"
    "  multipole      a slab of --thickness mm (Donner & Jensen 2005)\n"
    "  burley         normalized diffusion (Christensen & Burley 2015), --burley-fit\n"
    "  shortcut       a spectral skin's three-coefficient shortcut (docs/skin.md), to compare\n"
    "\n"
    "options:\n"
    "  --model M          one model (default: mc)\n"
    "  --compare LIST     several models on one chart (one panel per colour channel)\n"
    "  --photons N        Monte Carlo photons per channel (default 1000000)\n"
    "  --seed S           Monte Carlo seed (default 1); channel c uses seed 4 S + c\n"
    "  --layers LIST      a layered slab, top first: MATERIAL:THICKNESS_MM,...; the last may be\n"
    "                     'inf' (a half-space). Models: mc, multipole (finite layers only)\n"
    "  --thickness D      slab thickness in mm for multipole (default: a half-space for mc)\n"
    "  --burley-fit F     Burley's scaling factor s(A) (Christensen & Burley 2015): searchlight\n"
    "                     (mean free path, the default), diffuse (mean free path, diffuse\n"
    "                     transmission) or dmfp (diffuse mean free path)\n"
    "  --dr D             radial bin width in mm  } default: Freude 2014, Table 6.1:\n"
    "  --bins N           number of radial bins   } dr = min l'/20, N = 32 max l'/dr\n"
    "  --sog N            also fit N Gaussians per channel (d'Eon & Luebke 2007), to JSON\n"
    "  --bands N          a spectral skin (docs/skin.md): wavelength bands over 380-780 nm\n"
    "                     (default 20); its profile is mc or multipole band by band, weighted\n"
    "                     into linear sRGB per radius (mc: 3 x --photons / N per band)\n"
    "  --out PREFIX|DIR/  output prefix (default: NAME-MODEL, or NAME-compare); ending in '/': a\n"
    "                     folder, with the default names inside it\n"
    "  -h, --help         show this help\n"
    "\n"
    "examples:\n"
    "  lucent profile skin1 --model dipole\n"
    "  lucent profile marble --compare mc,dipole,better-dipole,burley --photons 200000\n"
    "  lucent profile skin1 --layers skin1:0.25,skin2:inf --model mc --out out/skin-layers\n"
    "  lucent profile skin-light --model multipole --out out/skin-light\n";

static const char *const k_models[] = {"mc", "dipole", "better-dipole", "multipole", "burley", "shortcut"};
enum { MODEL_MC, MODEL_DIPOLE, MODEL_BETTER, MODEL_MULTIPOLE, MODEL_BURLEY, MODEL_SHORTCUT, MODEL_COUNT };
enum { MAX_LAYERS = 16 };

typedef struct options {
    const char *spec;
    lucent_material material;
    lucent_material title; /* the material as outputs name it: a layered slab by its layers */
    bool layered;          /* --layers given: the outputs record the layers and are named after them */
    int models[MODEL_COUNT], model_count;
    bool compare;
    uint64_t photons, seed;
    lucent_layer layers[MAX_LAYERS];
    int layer_count;
    double thickness;
    lucent_burley_fit burley_fit;
    lucent_profile_grid grid;
    int sog;
    int bands; /* a spectral skin's wavelength bands (0: the default) */
    const char *out;
} options;

/* ---- arguments ---- */

static int find_model(const char *name)
{
    for (int m = 0; m < MODEL_COUNT; m++)
        if (strcmp(name, k_models[m]) == 0) return m;
    return -1;
}

static int parse_models(const char *list, options *o)
{
    char buf[256];
    snprintf(buf, sizeof buf, "%s", list);
    o->model_count = 0;
    for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int m = find_model(t);
        if (m < 0)
            return cli_usage_error("profile",
                                   "unknown model '%s' (mc, dipole, better-dipole, "
                                   "multipole, burley, shortcut)",
                                   t);
        if (o->model_count == MODEL_COUNT) return cli_usage_error("profile", "too many models");
        o->models[o->model_count++] = m;
    }
    return o->model_count ? CLI_OK : cli_usage_error("profile", "no model named");
}

static bool parse_u64(const char *text, uint64_t *dest)
{
    double v;
    if (!cli_parse_double(text, &v) || v < 0 || v > 1e15 || v != floor(v)) return false;
    *dest = (uint64_t)v;
    return true;
}

static lucent_status parse_layers(const char *list, options *o)
{
    return cli_parse_layers(list, o->layers, MAX_LAYERS, &o->layer_count);
}

static int parse_burley_fit(const char *v, options *o)
{
    if (v && strcmp(v, "searchlight") == 0)
        o->burley_fit = LUCENT_BURLEY_SEARCHLIGHT_MFP;
    else if (v && strcmp(v, "diffuse") == 0)
        o->burley_fit = LUCENT_BURLEY_DIFFUSE_MFP;
    else if (v && strcmp(v, "dmfp") == 0)
        o->burley_fit = LUCENT_BURLEY_SEARCHLIGHT_DMFP;
    else
        return cli_usage_error("profile", "--burley-fit must be searchlight, diffuse or dmfp");
    return CLI_OK;
}

/* Options with a number: returns CLI_OK, CLI_USAGE, or -1 when argv[*i] is none of them. */
static int parse_number_option(int argc, char **argv, int *i, options *o)
{
    const char *v;
    double d;
    int n;
    if (cli_option(argc, argv, i, "--photons", &v))
        return parse_u64(v, &o->photons) && o->photons > 0
                   ? CLI_OK
                   : cli_usage_error("profile", "--photons needs a whole number > 0");
    if (cli_option(argc, argv, i, "--seed", &v))
        return parse_u64(v, &o->seed) ? CLI_OK : cli_usage_error("profile", "--seed needs a whole number >= 0");
    if (cli_option(argc, argv, i, "--thickness", &v))
        return cli_parse_double(v, &o->thickness) && o->thickness > 0
                   ? CLI_OK
                   : cli_usage_error("profile", "--thickness needs a length > 0 (mm)");
    if (cli_option(argc, argv, i, "--dr", &v))
        return cli_parse_double(v, &d) && d >= LUCENT_MC_MIN_BIN && d <= LUCENT_MC_MAX_EXTENT
                   ? (o->grid.dr = d, CLI_OK)
                   : cli_usage_error("profile", "--dr needs a length from %g to %g mm", LUCENT_MC_MIN_BIN,
                                     LUCENT_MC_MAX_EXTENT);
    if (cli_option(argc, argv, i, "--bins", &v))
        return cli_parse_int(v, &n) && n > 0 ? (o->grid.count = n, CLI_OK)
                                             : cli_usage_error("profile", "--bins needs a whole number > 0");
    if (cli_option(argc, argv, i, "--bands", &v))
        return cli_parse_int(v, &o->bands) && o->bands >= 1 && o->bands <= LUCENT_BANDS_MAX
                   ? CLI_OK
                   : cli_usage_error("profile", "--bands needs a count from 1 to %d", LUCENT_BANDS_MAX);
    if (cli_option(argc, argv, i, "--sog", &v))
        return cli_parse_int(v, &o->sog) && o->sog >= 1 && o->sog <= LUCENT_SOG_MAX
                   ? CLI_OK
                   : cli_usage_error("profile", "--sog needs a count from 1 to %d", LUCENT_SOG_MAX);
    return -1;
}

static int parse_args(int argc, char **argv, options *o, const char **layers)
{
    int rc = CLI_OK;
    for (int i = 1; i < argc && rc == CLI_OK; i++) {
        const char *v;
        if ((rc = parse_number_option(argc, argv, &i, o)) != -1) continue;
        rc = CLI_OK;
        if (cli_option(argc, argv, &i, "--model", &v)) {
            o->compare = false;
            rc = v ? parse_models(v, o) : cli_usage_error("profile", "--model needs a model name");
            if (rc == CLI_OK && o->model_count > 1)
                rc = cli_usage_error("profile", "--model takes one model; use --compare for several");
        } else if (cli_option(argc, argv, &i, "--compare", &v)) {
            o->compare = true;
            rc = v ? parse_models(v, o) : cli_usage_error("profile", "--compare needs model names");
        } else if (cli_option(argc, argv, &i, "--layers", &v)) {
            *layers = v;
            if (!v) rc = cli_usage_error("profile", "--layers needs MATERIAL:THICKNESS,...");
        } else if (cli_option(argc, argv, &i, "--burley-fit", &v)) {
            rc = parse_burley_fit(v, o);
        } else if (cli_option(argc, argv, &i, "--out", &v)) {
            o->out = v;
            if (!v) rc = cli_usage_error("profile", "--out needs a file prefix");
        } else if (argv[i][0] == '-' && argv[i][1]) {
            rc = cli_usage_error("profile", "unknown option '%s'", argv[i]);
        } else if (o->spec) {
            rc = cli_usage_error("profile", "one material at a time (got '%s' and '%s')", o->spec, argv[i]);
        } else {
            o->spec = argv[i];
        }
    }
    if (rc == CLI_OK && !o->spec && !*layers) rc = cli_usage_error("profile", "expected a material");
    return rc;
}

/* ---- the models ---- */

/* Runs the Monte Carlo for channel c of the layers and copies R_d(r) into p. */
static lucent_status run_mc_channel(const options *o, int c, lucent_profile *p)
{
    lucent_mc_layer layers[MAX_LAYERS];
    for (int i = 0; i < o->layer_count; i++) {
        const lucent_material *m = &o->layers[i].material;
        double d = o->layers[i].slab.thickness;
        layers[i] = (lucent_mc_layer){
            .n = m->eta, .sigma_a = m->sigma_a[c], .sigma_s = m->sigma_s[c], .g = m->g[c], .thickness = d};
    }
    static const char *const labels[] = {"Monte Carlo R", "Monte Carlo G", "Monte Carlo B"};
    lucent_mc_desc desc = {.layers = layers,
                           .layer_count = o->layer_count,
                           .photons = o->photons,
                           .seed = 4 * o->seed + (uint64_t)c,
                           .grid = {.dr = p->dr, .nr = p->count},
                           .pool = cli_pool(),
                           .label = labels[c]};
    lucent_mc_result r = {0};
    lucent_status s = lucent_mc_run(&desc, &r);
    if (s != LUCENT_OK) return o->layer_count == 1 ? lucent_error_context(s, "%s", o->spec) : s;
    for (int j = 0; j < p->count; j++) p->value[c][j] = r.rd_r[j], p->error[c][j] = r.rd_r_se[j];
    lucent_mc_result_free(&r);
    return LUCENT_OK;
}

static lucent_status profile_mc(const options *o, const lucent_profile_grid *g, lucent_profile **dest)
{
    lucent_status s = lucent_profile_create(g, "mc", dest);
    for (int c = 0; c < 3 && s == LUCENT_OK; c++) s = run_mc_channel(o, c, *dest);
    if (s != LUCENT_OK) lucent_profile_destroy(*dest), *dest = NULL;
    return s;
}

static lucent_status profile_multipole(const options *o, const lucent_profile_grid *g, lucent_profile **dest)
{
    lucent_profile *rt[2] = {NULL, NULL};
    lucent_status s;
    if (o->layer_count > 1 || isinf(o->layers[0].slab.thickness)) {
        for (int i = 0; i < o->layer_count; i++)
            if (isinf(o->layers[i].slab.thickness))
                return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                    "multipole: every layer needs a finite "
                                    "thickness (--thickness, or MATERIAL:MM in --layers); use mc for a half-space");
        s = lucent_profile_layered(o->layers, o->layer_count, g, rt);
    } else {
        s = lucent_profile_multipole(&o->layers[0].material, &o->layers[0].slab, g, rt);
    }
    if (s != LUCENT_OK) return s;
    lucent_profile_destroy(rt[1]); /* the transmittance is not what this command draws */
    snprintf(rt[0]->model, sizeof rt[0]->model, "multipole");
    *dest = rt[0];
    return LUCENT_OK;
}

/* A spectral skin, band by band (lucent/skin.h): mc with 3 photons / bands per band for each photon per
 * channel asked (the work of an RGB material), or the layered multipole; the other models do not
 * carry layers. */
static lucent_status profile_skin(const options *o, int model, const lucent_profile_grid *g, lucent_profile **dest)
{
    if (model != MODEL_MC && model != MODEL_MULTIPOLE && model != MODEL_SHORTCUT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: %s is a spectral skin, carried in its layers band by band: --model mc, multipole "
                            "or shortcut",
                            k_models[model], o->material.name);
    int bands = o->bands ? o->bands : LUCENT_BANDS_DEFAULT;
    uint64_t per_band = 3 * o->photons / (uint64_t)bands;
    lucent_skin_desc d = {.bands = bands,
                          .transport = model == MODEL_MC         ? "mc"
                                       : model == MODEL_SHORTCUT ? "shortcut"
                                                                 : "multipole",
                          .photons = per_band ? per_band : 1,
                          .seed = o->seed,
                          .pool = cli_pool(),
                          .grid = *g};
    return lucent_profile_skin(&o->material, &d, dest);
}

static lucent_status make_profile(const options *o, int model, const lucent_profile_grid *g, lucent_profile **dest)
{
    if (o->material.skin.layer_count > 0) return profile_skin(o, model, g, dest);
    if (model == MODEL_SHORTCUT)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "shortcut: the three-coefficient shortcut of a spectral skin "
                            "(docs/skin.md); %s is not one",
                            o->material.name);
    if (o->layer_count > 1 && model != MODEL_MC && model != MODEL_MULTIPOLE)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: a layered slab needs --model mc or multipole",
                            k_models[model]);
    lucent_burley_params bp;
    lucent_status s;
    switch (model) {
    case MODEL_MC: return profile_mc(o, g, dest);
    case MODEL_DIPOLE: return lucent_profile_dipole(&o->material, g, dest);
    case MODEL_BETTER: return lucent_profile_better_dipole(&o->material, g, dest);
    case MODEL_MULTIPOLE: return profile_multipole(o, g, dest);
    default:
        s = lucent_burley_params_from_material(&o->material, o->burley_fit, &bp);
        return s == LUCENT_OK ? lucent_profile_burley(&bp, g, dest) : s;
    }
}

/* ---- the command ---- */

/* "Skin1 1mm + Skin2 2mm": a layered slab named by its layers and thicknesses (the chart, the CSV). */
static void layers_name(const options *o, char *dest, size_t size)
{
    dest[0] = '\0';
    for (int i = 0; i < o->layer_count; i++) {
        const lucent_layer *l = &o->layers[i];
        size_t n = strlen(dest);
        if (isinf(l->slab.thickness))
            snprintf(dest + n, size - n, "%s%s", i ? " + " : "", l->material.name);
        else
            snprintf(dest + n, size - n, "%s%s %gmm", i ? " + " : "", l->material.name, l->slab.thickness);
    }
}

/* "Skin1-1mm_Skin2-2mm": the same as a file name. */
static void layers_stem(const options *o, char *dest, size_t size)
{
    dest[0] = '\0';
    for (int i = 0; i < o->layer_count; i++) {
        const lucent_layer *l = &o->layers[i];
        size_t n = strlen(dest);
        snprintf(dest + n, size - n, isinf(l->slab.thickness) ? "%s%s" : "%s%s-%gmm", i ? "_" : "", l->material.name,
                 l->slab.thickness);
    }
}

/* The grid, from --dr and --bins or the material's default; a refusal names the material (issue 32: the
 * default grid of a too-dense one). */
static lucent_status grid_resolve(options *o)
{
    lucent_status s = lucent_profile_grid_resolve(&o->grid, &o->material, &o->grid);
    return s != LUCENT_OK && o->spec ? lucent_error_context(s, "%s", o->spec) : s;
}

/* Sets up the material and its layers once the arguments are read. */
static lucent_status prepare(options *o, const char *layers)
{
    lucent_status s;
    if (layers) {
        if ((s = parse_layers(layers, o)) != LUCENT_OK) return s;
        if (!o->spec) o->material = o->layers[0].material;
    }
    if (o->spec && (s = lucent_material_resolve(o->spec, &o->material)) != LUCENT_OK) return s;
    if ((s = lucent_skin_resolve(&o->material)) != LUCENT_OK) return s; /* its grid: the equivalent medium's */
    if (o->material.skin.layer_count > 0) {
        if (layers)
            return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                                "%s is a spectral skin, already layered: --layers takes RGB materials", o->spec);
        return grid_resolve(o);
    }
    if (!layers) {
        double d = o->thickness > 0 ? o->thickness : INFINITY;
        o->layers[0] = (lucent_layer){.material = o->material, .slab = {.thickness = d}};
        o->layer_count = 1;
    }
    o->title = o->material;
    o->layered = layers != NULL;
    if (o->layered) layers_name(o, o->title.name, sizeof o->title.name);
    bool multipole = false;
    for (int m = 0; m < o->model_count; m++) multipole |= o->models[m] == MODEL_MULTIPOLE;
    if (multipole && !layers && !(o->thickness > 0))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "multipole: give the slab --thickness in mm");
    return grid_resolve(o);
}

static void default_prefix(const options *o, char *dest, size_t size)
{
    const char *model = o->compare ? "compare" : k_models[o->models[0]];
    char stem[256];
    if (o->layered)
        layers_stem(o, stem, sizeof stem);
    else
        snprintf(stem, sizeof stem, "%s", o->material.name);
    if (snprintf(dest, size, "%s-%s", stem, model) >= (int)size) dest[size - 1] = '\0';
    for (char *p = dest; *p; p++)
        if (*p == '/' || *p == ' ') *p = '_';
}

/* PREFIX.EXT, or PREFIX-MODEL.EXT when several models are compared. */
static void path_for(const options *o, const char *prefix, const lucent_profile *p, const char *ext, char *dest,
                     size_t size)
{
    int n = o->compare ? snprintf(dest, size, "%s-%s.%s", prefix, p->model, ext)
                       : snprintf(dest, size, "%s.%s", prefix, ext);
    if (n >= (int)size) dest[size - 1] = '\0';
}

static lucent_status wrote(lucent_status s, const char *path)
{
    if (s == LUCENT_OK) cli_wrote("wrote %s", path);
    return s;
}

/* One profile's JSON and CSV (and its chart unless models are compared), with its sum of
 * Gaussians when asked. */
static lucent_status write_profile(const options *o, const char *prefix, const lucent_profile *p, bool with_sog)
{
    lucent_sog sog;
    char path[600];
    lucent_status s = with_sog ? lucent_sog_fit(p, &(lucent_sog_desc){.count = o->sog}, &sog) : LUCENT_OK;
    lucent_profile_report report = {.material = &o->material,
                                    .profile = p,
                                    .photons = o->photons,
                                    .seed = o->seed,
                                    .sog = with_sog ? &sog : NULL,
                                    .layers = o->layered ? o->layers : NULL,
                                    .layer_count = o->layered ? o->layer_count : 0};
    path_for(o, prefix, p, "json", path, sizeof path);
    if (s == LUCENT_OK) s = wrote(lucent_profile_write_json(path, &report), path);
    path_for(o, prefix, p, "csv", path, sizeof path);
    if (s == LUCENT_OK) s = wrote(lucent_profile_write_csv(path, &o->title, p), path);
    snprintf(path, sizeof path, "%s.svg", prefix);
    if (s == LUCENT_OK && !o->compare) s = wrote(lucent_profile_write_svg(path, &o->title, p, report.sog), path);
    return s;
}

static lucent_status write_outputs(const options *o, const char *prefix, lucent_profile *const *profiles)
{
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < o->model_count && s == LUCENT_OK; i++)
        s = write_profile(o, prefix, profiles[i], o->sog > 0 && (!o->compare || i == 0));
    char path[600];
    snprintf(path, sizeof path, "%s.svg", prefix);
    if (s == LUCENT_OK && o->compare)
        s = wrote(
            lucent_profile_write_compare_svg(path, &o->title, (const lucent_profile *const *)profiles, o->model_count),
            path);
    return s;
}

/* Before any work: PREFIX.json, .csv and .svg (with models compared, the chart) must not name the
 * material file (--out skin would overwrite skin.json); a usage error. */
static int check_outputs(const options *o, const char *prefix)
{
    char file[1024], paths[3][600];
    const char *ins[1] = {cli_spec_file(o->spec, file, sizeof file)}, *outs[3];
    static const char *const flags[3] = {"--out (JSON)", "--out (CSV)", "--out (SVG)"};
    static const char *const ext[3] = {"json", "csv", "svg"};
    for (int k = 0; k < 3; k++) {
        snprintf(paths[k], sizeof paths[k], "%s.%s", prefix, ext[k]);
        outs[k] = o->compare && k < 2 ? NULL : paths[k];
    }
    return cli_check_outputs("profile", ins, 1, outs, flags, 3);
}

static lucent_status run(options *o, const char *prefix)
{
    lucent_profile *profiles[MODEL_COUNT] = {NULL};
    lucent_status s = LUCENT_OK;
    for (int i = 0; i < o->model_count && s == LUCENT_OK; i++)
        s = make_profile(o, o->models[i], &o->grid, &profiles[i]);
    if (s == LUCENT_OK) s = write_outputs(o, prefix, profiles);
    for (int i = 0; i < o->model_count; i++) lucent_profile_destroy(profiles[i]);
    return s;
}

int cmd_profile(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.models = {MODEL_MC}, .model_count = 1, .photons = 1000000, .seed = 1};
    const char *layers = NULL;
    int rc = parse_args(argc, argv, &o, &layers);
    if (rc != CLI_OK) return rc;
    if (prepare(&o, layers) != LUCENT_OK) return cli_fail();
    char prefix[512], name[256];
    default_prefix(&o, name, sizeof name);
    cli_out_prefix(o.out, name, prefix, sizeof prefix);
    if ((rc = check_outputs(&o, prefix)) != CLI_OK) return rc;
    return run(&o, prefix) == LUCENT_OK ? CLI_OK : cli_fail();
}
