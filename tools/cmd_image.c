/* `lucent image`: inspect, convert and compare images (PNG, OpenEXR, PFM). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"

static const char k_usage[] =
    "usage: lucent image info FILE [--json]\n"
    "       lucent image convert IN OUT [--exposure E] [--tonemap OP] [--bits 8|16] [--half]\n"
    "       lucent image diff A B [--mask M] [--out FILE] [--relative] [--scale S] [--json]\n"
    "       lucent image <subcommand> --help\n\n"
    "Images are read as linear float RGB(A): PNG (sRGB-decoded), OpenEXR, PFM; the format\n"
    "follows the extension (.png, .exr, .pfm).\n";

static const char k_info_usage[] =
    "usage: lucent image info FILE [--json]\n\n"
    "Prints the size, the channels and per-channel min, max and mean of the finite values\n"
    "(with a count of NaN/inf values when there are any).\n"
    "  --json   print the same as a JSON object\n";

static const char k_convert_usage[] =
    "usage: lucent image convert IN OUT [options]\n\n"
    "Converts between PNG, OpenEXR and PFM (by extension), optionally tonemapping.\n"
    "  --exposure E    multiply by 2^E first (stops; default 0)\n"
    "  --tonemap OP    none (default), clamp, reinhard (x/(1+x)) or filmic (Narkowicz 2015 ACES fit)\n"
    "  --bits 8|16     PNG bit depth (default 8); samples are sRGB-encoded at both depths\n"
    "  --half          write OpenEXR half floats (default: 32-bit float)\n"
    "A PFM holds 1 or 3 channels: an alpha channel is dropped.\n";

static const char k_diff_usage[] =
    "usage: lucent image diff A B [options]\n\n"
    "Compares image A with the reference B and prints, per channel and over all channels,\n"
    "  RMS           sqrt(mean((A - B)^2))\n"
    "  relative RMS  RMS / sqrt(mean(B^2))\n"
    "  max |A - B|\n"
    "An alpha channel in only one image is dropped; a grey image is compared as grey RGB.\n"
    "  --mask M      count only the pixels where M (its luminance, linear) is > 0.5\n"
    "  --out FILE    .png: a false-colour heat map of the per-pixel error (mean over colour\n"
    "                channels) with its colour bar and scale below it; .exr/.pfm: the signed\n"
    "                difference A - B\n"
    "  --relative    heat map of |A - B| / (|B| + 0.01) instead of |A - B|\n"
    "  --scale S     the error drawn white (a fixed scale, so that maps compare); default: the\n"
    "                99th percentile of this map's errors\n"
    "  --json        print the results as a JSON object\n";

static const char *const k_channel_names[4][4] = {{"Y"}, {0}, {"R", "G", "B"}, {"R", "G", "B", "A"}};

/* ---- argument helpers ---- */

/* True when argv[*i] is the option name, as "--name VALUE" or "--name=VALUE"; *value receives
 * the value (NULL when missing) and *i moves past it. */
static bool take_option(int argc, char **argv, int *i, const char *name, const char **value)
{
    size_t n = strlen(name);
    if (strncmp(argv[*i], name, n) != 0) return false;
    if (argv[*i][n] == '=') {
        *value = argv[*i] + n + 1;
        return true;
    }
    if (argv[*i][n] != '\0') return false;
    *value = *i + 1 < argc ? argv[++*i] : NULL;
    return true;
}

/* Collects a positional argument into pos (at most max); false when there are too many. */
static bool add_positional(const char **pos, int *count, int max, const char *arg)
{
    if (*count >= max) return false;
    pos[(*count)++] = arg;
    return true;
}

static void print_json_string(const char *s)
{
    putchar('"');
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\')
            printf("\\%c", c);
        else if (c < 0x20)
            printf("\\u%04x", c);
        else
            putchar(c);
    }
    putchar('"');
}

