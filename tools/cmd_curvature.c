/* `lucent curvature`: per-vertex curvature of a mesh (Rusinkiewicz 2004, Meyer et al. 2003,
 * Garimella & Swartz 2003), written as CSV or as a colour-mapped PLY (like the CDRF paper's
 * Figure 10a: mean curvature on a diverging map). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"
#include "lucent/image.h"
#include "lucent/mesh.h"

static const char k_usage[] =
    "usage: lucent curvature MESH [--method M] [--smooth N] [--out FILE.ply|.csv|.png] [options]\n"
    "\n"
    "Estimates the principal, mean and Gaussian curvature at every vertex of a triangle mesh\n"
    "(PLY ASCII or binary, .ply.gz, OBJ, glTF). Vertices at identical positions are welded.\n"
    "Sign: a sphere with outward normals has positive mean curvature. Units: inverse mesh units\n"
    "times 1/--mm-per-unit, i.e. mm^-1 when the scale is given.\n"
    "\n"
    "methods:\n"
    "  rusinkiewicz  per-face curvature tensors (Rusinkiewicz 2004), with directions (default)\n"
    "  meyer         cotangent Laplacian and angle deficit (Meyer et al. 2003)\n"
    "  garimella     area-weighted normal curvatures (Garimella & Swartz 2003)\n"
    "\n"
    "options:\n"
    "  --method M         the estimator (default rusinkiewicz)\n"
    "  --smooth N         average over the N-ring, weighted by vertex area (default 0)\n"
    "  --fast             rusinkiewicz without its normal-correcting second pass (about 2x\n"
    "                     faster; less accurate on irregular meshes)\n"
    "  --mm-per-unit S    millimetres per mesh unit (default 1)\n"
    "  --out FILE         .csv: one row per vertex (x, y, z, k1, k2, mean, gauss, flags);\n"
    "                     .ply: binary PLY, mean curvature colour-mapped (blue < 0 < red) plus\n"
    "                     the values as vertex properties (default: MESH-METHOD.ply here);\n"
    "                     .png: a picture of the colour-mapped mesh (Kubo et al. Fig. 10a)\n"
    "  --range R          |H| mapped to full colour (default: the 95th percentile of |H|)\n"
    "  --size WxH         .png: its size in pixels (default 800x800)\n"
    "  --view AZ,EL       .png: the eye's azimuth about +y and elevation, degrees (default 0,0:\n"
    "                     looking along -z with +y up)\n"
    "  -h, --help         show this help\n"
    "\n"
    "flags in the CSV: 1 boundary vertex, 2 invalid (no face of non-zero area; values 0).\n"
    "\n"
    "examples:\n"
    "  lucent curvature data/meshes/bunny.ply --out out/bunny-curv.ply\n"
    "  lucent curvature data/meshes/dragon_vrip_res2.ply.gz --smooth 1 --view 30,10 --out out/dragon-curv.png\n"
    "  lucent curvature data/meshes/dragon_vrip_res2.ply.gz --method meyer --smooth 2 --out out/d.csv\n";

typedef struct options {
    const char *mesh, *out;
    lucent_curvature_method method;
    int smooth, fast;
    double mm_per_unit, range, view[2];
    bool scale_given; /* --mm-per-unit: curvature in mm^-1, else per mesh unit */
    int size[2];
    char default_out[1024];
} options;

/* The colour bar beside a .png's picture: its text scale and its width in pixels, from the picture's height. */
static int bar_scale(int height) { return height >= 600 ? 2 : 1; }

static int colour_bar_margin(int height) { return 64 * bar_scale(height); }

