/* `lucent cdrf-lut` and `lucent cdrf-fit`: the curvature-dependent reflectance function of Kubo,
 * Dobashi & Morishima as a look-up table, and sigma0 fitted to Monte Carlo spheres of a material. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "lucent/cdrf.h"
#include "lucent/eval.h"

enum { MAX_OUTS = 8, MAX_RADII = LUCENT_CDRF_FIT_MAX_RADII };

static const char k_lut_usage[] =
    "usage: lucent cdrf-lut [--variant kubo|collomb] [options] --out FILE...\n"
    "\n"
    "Tabulates the curvature-dependent reflectance function (Kubo, Dobashi & Morishima 2011,\n"
    "section V): column i holds cos theta = -1 + 2 i / (width - 1), row j (top first) holds\n"
    "sigma = sigma0 kappa = sigma_max j / (height - 1) radians. Single-channel float.\n"
    "\n"
    "options:\n"
    "  --variant V     kubo (Eq. 1-3: max(cos, 0) convolved with a Gaussian, the default) or\n"
    "                  collomb (the blog's closed-form fit, its kappa read as sigma)\n"
    "  --width N       cos theta samples (default 256)\n"
    "  --height N      sigma samples (default 256)\n"
    "  --sigma-max S   largest sigma in radians (default 3)\n"
    "  --out FILE      output by extension: .exr, .pfm, or .c/.h (a C array); may be repeated\n"
    "                  (default: cdrf-VARIANT.exr)\n"
    "  --name NAME     the C array's name (default lucent_cdrf_lut)\n"
    "  -h, --help      show this help\n"
    "\n"
    "examples:\n"
    "  lucent cdrf-lut --out lut.exr\n"
    "  lucent cdrf-lut --variant collomb --width 128 --height 64 --out lut.pfm --out lut.c\n";

static const char k_fit_usage[] =
    "usage: lucent cdrf-fit MATERIAL [--radii R1,R2,...] [options]\n"
    "\n"
    "Simulates spheres of MATERIAL (a preset, FILE.json or FILE.json#NAME) of the given radii (mm)\n"
    "under a directional light from the side, seen from the front (Kubo et al., Figure 6), by Monte\n"
    "Carlo transport through a dielectric boundary; scores the radiance toward the camera against\n"
    "the angle theta between the normal and the light; fits sigma0 (mm) and the albedo scale k_d\n"
    "per channel by weighted least squares, and Lambert (sigma0 = 0) for comparison. Prints sigma0\n"
    "and the RMS errors over the equator's pixels; writes PREFIX.json, PREFIX.csv (the data) and PREFIX.svg (data and "
    "fits).\n"
    "\n"
    "options:\n"
    "  --radii LIST       sphere radii in mm (default 2,5,10,20)\n"
    "  --photons N        photons per channel and sphere (default 400000)\n"
    "  --bins N           theta bins over [0, 180] degrees (default 36)\n"
    "  --cone DEG         half-angle of the camera's acceptance cone (default 11.46 = 0.2 rad)\n"
    "  --roughness A      GGX alpha of the boundary (default 0: smooth, Fresnel)\n"
    "  --variant V        kubo (default) or collomb, the function fitted\n"
    "  --sigma0-max MM    upper end of the sigma0 search (default 20)\n"
    "  --seed S           seed (default 1)\n"
    "  --out PREFIX|DIR/  output prefix (default NAME-cdrf); ending in '/': a folder, with\n"
    "                     NAME-cdrf inside it\n"
    "  -h, --help         show this help\n"
    "\n"
    "example:\n"
    "  lucent cdrf-fit skin1 --radii 2,5,10,20 --out out/skin1-cdrf\n";

static bool parse_u64(const char *text, uint64_t *dest)
{
    double v;
    if (!cli_parse_double(text, &v) || v < 0 || v > 1e15 || v != floor(v)) return false;
    *dest = (uint64_t)v;
    return true;
}

/* ---- cdrf-lut ---- */

typedef struct lut_options {
    lucent_cdrf_lut_desc desc;
    const char *outs[MAX_OUTS];
    int out_count;
    const char *name;
} lut_options;

