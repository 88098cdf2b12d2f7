/* `lucent kernel`: separable subsurface-scattering kernels of a material (Freude 2014, ch. 5),
 * sampled into importance-sampled taps and exported as GLSL, HLSL, C or JSON. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/kernel.h"
#include "lucent/mc.h"
#include "lucent/profile.h"

static const char k_usage[] =
    "usage: lucent kernel MATERIAL [--model M] [options]\n"
    "\n"
    "Builds the ground-truth 2-D kernel of MATERIAL's radial profile (normalised per channel),\n"
    "approximates it by a separable model, samples the model into importance-sampled taps\n"
    "(offsets in mm, as in Jimenez's separable SSS) and writes them. MATERIAL is a preset name\n"
    "(see 'lucent materials'), FILE.json or FILE.json#NAME (jimenez needs none).\n"
    "\n"
    "models (--model, default preint):\n"
    "  svd      SVD rank N (Freude (5.5)-(5.10)); --normalize scales to the 1-norm (5.12)\n"
    "  preint   pre-integration (5.15)-(5.18), rank 1, energy conserving\n"
    "  guided   guided optimisation (5.19)-(5.20) with weight Gamma(x, y; k, b), rank 1\n"
    "  manual   two Gaussians (5.21), Freude Table A.1 presets (Apple, Ketchup, Marble,\n"
    "           Skin1, Wholemilk) or --near R,G,B --far R,G,B --w W (standard deviations, mm)\n"
    "  sog      d'Eon's sum of N Gaussians fitted to the profile (two passes per Gaussian)\n"
    "  jimenez  Jimenez's skin kernel (4.8): --strength R,G,B --falloff R,G,B\n"
    "\n"
    "options:\n"
    "  --rank N           passes for svd and sog (1..16, default 1)\n"
    "  --taps N           taps per pass (odd, 3..255, default 17: the renderer's ssss.taps)\n"
    "  --range MM         taps' half-width in mm (default: the model's; jimenez 2)\n"
    "  --k K --b B        guided: weight exponent (default 1) and axis damping (default 0)\n"
    "  --normalize        svd: scale the kernel to the ground truth's 1-norm\n"
    "  --profile P        dipole (default), better-dipole, burley or mc (Monte Carlo, half-space)\n"
    "  --photons N        mc: photons per channel (default 1000000)\n"
    "  --seed S           mc: seed (default 1)\n"
    "  --export F         glsl, hlsl, c or json (default json)\n"
    "  --out FILE         write there (atomically) instead of stdout\n"
    "  --screen WxH --fov DEG --object-height H | --distance D\n"
    "                     print the kernel's width in pixels on that screen (defaults 1920x1080,\n"
    "                     45 degrees, an object of 1.8m filling the height; lengths with their\n"
    "                     unit: m, cm or mm); printed with --out too (to stderr when the export goes\n"
    "                     to stdout)\n"
    "  -q, --quiet        no informational lines\n";

typedef struct options {
    const char *spec, *out, *profile;
    lucent_kernel_desc desc;
    lucent_taps_desc taps;
    lucent_kernel_format format;
    bool have_k;
    int photons, seed;
    cli_view view;
} options;

static bool parse_triple(const char *text, double dest[3])
{
    char buf[256];
    if (!text || strlen(text) >= sizeof buf) return false;
    strcpy(buf, text);
    char *save = NULL, *tok = strtok_r(buf, ",", &save);
    for (int c = 0; c < 3; c++, tok = strtok_r(NULL, ",", &save))
        if (!cli_parse_double(tok, &dest[c])) return false;
    return tok == NULL;
}

static int need(bool ok, const char *message) { return ok ? CLI_OK : cli_usage_error("kernel", "%s", message); }

/* Options that take a number or a triple. Returns CLI_OK, CLI_USAGE, or -1: not one of them. */
static int parse_value(options *o, const char *name, const char *v)
{
    lucent_kernel_desc *d = &o->desc;
    if (!strcmp(name, "--photons"))
        return need(cli_parse_int(v, &o->photons) && o->photons > 0, "--photons needs a whole number > 0");
    if (!strcmp(name, "--seed")) return need(cli_parse_int(v, &o->seed), "--seed needs a whole number");
    if (!strcmp(name, "--rank"))
        return need(cli_parse_int(v, &d->rank) && d->rank >= 1, "--rank needs a whole number >= 1");
    if (!strcmp(name, "--taps"))
        return need(cli_parse_int(v, &o->taps.count) && o->taps.count >= 1, "--taps needs a whole number >= 1");
    if (!strcmp(name, "--range"))
        return need(cli_parse_double(v, &o->taps.range) && o->taps.range > 0 && o->taps.range <= LUCENT_TAPS_MAX_RANGE,
                    "--range needs a number > 0 and at most 1e6 (mm)");
    if (!strcmp(name, "--k")) return need(o->have_k = cli_parse_double(v, &d->k), "--k needs a number");
    if (!strcmp(name, "--b")) return need(cli_parse_double(v, &d->b), "--b needs a number");
    if (!strcmp(name, "--w")) return need(d->use_manual = cli_parse_double(v, &d->manual.w), "--w needs a number");
    if (!strcmp(name, "--near")) return need(d->use_manual = parse_triple(v, d->manual.sd_near), "--near needs R,G,B");
    if (!strcmp(name, "--far")) return need(d->use_manual = parse_triple(v, d->manual.sd_far), "--far needs R,G,B");
    if (!strcmp(name, "--strength")) return need(parse_triple(v, d->strength), "--strength needs R,G,B");
    if (!strcmp(name, "--falloff")) return need(parse_triple(v, d->falloff), "--falloff needs R,G,B");
    return -1;
}