static int parse_value_option(int argc, char **argv, int *i, options *o)
{
    const char *v;
    if (cli_option(argc, argv, i, "--method", &v)) {
        if (lucent_curvature_method_parse(v, &o->method) != LUCENT_OK)
            return cli_usage_error("curvature", "--method must be rusinkiewicz, meyer or garimella");
    } else if (cli_option(argc, argv, i, "--smooth", &v)) {
        if (!cli_parse_int(v, &o->smooth) || o->smooth > 1000)
            return cli_usage_error("curvature", "--smooth needs a whole number of rings from 0 to 1000");
    } else if (cli_option(argc, argv, i, "--mm-per-unit", &v)) {
        o->scale_given = true;
        if (!cli_parse_double(v, &o->mm_per_unit) || !(o->mm_per_unit > 0))
            return cli_usage_error("curvature", "--mm-per-unit needs a scale > 0");
    } else if (cli_option(argc, argv, i, "--range", &v)) {
        if (!cli_parse_double(v, &o->range) || !(o->range > 0))
            return cli_usage_error("curvature", "--range needs a curvature > 0");
    } else if (cli_option(argc, argv, i, "--size", &v)) {
        char tail;
        if (!v || sscanf(v, "%dx%d%c", &o->size[0], &o->size[1], &tail) != 2 || o->size[0] < 1 || o->size[1] < 1 ||
            o->size[0] > 16384 || o->size[1] > 16384)
            return cli_usage_error("curvature", "--size needs WIDTHxHEIGHT, 1 to 16384 pixels each (e.g. 800x600)");
        /* the .png holds the colour bar beside the picture: both must fit an image (issue 32: 16384x16384 was
         * refused by the PNG writer after the whole paint, 16 s and 4.7 GB later) */
        int64_t w = (int64_t)o->size[0] + colour_bar_margin(o->size[1]), h = o->size[1];
        if ((uint64_t)(w * h) > LUCENT_IMAGE_MAX_PIXELS)
            return cli_usage_error(
                "curvature",
                "--size %dx%d: the picture with its colour bar is %lld x %lld pixels, above the "
                "image limit of %llu (2^28) pixels; at most %lldx%d at this height",
                o->size[0], o->size[1], (long long)w, (long long)h, (unsigned long long)LUCENT_IMAGE_MAX_PIXELS,
                (long long)(LUCENT_IMAGE_MAX_PIXELS / (uint64_t)h) - colour_bar_margin(o->size[1]), o->size[1]);
    } else if (cli_option(argc, argv, i, "--view", &v)) {
        char tail;
        if (!v || sscanf(v, "%lf,%lf%c", &o->view[0], &o->view[1], &tail) != 2 || !isfinite(o->view[0]) ||
            !(fabs(o->view[1]) <= 90))
            return cli_usage_error("curvature", "--view needs AZIMUTH,ELEVATION in degrees, elevation in [-90, 90]");
    } else if (cli_option(argc, argv, i, "--out", &v)) {
        if (!(o->out = v)) return cli_usage_error("curvature", "--out needs a file name (.ply, .csv or .png)");
    } else {
        return -1;
    }
    return CLI_OK;
}

static int parse_args(int argc, char **argv, options *o)
{
    for (int i = 1; i < argc; i++) {
        int rc = parse_value_option(argc, argv, &i, o);
        if (rc == CLI_OK) continue;
        if (rc != -1) return rc;
        if (strcmp(argv[i], "--fast") == 0) {
            o->fast = 1;
            continue;
        }
        if (argv[i][0] == '-' && argv[i][1]) return cli_usage_error("curvature", "unknown option '%s'", argv[i]);
        if (o->mesh) return cli_usage_error("curvature", "one mesh at a time (got '%s' and '%s')", o->mesh, argv[i]);
        o->mesh = argv[i];
    }
    if (!o->mesh) return cli_usage_error("curvature", "expected a mesh file");
    if (!o->out) {
        const char *base = strrchr(o->mesh, '/') ? strrchr(o->mesh, '/') + 1 : o->mesh;
        size_t n = strcspn(base, ".");
        snprintf(o->default_out, sizeof o->default_out, "%.*s-%s.ply", (int)n, base,
                 lucent_curvature_method_name(o->method));
        o->out = o->default_out;
    }
    size_t n = strlen(o->out);
    if (n < 4 || (strcasecmp(o->out + n - 4, ".ply") != 0 && strcasecmp(o->out + n - 4, ".csv") != 0 &&
                  strcasecmp(o->out + n - 4, ".png") != 0))
        return cli_usage_error("curvature", "--out must end in .ply, .csv or .png");
    return CLI_OK;
}

/* ---- outputs ---- */

/* The k-th smallest of a[0..n) (Hoare's selection, median-of-three pivots; a is reordered): the value
 * a full sort would put at a[k], in linear expected time. */
