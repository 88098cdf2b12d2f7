/* `lucent kernel-eval`: every separable kernel model of a material against the ground truth,
 * in kernel space (Freude 2014, Table 6.3, Figure 6.2) and in image space on a test signal
 * (Tables 6.4-6.5, Figures 6.6-6.10). See docs/kernel-eval.md. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/eval.h"

static const char k_usage[] =
    "usage: lucent kernel-eval MATERIAL [--models all|M1,M2,...] [--signal edge|shapes|IMAGE]\n"
    "                          [--out DIR] [options]\n"
    "\n"
    "Builds the ground-truth 2-D kernel of MATERIAL's profile and every kernel model of it,\n"
    "then compares them in kernel space (RMS over the grid, Freude Table 6.3; axis and diagonal\n"
    "slices, Figure 6.2) and in image space: the signal convolved exactly with the ground truth\n"
    "(2-D FFT) against each model's separable rank-N convolution and its taps (Tables 6.4-6.5).\n"
    "Writes into DIR (default NAME-eval, created if absent; its parent must exist):\n"
    "  kernel-axis.svg, kernel-diagonal.svg   slices y = 0 and x = y, one panel per channel\n"
    "  signal.png, exact.png/.exr             the signal and its exact convolution\n"
    "  MODEL.png/.exr, MODEL-taps.png/.exr    each model's convolution (separable; taps)\n"
    "  MODEL-diff.png, MODEL-taps-diff.png    heat maps of |model - exact| (mean over RGB)\n"
    "  tables.md, results.json                kernel- and image-space RMS per model and channel\n"
    "\n"
    "models (--models, default all): svd (rank 1), svd-norm (normalised, (5.12)), preint,\n"
    "  guided (k = 1), manual (Table A.1 presets only; skipped otherwise), sog (1 Gaussian),\n"
    "  jimenez. svd-rN and sog-rN (N = 1..16) pick a rank.\n"
    "\n"
    "options:\n"
    "  --signal S         edge (default), shapes, or a PNG/EXR/PFM image\n"
    "  --size N           signal side in pixels for edge and shapes (default 256)\n"
    "  --mm-per-pixel P   the signal's scale (default 0.1)\n"
    "  --taps N           taps per pass for the tap convolutions (odd, default 17; 0: none)\n"
    "  --table65          also svd rank N against sog with N Gaussians, N = 1..6 (Table 6.5;\n"
    "                     always on for Skin1)\n"
    "  --heat-scale E     the error mapped to white in the heat maps (default 0.1)\n"
    "  --profile P        dipole (default), better-dipole, burley or mc\n"
    "  --photons N        mc: photons per channel (default 1000000)\n"
    "  --seed S           mc: seed (default 1)\n"
    "  -q, --quiet        no informational lines\n";

typedef struct options {
    const char *spec, *out, *profile, *signal, *models;
    int size, taps, photons, seed;
    double mm_per_pixel, heat_scale;
    bool table65;
    char model_text[512];
    const char *model_names[LUCENT_KERNEL_EVAL_MAX_MODELS];
    int model_count;
} options;

/* ---- Arguments ---- */

static int usage(const char *message, const char *arg) { return cli_usage_error("kernel-eval", message, arg); }

static int parse_args(int argc, char **argv, options *o)
{
    static const char *const valued[] = {"--models", "--signal",  "--out",     "--size", "--mm-per-pixel",
                                         "--taps",   "--profile", "--photons", "--seed", "--heat-scale"};
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        int n = -1;
        for (int j = 0; j < (int)(sizeof valued / sizeof valued[0]) && n < 0; j++)
            if (cli_option(argc, argv, &i, valued[j], &v)) n = j;
        if (n >= 0 && !v) return usage("%s needs a value", valued[n]);
        bool ok = true;
        switch (n) {
        case 0: o->models = v; break;
        case 1: o->signal = v; break;
        case 2: o->out = v; break;
        case 3: ok = cli_parse_int(v, &o->size) && o->size >= 8 && o->size <= 16384; break;
        case 4: ok = cli_parse_double(v, &o->mm_per_pixel) && o->mm_per_pixel > 0; break;
        case 5:
            ok = cli_parse_int(v, &o->taps) && (o->taps == 0 || (o->taps % 2 == 1 && o->taps >= 3 && o->taps <= 255));
            break;
        case 6: ok = lucent_profile_source_known(o->profile = v); break;
        case 7: ok = cli_parse_int(v, &o->photons) && o->photons > 0; break;
        case 8: ok = cli_parse_int(v, &o->seed); break;
        case 9: ok = cli_parse_double(v, &o->heat_scale) && o->heat_scale > 0; break;
        default:
            if (!strcmp(argv[i], "--table65"))
                o->table65 = true;
            else if (argv[i][0] == '-')
                return usage("unknown option '%s'", argv[i]);
            else if (o->spec)
                return usage("expected one material, got '%s' too", argv[i]);
            else
                o->spec = argv[i];
        }
        if (!ok) {
            static const char *const what[] = {"",
                                               "",
                                               "",
                                               "a whole number in 8..16384",
                                               "a number > 0 (mm)",
                                               "0 or an odd number in 3..255",
                                               "dipole, better-dipole, burley or mc",
                                               "a whole number > 0",
                                               "a whole number",
                                               "a number > 0"};
            return cli_usage_error("kernel-eval", "%s needs %s", valued[n], what[n]);
        }
    }
    if (!o->spec) return usage("expected a material%s", "");
    return CLI_OK;
}