static int parse_lut_args(int argc, char **argv, lut_options *o)
{
    for (int i = 1; i < argc; i++) {
        const char *v;
        if (cli_option(argc, argv, &i, "--variant", &v)) {
            if (lucent_cdrf_variant_parse(v, &o->desc.variant) != LUCENT_OK)
                return cli_usage_error("cdrf-lut", "--variant must be kubo or collomb");
        } else if (cli_option(argc, argv, &i, "--width", &v)) {
            if (!cli_parse_int(v, &o->desc.width) || o->desc.width < 2 || o->desc.width > 8192)
                return cli_usage_error("cdrf-lut", "--width needs a whole number from 2 to 8192");
        } else if (cli_option(argc, argv, &i, "--height", &v)) {
            if (!cli_parse_int(v, &o->desc.height) || o->desc.height < 2 || o->desc.height > 8192)
                return cli_usage_error("cdrf-lut", "--height needs a whole number from 2 to 8192");
        } else if (cli_option(argc, argv, &i, "--sigma-max", &v)) {
            if (!cli_parse_double(v, &o->desc.sigma_max) || !(o->desc.sigma_max > 0) || o->desc.sigma_max > 100)
                return cli_usage_error("cdrf-lut", "--sigma-max needs an angle in (0, 100] radians");
        } else if (cli_option(argc, argv, &i, "--out", &v)) {
            if (!v) return cli_usage_error("cdrf-lut", "--out needs a file name");
            if (o->out_count == MAX_OUTS) return cli_usage_error("cdrf-lut", "at most %d --out files", MAX_OUTS);
            o->outs[o->out_count++] = v;
        } else if (cli_option(argc, argv, &i, "--name", &v)) {
            if (!v) return cli_usage_error("cdrf-lut", "--name needs a C identifier");
            for (const char *p = v; *p; p++)
                if (!((*p >= 'a' && *p <= 'z') || (*p >= 'A' && *p <= 'Z') || *p == '_' ||
                      (p > v && *p >= '0' && *p <= '9')))
                    return cli_usage_error("cdrf-lut", "--name '%s' is not a C identifier", v);
            o->name = v;
        } else {
            return cli_usage_error("cdrf-lut", argv[i][0] == '-' ? "unknown option '%s'" : "unexpected argument '%s'",
                                   argv[i]);
        }
    }
    return CLI_OK;
}

static const char *lut_extension_check(const lut_options *o)
{
    static const char *const exts[] = {".exr", ".pfm", ".c", ".h"};
    for (int k = 0; k < o->out_count; k++) {
        const char *p = o->outs[k], *dot = strrchr(p, '.');
        bool ok = false;
        for (int e = 0; e < 4 && dot; e++) ok |= strcasecmp(dot, exts[e]) == 0;
        if (!ok) return p;
    }
    return NULL;
}

/* Prints what the acceptance checks say about the table. */
static void lut_summary(const lucent_image *lut, const lucent_cdrf_lut_desc *d)
{
    int w = lut->width, h = lut->height;
    double dev = 0;
    for (int i = 0; i < w; i++) dev = fmax(dev, fabs(lut->data[i] - fmax(-1.0 + 2.0 * i / (w - 1), 0.0)));
    bool peak_falls = true, shadow_rises = true;
    for (int j = 1; j < h; j++) {
        const float *row = lut->data + (size_t)j * (size_t)w, *up = row - w;
        peak_falls &= row[w - 1] <= up[w - 1];
        for (int i = 0; i < w && -1.0 + 2.0 * i / (w - 1) <= 0; i++) shadow_rises &= row[i] >= up[i];
    }
    cli_info("cdrf-lut: %s, %d x %d (cos theta in [-1, 1] x sigma in [0, %g])", lucent_cdrf_variant_name(d->variant), w,
             h, d->sigma_max ? d->sigma_max : 3.0);
    cli_info("  row sigma = 0: max |LUT - max(cos theta, 0)| = %.3g", dev);
    cli_info("  widening with sigma: peak falls monotonically: %s; shadow (cos <= 0) rises monotonically: %s",
             peak_falls ? "yes" : "no", shadow_rises ? "yes" : "no");
}

int cmd_cdrf_lut(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_lut_usage, stdout);
        return CLI_OK;
    }
    lut_options o = {0};
    int rc = parse_lut_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    char def[64];
    if (!o.out_count) {
        snprintf(def, sizeof def, "cdrf-%s.exr", lucent_cdrf_variant_name(o.desc.variant));
        o.outs[o.out_count++] = def;
    }
    const char *bad = lut_extension_check(&o);
    if (bad) return cli_usage_error("cdrf-lut", "--out '%s': use .exr, .pfm or .c", bad);
    const char *flags[MAX_OUTS];
    for (int k = 0; k < o.out_count; k++) flags[k] = "--out";
    if ((rc = cli_check_outputs("cdrf-lut", NULL, 0, o.outs, flags, o.out_count)) != CLI_OK) return rc;
    o.desc.pool = cli_pool();
    lucent_image *lut = NULL;
    lucent_status s = lucent_cdrf_lut_build(&o.desc, &lut);
    double smax = o.desc.sigma_max ? o.desc.sigma_max : 3.0;
    for (int k = 0; k < o.out_count && s == LUCENT_OK; k++) {
        s = lucent_cdrf_lut_write(o.outs[k], lut, smax, o.name);
        if (s == LUCENT_OK) cli_wrote("wrote %s", o.outs[k]);
    }
    if (s == LUCENT_OK) lut_summary(lut, &o.desc);
    lucent_image_destroy(lut);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}