static double select_kth(double *a, size_t n, size_t k)
{
    size_t lo = 0, hi = n - 1;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        double x = a[lo], y = a[mid], z = a[hi];
        double pivot = x < y ? (y < z ? y : (x < z ? z : x)) : (x < z ? x : (y < z ? z : y));
        size_t i = lo, j = hi;
        while (i <= j) {
            while (a[i] < pivot) i++;
            while (a[j] > pivot) j--;
            if (i <= j) {
                double t = a[i];
                a[i] = a[j], a[j] = t;
                i++;
                if (j == 0) break;
                j--;
            }
        }
        if (k <= j && j != (size_t)-1)
            hi = j;
        else if (k >= i)
            lo = i;
        else
            return a[k];
    }
    return a[k];
}

/* The 50% and 95% quantiles of |H| over valid vertices (0 when none), from one copy (selection
 * only reorders it). */
static void abs_quantiles(const lucent_curvature *c, double dest[2])
{
    double *a = malloc((c->count + 1) * sizeof *a);
    size_t n = 0;
    for (size_t v = 0; a && v < c->count; v++)
        if (!(c->flags[v] & LUCENT_CURVATURE_INVALID)) a[n++] = fabs(c->mean[v]);
    dest[0] = a && n ? select_kth(a, n, (size_t)(0.5 * (double)(n - 1))) : 0;
    dest[1] = a && n ? select_kth(a, n, (size_t)(0.95 * (double)(n - 1))) : 0;
    free(a);
}

/* Diverging map: blue (-range) -> white (0) -> red (+range); invalid vertices grey. */
static void colour(double h, double range, int invalid, uint8_t *rgb)
{
    if (invalid) {
        rgb[0] = rgb[1] = rgb[2] = 128;
        return;
    }
    double t = fmax(-1, fmin(1, h / range)), a = 1 - fabs(t);
    double r = t > 0 ? 1 : a, g = a, b = t < 0 ? 1 : a;
    rgb[0] = (uint8_t)lrint(255 * (0.2 + 0.8 * r)), rgb[1] = (uint8_t)lrint(255 * (0.2 + 0.8 * g));
    rgb[2] = (uint8_t)lrint(255 * (0.2 + 0.8 * b));
}

/* The picture with a colour bar at its right: the map from -range (concave, blue) through 0 to +range
 * (convex, red), labelled in mm^-1 (per mesh unit without --mm-per-unit). */