/* A number for JSON: non-finite values become null. */
static void print_json_number(double v)
{
    if (isfinite(v))
        printf("%.9g", v);
    else
        printf("null");
}

/* ---- info ---- */

static void print_info_text(const char *path, const lucent_image *img, const lucent_image_stats *st)
{
    printf("%s: %dx%d, %d channel%s\n", path, img->width, img->height, img->channels, img->channels > 1 ? "s" : "");
    printf("  channel %14s %14s %14s\n", "min", "max", "mean");
    for (int c = 0; c < img->channels; c++) {
        printf("  %-7s %14.6g %14.6g %14.6g", k_channel_names[img->channels - 1][c], st->min[c], st->max[c],
               st->mean[c]);
        if (st->nonfinite[c]) printf("  (%llu NaN/inf)", (unsigned long long)st->nonfinite[c]);
        putchar('\n');
    }
}

static void print_info_json(const char *path, const lucent_image *img, const lucent_image_stats *st)
{
    printf("{\"file\": ");
    print_json_string(path);
    printf(", \"width\": %d, \"height\": %d, \"channels\": [", img->width, img->height);
    for (int c = 0; c < img->channels; c++) {
        printf("%s{\"name\": \"%s\", \"min\": ", c ? ", " : "", k_channel_names[img->channels - 1][c]);
        print_json_number(st->min[c]);
        printf(", \"max\": ");
        print_json_number(st->max[c]);
        printf(", \"mean\": ");
        print_json_number(st->mean[c]);
        printf(", \"nonfinite\": %llu}", (unsigned long long)st->nonfinite[c]);
    }
    printf("]}\n");
}

static int run_info(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_info_usage, stdout), CLI_OK;
    const char *pos[1];
    int npos = 0;
    bool json = false;
    for (int i = 1; i < argc; i++) {
        if (strcmp(argv[i], "--json") == 0)
            json = true;
        else if (argv[i][0] == '-' && argv[i][1])
            return cli_usage_error("image info", "unknown option '%s'", argv[i]);
        else if (!add_positional(pos, &npos, 1, argv[i]))
            return cli_usage_error("image info", "too many arguments ('%s')", argv[i]);
    }
    if (npos != 1) return cli_usage_error("image info", "expected one image file");
    lucent_image *img;
    if (lucent_image_load(pos[0], &img) != LUCENT_OK) return cli_fail();
    lucent_image_stats st;
    lucent_image_stats_compute(img, &st);
    if (json)
        print_info_json(pos[0], img, &st);
    else
        print_info_text(pos[0], img, &st);
    lucent_image_destroy(img);
    return CLI_OK;
}

/* ---- convert ---- */

typedef struct convert_args {
    const char *in, *out;
    lucent_tonemap_desc tonemap;
    int bits;
    bool half;
} convert_args;

static int parse_convert_option(int argc, char **argv, int *i, convert_args *a)
{
    const char *v, *cmd = "image convert";
    double e;
    if (take_option(argc, argv, i, "--exposure", &v)) {
        if (!cli_parse_double(v, &e) || fabs(e) > 100)
            return cli_usage_error(cmd, "--exposure needs a number of stops (|E| <= 100)");
        a->tonemap.exposure = (float)e;
    } else if (take_option(argc, argv, i, "--tonemap", &v)) {
        if (lucent_tonemap_op_parse(v, &a->tonemap.op) != LUCENT_OK)
            return cli_usage_error(cmd, "--tonemap must be none, clamp, reinhard or filmic");
    } else if (take_option(argc, argv, i, "--bits", &v)) {
        if (!cli_parse_int(v, &a->bits) || (a->bits != 8 && a->bits != 16))
            return cli_usage_error(cmd, "--bits must be 8 or 16");
    } else if (strcmp(argv[*i], "--half") == 0) {
        a->half = true;
    } else {
        return cli_usage_error(cmd, "unknown option '%s'", argv[*i]);
    }
    return CLI_OK;
}