/* ---- Models ---- */

/* Splits --models (default: all) into names the library knows; a usage error otherwise. */
static int choose_models(options *o)
{
    const char *list = o->models;
    if (!list || !strcmp(list, "all")) list = LUCENT_KERNEL_EVAL_DEFAULT_MODELS;
    if (strlen(list) >= sizeof o->model_text) return usage("--models: list too long%s", "");
    strcpy(o->model_text, list);
    char *save = NULL;
    for (char *t = strtok_r(o->model_text, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        lucent_kernel_desc d;
        if (o->model_count == LUCENT_KERNEL_EVAL_MAX_MODELS || lucent_kernel_eval_model_parse(t, &d) != LUCENT_OK) {
            lucent_clear_error();
            return usage("unknown model '%s' (svd, svd-norm, preint, guided, manual, sog, jimenez, svd-rN, sog-rN)", t);
        }
        o->model_names[o->model_count++] = t;
    }
    if (o->model_count == 0) return usage("--models needs at least one model%s", "");
    return CLI_OK;
}

/* ---- Driver ---- */

/* Says what the evaluation wrote and skipped, as it goes. */
static void on_event(const lucent_eval_event *e, void *user)
{
    (void)user;
    if (e->kind == LUCENT_EVAL_WROTE) cli_wrote("wrote %s", e->path);
    if (e->kind == LUCENT_EVAL_SKIPPED) cli_info("%s: skipped (%s)", e->name, e->reason);
}

static lucent_status run(const options *o)
{
    lucent_material m;
    lucent_status s = lucent_material_resolve(o->spec, &m);
    if (s == LUCENT_OK) s = lucent_skin_resolve(&m); /* a skin: its equivalent medium */
    if (s != LUCENT_OK) return s;
    char dir[512];
    if (o->out)
        snprintf(dir, sizeof dir, "%s", o->out);
    else
        snprintf(dir, sizeof dir, "%s-eval", m.name);
    if ((s = lucent_output_check_folder(dir)) != LUCENT_OK) return s;
    lucent_kernel_eval_desc d = {
        .material = &m,
        .models = o->model_names,
        .model_count = o->model_count,
        .table65 = o->table65,
        .profile = {.source = o->profile, .photons = (uint64_t)o->photons, .seed = (uint64_t)o->seed},
        .signal = o->signal,
        .size = o->size,
        .mm_per_pixel = o->mm_per_pixel,
        .taps = o->taps,
        .no_taps = o->taps == 0,
        .heat_scale = o->heat_scale,
        .out = dir,
        .pool = cli_pool(),
        .on_event = on_event};
    lucent_kernel_eval_result res;
    s = lucent_kernel_eval_run(&d, &res);
    lucent_kernel_eval_result_free(&res);
    return s;
}

int cmd_kernel_eval(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    lucent_kernel_eval_desc def = lucent_kernel_eval_defaults();
    options o = {.profile = def.profile.source,
                 .signal = def.signal,
                 .size = def.size,
                 .taps = def.taps,
                 .photons = 1000000,
                 .seed = 1,
                 .mm_per_pixel = def.mm_per_pixel,
                 .heat_scale = def.heat_scale};
    int rc = parse_args(argc, argv, &o);
    if (rc == CLI_OK) rc = choose_models(&o);
    if (rc != CLI_OK) return rc;
    lucent_status s = run(&o);
    const char *e = lucent_last_error();
    if (s != LUCENT_OK && (strncmp(e, "layers[", 7) == 0 || strncmp(e, "sigma_", 6) == 0))
        lucent_error_context(s, "%s", o.spec); /* a check of the material's fields (the Monte Carlo's, the profile
                                                  grid's): name its file */
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