/* ---- cdrf-fit ---- */

typedef struct fit_options {
    const char *spec, *out;
    lucent_material material;
    double radii[MAX_RADII];
    int radius_count;
    uint64_t photons, seed;
    int bins;
    double cone_deg, roughness, sigma0_max;
    lucent_cdrf_variant variant;
} fit_options;

static int parse_radii(const char *list, fit_options *o)
{
    char buf[512];
    if (!list) return cli_usage_error("cdrf-fit", "--radii needs a list of radii in mm");
    snprintf(buf, sizeof buf, "%s", list);
    o->radius_count = 0;
    for (char *save, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        double r;
        if (!cli_parse_double(t, &r) || !(r >= LUCENT_CDRF_SPHERE_MIN_RADIUS && r <= LUCENT_CDRF_SPHERE_MAX_RADIUS))
            return cli_usage_error("cdrf-fit", "--radii: '%s' is not a radius from %g to %g (mm)", t,
                                   LUCENT_CDRF_SPHERE_MIN_RADIUS, LUCENT_CDRF_SPHERE_MAX_RADIUS);
        if (o->radius_count == MAX_RADII) return cli_usage_error("cdrf-fit", "--radii: at most %d radii", MAX_RADII);
        o->radii[o->radius_count++] = r;
    }
    return o->radius_count ? CLI_OK : cli_usage_error("cdrf-fit", "--radii needs a list of radii in mm");
}

static int parse_fit_number(int argc, char **argv, int *i, fit_options *o)
{
    const char *v;
    if (cli_option(argc, argv, i, "--photons", &v))
        return parse_u64(v, &o->photons) && o->photons >= 100
                   ? CLI_OK
                   : cli_usage_error("cdrf-fit", "--photons needs a whole number >= 100");
    if (cli_option(argc, argv, i, "--seed", &v))
        return parse_u64(v, &o->seed) ? CLI_OK : cli_usage_error("cdrf-fit", "--seed needs a whole number >= 0");
    if (cli_option(argc, argv, i, "--bins", &v))
        return cli_parse_int(v, &o->bins) && o->bins >= 2 && o->bins <= LUCENT_CDRF_MAX_BINS
                   ? CLI_OK
                   : cli_usage_error("cdrf-fit", "--bins needs a count from 2 to %d", LUCENT_CDRF_MAX_BINS);
    if (cli_option(argc, argv, i, "--cone", &v))
        return cli_parse_double(v, &o->cone_deg) && o->cone_deg > 0 && o->cone_deg <= 90
                   ? CLI_OK
                   : cli_usage_error("cdrf-fit", "--cone needs an angle in (0, 90] degrees");
    if (cli_option(argc, argv, i, "--roughness", &v))
        return cli_parse_double(v, &o->roughness) && o->roughness >= 0 && o->roughness <= 1
                   ? CLI_OK
                   : cli_usage_error("cdrf-fit", "--roughness needs a GGX alpha in [0, 1]");
    if (cli_option(argc, argv, i, "--sigma0-max", &v))
        return cli_parse_double(v, &o->sigma0_max) && o->sigma0_max > 0 && o->sigma0_max <= 1e4
                   ? CLI_OK
                   : cli_usage_error("cdrf-fit", "--sigma0-max needs a length > 0 (mm)");
    return -1;
}

static int parse_fit_args(int argc, char **argv, fit_options *o)
{
    int rc = CLI_OK;
    for (int i = 1; i < argc && rc == CLI_OK; i++) {
        const char *v;
        if ((rc = parse_fit_number(argc, argv, &i, o)) != -1) continue;
        rc = CLI_OK;
        if (cli_option(argc, argv, &i, "--radii", &v))
            rc = parse_radii(v, o);
        else if (cli_option(argc, argv, &i, "--variant", &v))
            rc = lucent_cdrf_variant_parse(v, &o->variant) == LUCENT_OK
                     ? CLI_OK
                     : cli_usage_error("cdrf-fit", "--variant must be kubo or collomb");
        else if (cli_option(argc, argv, &i, "--out", &v))
            rc = (o->out = v) ? CLI_OK : cli_usage_error("cdrf-fit", "--out needs a file prefix");
        else if (argv[i][0] == '-' && argv[i][1])
            rc = cli_usage_error("cdrf-fit", "unknown option '%s'", argv[i]);
        else if (o->spec)
            rc = cli_usage_error("cdrf-fit", "one material at a time (got '%s' and '%s')", o->spec, argv[i]);
        else
            o->spec = argv[i];
    }
    if (rc == CLI_OK && !o->spec) rc = cli_usage_error("cdrf-fit", "expected a material");
    return rc;
}