static int parse_convert(int argc, char **argv, convert_args *a)
{
    const char *pos[2];
    int npos = 0;
    for (int i = 1; i < argc; i++) {
        if (argv[i][0] == '-' && argv[i][1]) {
            int rc = parse_convert_option(argc, argv, &i, a);
            if (rc != CLI_OK) return rc;
        } else if (!add_positional(pos, &npos, 2, argv[i])) {
            return cli_usage_error("image convert", "too many arguments ('%s')", argv[i]);
        }
    }
    if (npos != 2) return cli_usage_error("image convert", "expected an input and an output file");
    a->in = pos[0], a->out = pos[1];
    return CLI_OK;
}

/* Checks that the options fit the output format; returns CLI_OK or a usage error. */
static int check_convert_format(const convert_args *a, lucent_image_format f)
{
    if (a->bits && f != LUCENT_IMAGE_FORMAT_PNG)
        return cli_usage_error("image convert", "--bits applies to PNG outputs only");
    if (a->half && f != LUCENT_IMAGE_FORMAT_EXR)
        return cli_usage_error("image convert", "--half applies to OpenEXR outputs only");
    return CLI_OK;
}

/* Drops alpha for PFM outputs (which hold 1 or 3 channels). */
static lucent_status fit_channels(lucent_image **img, lucent_image_format f)
{
    if (f != LUCENT_IMAGE_FORMAT_PFM || (*img)->channels != 4) return LUCENT_OK;
    lucent_image *rgb;
    lucent_status s = lucent_image_convert_channels(*img, 3, &rgb);
    if (s != LUCENT_OK) return s;
    lucent_image_destroy(*img);
    *img = rgb;
    return LUCENT_OK;
}

static int run_convert(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_convert_usage, stdout), CLI_OK;
    convert_args a = {0};
    int rc = parse_convert(argc, argv, &a);
    const char *ins[1] = {a.in}, *outs[1] = {a.out};
    static const char *const flags[1] = {"OUT"};
    if (rc == CLI_OK) rc = cli_check_outputs("image convert", ins, 1, outs, flags, 1);
    if (rc != CLI_OK) return rc;
    lucent_image_format f;
    if (lucent_image_format_from_path(a.out, &f) != LUCENT_OK) return cli_fail();
    if ((rc = check_convert_format(&a, f)) != CLI_OK) return rc;
    lucent_image *img;
    if (lucent_image_load(a.in, &img) != LUCENT_OK) return cli_fail();
    lucent_image_tonemap(img, &a.tonemap);
    lucent_image_write_desc d = {.png_bits = a.bits, .exr_pixel = a.half ? LUCENT_EXR_PIXEL_HALF : 0};
    lucent_status s = fit_channels(&img, f);
    if (s == LUCENT_OK) s = lucent_image_write(a.out, img, &d);
    lucent_image_destroy(img);
    if (s != LUCENT_OK) return cli_fail();
    cli_wrote("wrote %s", a.out);
    return CLI_OK;
}

/* ---- diff ---- */

typedef struct diff_args {
    const char *a, *b, *mask, *out;
    bool relative, json;
    double scale; /* the error drawn white (0: the 99th percentile) */
} diff_args;