static lucent_status add_colour_bar(lucent_image **img, double range, bool mm)
{
    lucent_image *src = *img, *dst = NULL;
    int s = bar_scale(src->height), margin = colour_bar_margin(src->height), w = src->width + margin, h = src->height;
    lucent_status st = lucent_image_create(w, h, 3, &dst);
    if (st != LUCENT_OK) return st;
    for (int c = 0; c < 3; c++) lucent_image_fill(dst, c, 0.05f); /* the painter's background */
    for (int y = 0; y < h; y++)
        for (int x = 0; x < src->width; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(dst, x, y, c, lucent_image_get(src, x, y, c));
    int x0 = src->width + 4 * s, y0 = h / 8 + 20 * s, y1 = h - h / 8, bw = 10 * s;
    for (int y = y0; y <= y1; y++) {
        uint8_t rgb[3];
        colour(range * (1 - 2.0 * (y - y0) / (y1 - y0)), range, 0, rgb);
        for (int x = x0; x < x0 + bw; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(dst, x, y, c, lucent_srgb_decode(rgb[c] / 255.0f));
    }
    static const float white[3] = {0.8f, 0.8f, 0.8f};
    char text[32];
    lucent_image_draw_text(dst, x0, h / 8 - 2 * s, s, white, "mean H");
    lucent_image_draw_text(dst, x0, h / 8 + 8 * s, s, white, mm ? "mm^-1" : "1/unit");
    snprintf(text, sizeof text, "%+.3g", range);
    lucent_image_draw_text(dst, x0 + bw + 3 * s, y0, s, white, text);
    lucent_image_draw_text(dst, x0 + bw + 3 * s, (y0 + y1) / 2 - 3 * s, s, white, "0");
    snprintf(text, sizeof text, "%+.3g", -range);
    lucent_image_draw_text(dst, x0 + bw + 3 * s, y1 - 7 * s, s, white, text);
    lucent_image_destroy(src);
    *img = dst;
    return LUCENT_OK;
}

/* The colour-mapped mesh as a PLY (with the values as vertex properties) or as a picture. */
static lucent_status write_colours(const char *path, const options *o, const lucent_mesh *m, const lucent_curvature *c,
                                   double range)
{
    uint8_t *rgb = malloc(3 * m->vertex_count + 1);
    if (!rgb) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", path);
    for (size_t v = 0; v < m->vertex_count; v++)
        colour(c->mean[v], range, c->flags[v] & LUCENT_CURVATURE_INVALID, rgb + 3 * v);
    lucent_status s;
    if (strcasecmp(path + strlen(path) - 4, ".png") == 0) {
        lucent_image *img = NULL;
        lucent_mesh_paint_desc d = {.width = o->size[0],
                                    .height = o->size[1],
                                    .azimuth = o->view[0],
                                    .elevation = o->view[1],
                                    .colors = rgb,
                                    .background = {0.05f, 0.05f, 0.05f}};
        s = lucent_mesh_paint(m, &d, &img);
        if (s != LUCENT_OK) s = lucent_error_context(s, "%s: --size %dx%d", path, o->size[0], o->size[1]);
        if (s == LUCENT_OK && (s = add_colour_bar(&img, range, o->scale_given)) != LUCENT_OK)
            s = lucent_error_context(s, "%s: --size %dx%d with the colour bar", path, o->size[0], o->size[1]);
        if (s == LUCENT_OK) s = lucent_image_write(path, img, NULL);
        lucent_image_destroy(img);
    } else {
        const char *names[] = {"k1", "k2", "mean", "gauss"};
        const double *values[] = {c->k1, c->k2, c->mean, c->gauss};
        s = lucent_mesh_write_ply(path, m, &(lucent_mesh_ply_extra){rgb, 4, names, values});
    }
    free(rgb);
    return s;
}

static void report(const options *o, const lucent_mesh *m, const lucent_curvature *c, double t, const double q[2],
                   double range)
{
    lucent_mesh_stats st;
    if (lucent_mesh_stats_compute(m, &st) == LUCENT_OK)
        cli_info("%s: %zu vertices, %zu faces; %zu boundary edges, %zu non-manifold edges, %zu zero-area faces",
                 o->mesh, m->vertex_count, m->face_count, st.boundary_edges, st.nonmanifold_edges, st.degenerate_faces);
    const char *unit = o->scale_given ? "mm^-1" : "1/mesh unit; --mm-per-unit gives mm^-1";
    cli_info("%s: %.3f s; %zu vertices without a usable neighbourhood (set to 0); mean curvature |H| 50%% %.4g, "
             "95%% %.4g, colour range %.4g (%s)",
             lucent_curvature_method_name(o->method), t, c->invalid_count, q[0], q[1], range, unit);
}

int cmd_curvature(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) return fputs(k_usage, stdout), CLI_OK;
    options o = {.mm_per_unit = 1};
    int rc = parse_args(argc, argv, &o);
    const char *ins[1] = {o.mesh}, *outs[1] = {o.out};
    static const char *const flags[1] = {"--out"};
    if (rc == CLI_OK) rc = cli_check_outputs("curvature", ins, 1, outs, flags, 1);
    if (rc != CLI_OK) return rc;
    lucent_mesh *m;
    if (lucent_mesh_load(o.mesh, NULL, &m) != LUCENT_OK) return cli_fail();
    lucent_curvature c = {0};
    lucent_curvature_desc d = {
        .method = o.method, .smooth_rings = o.smooth, .mm_per_unit = o.mm_per_unit, .pool = cli_pool(), .fast = o.fast};
    double t0 = lucent_clock_seconds();
    lucent_status s = lucent_mesh_curvature(m, &d, &c);
    double t = lucent_clock_seconds() - t0;
    if (s == LUCENT_OK) {
        double q[2];
        abs_quantiles(&c, q);
        double range = o.range > 0 ? o.range : q[1];
        if (!(range > 0)) range = 1;
        size_t n = strlen(o.out);
        s = strcasecmp(o.out + n - 4, ".csv") == 0 ? lucent_curvature_write_csv(o.out, m, &c)
                                                   : write_colours(o.out, &o, m, &c, range);
        if (s == LUCENT_OK) report(&o, m, &c, t, q, range), cli_wrote("wrote %s", o.out);
    }
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