static int parse_named(options *o, const char *name, const char *v)
{
    if (!v) return cli_usage_error("kernel", "%s needs a value", name);
    if (!strcmp(name, "--model"))
        return lucent_kernel_model_parse(v, &o->desc.model) == LUCENT_OK
                   ? CLI_OK
                   : cli_usage_error("kernel", "unknown model '%s'", v);
    if (!strcmp(name, "--export"))
        return lucent_kernel_format_parse(v, &o->format) == LUCENT_OK
                   ? CLI_OK
                   : cli_usage_error("kernel", "unknown export format '%s' (glsl, hlsl, c, json)", v);
    if (!strcmp(name, "--profile")) {
        o->profile = v;
        return lucent_profile_source_known(v)
                   ? CLI_OK
                   : cli_usage_error("kernel", "--profile must be dipole, better-dipole, burley or mc");
    }
    if (!strcmp(name, "--out")) return (o->out = v), CLI_OK;
    return parse_value(o, name, v);
}

static const char *const k_valued[] = {"--model", "--export", "--profile",  "--out",    "--rank",    "--taps",
                                       "--range", "--k",      "--b",        "--w",      "--photons", "--seed",
                                       "--near",  "--far",    "--strength", "--falloff"};

static int parse_args(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        bool matched = false;
        for (size_t n = 0; n < sizeof k_valued / sizeof k_valued[0] && !matched; n++)
            if (cli_option(argc, argv, &i, k_valued[n], &v)) {
                matched = true;
                int rc = parse_named(o, k_valued[n], v);
                if (rc != CLI_OK) return rc;
            }
        if (matched) continue;
        int view = cli_view_option("kernel", argc, argv, &i, &o->view);
        if (view == CLI_USAGE) return CLI_USAGE;
        if (view == CLI_OK) continue;
        if (!strcmp(argv[i], "--normalize"))
            o->desc.normalize = true;
        else if (argv[i][0] == '-')
            return cli_usage_error("kernel", "unknown option '%s'", argv[i]);
        else if (o->spec)
            return cli_usage_error("kernel", "expected one material, got '%s' too", argv[i]);
        else
            o->spec = argv[i];
    }
    if (!o->spec && o->desc.model != LUCENT_KERNEL_JIMENEZ) return cli_usage_error("kernel", "expected a material");
    if (!o->have_k) o->desc.k = 1;
    return CLI_OK;
}