static int parse_diff(int argc, char **argv, diff_args *d)
{
    const char *pos[2], *cmd = "image diff";
    int npos = 0;
    for (int i = 1; i < argc; i++) {
        const char *v = NULL;
        if (take_option(argc, argv, &i, "--mask", &v)) {
            if (!v || !*v) return cli_usage_error(cmd, "--mask needs a file name");
            d->mask = v;
        } else if (take_option(argc, argv, &i, "--out", &v)) {
            if (!v || !*v) return cli_usage_error(cmd, "--out needs a file name");
            d->out = v;
        } else if (take_option(argc, argv, &i, "--scale", &v)) {
            if (!v || !cli_parse_double(v, &d->scale) || !(d->scale > 0) || d->scale > 1e30)
                return cli_usage_error(cmd, "--scale needs the error drawn white, a number > 0");
        } else if (strcmp(argv[i], "--relative") == 0) {
            d->relative = true;
        } else if (strcmp(argv[i], "--json") == 0) {
            d->json = true;
        } else if (argv[i][0] == '-' && argv[i][1]) {
            return cli_usage_error(cmd, "unknown option '%s'", argv[i]);
        } else if (!add_positional(pos, &npos, 2, argv[i])) {
            return cli_usage_error(cmd, "too many arguments ('%s')", argv[i]);
        }
    }
    if (npos != 2) return cli_usage_error(cmd, "expected two images: A and the reference B");
    d->a = pos[0], d->b = pos[1];
    return CLI_OK;
}

/* Replaces *img by a copy with `channels` channels (no-op when it has them). */
static lucent_status to_channels(lucent_image **img, int channels)
{
    if ((*img)->channels == channels) return LUCENT_OK;
    lucent_image *c;
    lucent_status s = lucent_image_convert_channels(*img, channels, &c);
    if (s != LUCENT_OK) return s;
    lucent_image_destroy(*img);
    *img = c;
    return LUCENT_OK;
}

/* Reads A, B and the mask; makes A and B comparable (RGB when their channels differ). */
static lucent_status load_diff_inputs(const diff_args *d, lucent_image *im[3])
{
    lucent_status s = lucent_image_load(d->a, &im[0]);
    if (s == LUCENT_OK) s = lucent_image_load(d->b, &im[1]);
    if (s == LUCENT_OK && d->mask) s = lucent_image_load(d->mask, &im[2]);
    if (s == LUCENT_OK && im[2]) s = to_channels(&im[2], 1);
    if (s == LUCENT_OK && im[0]->channels != im[1]->channels) {
        s = to_channels(&im[0], 3);
        if (s == LUCENT_OK) s = to_channels(&im[1], 3);
    }
    return s;
}

/* Writes the heat map or the difference; *scale receives the heat map's scale (0: none written). */
static lucent_status write_diff_output(const diff_args *d, const lucent_image *a, const lucent_image *b, float *scale)
{
    lucent_image_format f;
    lucent_status s = lucent_image_format_from_path(d->out, &f);
    lucent_image *out = NULL, *map = NULL;
    *scale = 0;
    if (s == LUCENT_OK && f == LUCENT_IMAGE_FORMAT_PNG) {
        s = lucent_image_error_map(a, b, d->relative, 0.0f, &map);
        if (s == LUCENT_OK)
            s = lucent_image_heatmap_with_bar(map, (float)d->scale, d->relative ? "(A-B)/(B+0.01)" : "A-B", &out,
                                              scale);
    } else if (s == LUCENT_OK) {
        s = lucent_image_difference(a, b, LUCENT_DIFF_SIGNED, &out);
        if (s == LUCENT_OK) s = fit_channels(&out, f);
    }
    if (s == LUCENT_OK) s = lucent_image_write(d->out, out, NULL);
    lucent_image_destroy(out);
    lucent_image_destroy(map);
    return s;
}

static void print_diff_text(const diff_args *d, const lucent_image *a, const lucent_image_error_stats *e)
{
    printf("%s vs %s: %dx%d, %d channel%s, %llu pixels compared%s\n", d->a, d->b, a->width, a->height, a->channels,
           a->channels > 1 ? "s" : "", (unsigned long long)e->pixel_count, d->mask ? " (under the mask)" : "");
    printf("  channel %14s %14s %14s\n", "RMS", "relative RMS", "max |A-B|");
    for (int c = 0; c < e->channels; c++)
        printf("  %-7s %14.6g %14.6g %14.6g\n", k_channel_names[e->channels - 1][c], e->rms[c], e->rel_rms[c],
               e->max_abs[c]);
    printf("  %-7s %14.6g %14.6g\n", "all", e->rms_all, e->rel_rms_all);
}