static const char *const k_channel[] = {"R", "G", "B"};

/* Before the fit: PREFIX.json, .csv, .svg must not name the material file; a usage error. */
static int check_fit_outputs(const fit_options *o, const char *prefix)
{
    static const char *const exts[3] = {"json", "csv", "svg"}, *const flags[3] = {"--out", "--out", "--out"};
    char file[1024], paths[3][600];
    const char *ins[1] = {cli_spec_file(o->spec, file, sizeof file)}, *outs[3];
    for (int k = 0; k < 3; k++) snprintf(paths[k], sizeof paths[k], "%s.%s", prefix, exts[k]), outs[k] = paths[k];
    return cli_check_outputs("cdrf-fit", ins, 1, outs, flags, 3);
}

static lucent_status run_fit(fit_options *o, const char *prefix)
{
    lucent_status s = LUCENT_OK;
    lucent_cdrf_sphere_result *sp = NULL;
    lucent_cdrf_fit fit;
    lucent_cdrf_material_fit_desc fd = {.material = &o->material,
                                        .variant = o->variant,
                                        .radii = o->radii,
                                        .radius_count = o->radius_count,
                                        .photons = o->photons,
                                        .bins = o->bins,
                                        .roughness = o->roughness,
                                        .cone = o->cone_deg * M_PI / 180,
                                        .seed = o->seed,
                                        .sigma0_max = o->sigma0_max,
                                        .pool = cli_pool()};
    s = lucent_cdrf_fit_material(&fd, &fit, &sp);
    char path[600];
    static const char *const exts[] = {"json", "csv", "svg"};
    lucent_cdrf_fit_report report = {.material = &o->material,
                                     .spheres = sp,
                                     .sphere_count = o->radius_count,
                                     .fit = &fit,
                                     .seed = o->seed,
                                     .cone = o->cone_deg * M_PI / 180,
                                     .roughness = o->roughness};
    for (int k = 0; k < 3 && s == LUCENT_OK; k++) {
        snprintf(path, sizeof path, "%s.%s", prefix, exts[k]);
        s = k == 0   ? lucent_cdrf_fit_write_json(path, &report)
            : k == 1 ? lucent_cdrf_fit_write_csv(path, &report)
                     : lucent_cdrf_fit_write_svg(path, &report);
        if (s == LUCENT_OK) cli_wrote("wrote %s", path);
    }
    if (s == LUCENT_OK) {
        printf("%s: CDRF (%s) fitted to %d spheres, %llu photons per channel each\n", o->material.name,
               lucent_cdrf_variant_name(fit.variant), o->radius_count, (unsigned long long)sp[0].photons);
        printf("channel  sigma0_mm  k_d       rms_cdrf   rms_lambert  better\n");
        for (int c = 0; c < 3; c++)
            printf("%-7s  %-9.4g  %-8.4g  %-9.4g  %-11.4g  %s\n", k_channel[c], fit.sigma0[c], fit.kd[c], fit.rms[c],
                   fit.lambert_rms[c], fit.rms[c] < fit.lambert_rms[c] ? "cdrf" : "lambert");
    }
    free(sp);
    return s;
}

int cmd_cdrf_fit(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_fit_usage, stdout);
        return CLI_OK;
    }
    fit_options o = {.radii = LUCENT_CDRF_FIT_RADII,
                     .radius_count = LUCENT_CDRF_FIT_RADIUS_COUNT,
                     .photons = 400000,
                     .seed = 1,
                     .bins = 36,
                     .cone_deg = 0.2 * 180 / M_PI};
    int rc = parse_fit_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    if (lucent_material_resolve(o.spec, &o.material) != LUCENT_OK) return cli_fail();
    if (lucent_skin_resolve(&o.material) != LUCENT_OK) return cli_fail(); /* a skin: its equivalent medium */
    char prefix[512], name[128];
    snprintf(name, sizeof name, "%s-cdrf", o.material.name);
    cli_out_prefix(o.out, name, prefix, sizeof prefix);
    if ((rc = check_fit_outputs(&o, prefix)) != CLI_OK) return rc;
    return run_fit(&o, prefix) == LUCENT_OK ? CLI_OK : cli_fail();
}