static lucent_status write_out(const options *o, const char *text)
{
    if (!o->out) return fputs(text, stdout) < 0 ? lucent_error(LUCENT_ERR_IO, "stdout: write failed") : LUCENT_OK;
    lucent_status s = lucent_write_file(o->out, text, strlen(text));
    if (s == LUCENT_OK) cli_wrote("wrote %s", o->out);
    return s;
}

static void report(const options *o, const lucent_kernel *k, const lucent_kernel2d *gt, const char *name)
{
    if (!o->out || !gt) return;
    double rms[3];
    lucent_kernel_rms(k, gt, rms);
    cli_info("%s %s rank %d: grid %d x %d of %.4g mm, kernel-space RMS %.3g %.3g %.3g mm^-2, taps to %.4g mm", name,
             lucent_kernel_model_name(k->model), k->rank, 2 * gt->half + 1, 2 * gt->half + 1, gt->h, rms[0], rms[1],
             rms[2], o->taps.range > 0 ? o->taps.range : k->range);
    if (k->model == LUCENT_KERNEL_GUIDED) cli_info("guided: 1-norm constraint error %.3g", k->constraint_error);
}

static lucent_status run(options *o)
{
    lucent_material m = {0};
    lucent_profile *p = NULL;
    lucent_kernel2d *gt = NULL;
    lucent_kernel *k = NULL;
    lucent_taps *t = NULL;
    char *text = NULL, label[160];
    lucent_status s = o->spec ? lucent_material_resolve(o->spec, &m) : LUCENT_OK;
    if (s == LUCENT_OK && o->spec) s = lucent_skin_resolve(&m); /* a skin: its equivalent medium */
    if (s == LUCENT_OK && o->spec)
        s = lucent_profile_from_source(
            &(lucent_profile_source_desc){
                .source = o->profile, .photons = (uint64_t)o->photons, .seed = (uint64_t)o->seed, .pool = cli_pool()},
            &m, &p);
    if (s != LUCENT_OK && o->spec && strncmp(lucent_last_error(), o->spec, strlen(o->spec)) != 0)
        s = lucent_error_context(s, "%s", o->spec); /* the material's fields are the file's: name it */
    if (s == LUCENT_OK && p) s = lucent_kernel2d_from_profile(p, NULL, &gt);
    if (s == LUCENT_OK) s = lucent_kernel_build(gt, p, o->spec ? m.name : NULL, &o->desc, &k);
    if (s == LUCENT_OK) s = lucent_kernel_taps(k, &o->taps, &t);
    snprintf(label, sizeof label, "%s, %s rank %d", o->spec ? m.name : "skin", lucent_kernel_model_name(o->desc.model),
             k ? k->rank : 1);
    if (s == LUCENT_OK) s = lucent_taps_export(t, o->format, label, &text);
    if (s == LUCENT_OK) s = write_out(o, text);
    if (s == LUCENT_OK) report(o, k, gt, o->spec ? m.name : "skin");
    /* The width on screen: with the export on stdout, on stderr (and only when a screen was given). */
    if (s == LUCENT_OK && !g_cli.quiet && (o->out || o->view.given))
        cli_print_kernel_width(o->out ? stdout : stderr, o->taps.range > 0 ? o->taps.range : lucent_taps_radius(t),
                               &o->view);
    free(text);
    lucent_taps_destroy(t);
    lucent_kernel_destroy(k);
    lucent_kernel2d_destroy(gt);
    lucent_profile_destroy(p);
    return s;
}

int cmd_kernel(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {.profile = "dipole",
                 .desc = {.model = LUCENT_KERNEL_PREINT},
                 .format = LUCENT_KERNEL_JSON,
                 .photons = 1000000,
                 .seed = 1,
                 .view = cli_view_defaults()};
    int rc = parse_args(argc, argv, &o);
    char file[1024];
    const char *ins[1] = {cli_spec_file(o.spec, file, sizeof file)}, *outs[1] = {o.out};
    static const char *const flags[1] = {"--out"};
    if (rc == CLI_OK) rc = cli_check_outputs("kernel", ins, 1, outs, flags, 1);
    if (rc != CLI_OK) return rc;
    return run(&o) == LUCENT_OK ? CLI_OK : cli_fail();
}