static void print_diff_json(const diff_args *d, const lucent_image *a, const lucent_image_error_stats *e, float scale)
{
    printf("{\"a\": ");
    print_json_string(d->a);
    printf(", \"b\": ");
    print_json_string(d->b);
    printf(", \"mask\": ");
    if (d->mask)
        print_json_string(d->mask);
    else
        printf("null");
    printf(", \"width\": %d, \"height\": %d, \"pixels\": %llu, \"channels\": [", a->width, a->height,
           (unsigned long long)e->pixel_count);
    for (int c = 0; c < e->channels; c++) {
        printf("%s{\"name\": \"%s\", \"rms\": ", c ? ", " : "", k_channel_names[e->channels - 1][c]);
        print_json_number(e->rms[c]);
        printf(", \"rel_rms\": ");
        print_json_number(e->rel_rms[c]);
        printf(", \"max_abs\": ");
        print_json_number(e->max_abs[c]);
        printf("}");
    }
    printf("], \"rms\": ");
    print_json_number(e->rms_all);
    printf(", \"rel_rms\": ");
    print_json_number(e->rel_rms_all);
    if (scale > 0) {
        printf(", \"heat_scale\": ");
        print_json_number(scale);
    }
    printf("}\n");
}

static int run_diff(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_diff_usage, stdout), CLI_OK;
    diff_args d = {0};
    int rc = parse_diff(argc, argv, &d);
    const char *ins[3] = {d.a, d.b, d.mask}, *outs[1] = {d.out};
    static const char *const flags[1] = {"--out"};
    if (rc == CLI_OK) rc = cli_check_outputs("image diff", ins, 3, outs, flags, 1);
    if (rc != CLI_OK) return rc;
    lucent_image_format f;
    if (d.out && lucent_image_format_from_path(d.out, &f) != LUCENT_OK) return cli_fail();
    lucent_image *im[3] = {NULL, NULL, NULL};
    lucent_image_error_stats e;
    lucent_status s = load_diff_inputs(&d, im);
    if (s == LUCENT_OK && (s = lucent_image_compare_masked(im[0], im[1], im[2], &e)) != LUCENT_OK)
        lucent_error_context(s, "%s vs %s%s%s", d.a, d.b, d.mask ? " under " : "", d.mask ? d.mask : "");
    float scale = 0;
    if (s == LUCENT_OK && d.out) s = write_diff_output(&d, im[0], im[1], &scale);
    if (s == LUCENT_OK) {
        if (d.json)
            print_diff_json(&d, im[0], &e, scale);
        else
            print_diff_text(&d, im[0], &e);
        if (d.out && !d.json && scale > 0)
            cli_wrote("wrote %s (heat map: white at %s %.4g, %s; the colour bar below it)", d.out,
                      d.relative ? "relative error" : "|A - B|", scale,
                      d.scale > 0 ? "--scale" : "the 99th percentile");
        else if (d.out && !d.json)
            cli_wrote("wrote %s", d.out);
    }
    for (int i = 0; i < 3; i++) lucent_image_destroy(im[i]);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}

int cmd_image(int argc, char **argv)
{
    if (argc < 2) return cli_usage_error("image", "expected a subcommand: info, convert or diff");
    const char *sub = argv[1];
    if (strcmp(sub, "--help") == 0 || strcmp(sub, "-h") == 0 || strcmp(sub, "help") == 0)
        return fputs(k_usage, stdout), CLI_OK;
    if (strcmp(sub, "info") == 0) return run_info(argc - 1, argv + 1);
    if (strcmp(sub, "convert") == 0) return run_convert(argc - 1, argv + 1);
    if (strcmp(sub, "diff") == 0) return run_diff(argc - 1, argv + 1);
    return cli_usage_error("image", "unknown subcommand '%s' (info, convert or diff)", sub);
}
