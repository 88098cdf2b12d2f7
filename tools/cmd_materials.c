/* `lucent materials`: lists material presets (or materials from files) with their derived
 * optical quantities, as aligned tables or as JSON. */
#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli.h"

static const char k_usage[] =
    "usage: lucent materials [NAME | FILE.json | FILE.json#NAME ...] [--json] [--out FILE]\n"
    "\n"
    "Prints materials with their derived quantities: reduced coefficients, albedos, the\n"
    "transport coefficient sigma_tr, the diffusion constant D, mean free paths and the\n"
    "classical-dipole total diffuse reflectance Rd (Jensen et al. 2001).\n"
    "Without arguments: the 11 measured presets of Jensen et al. 2001 and the spectral skins.\n"
    "Arguments name presets (case-insensitive) or material files (docs/materials.md).\n"
    "A spectral skin (docs/skin.md) shows its equivalent medium in the tables and, in tables\n"
    "of its own, its layers and the CIELAB colour, ITA and linear sRGB of its total diffuse\n"
    "reflectance under D65 (Monte Carlo per band, kept in the disk cache: $LUCENT_CACHE_DIR).\n"
    "\n"
    "options:\n"
    "  --json        print JSON (coefficients in mm^-1, lengths in mm) instead of tables\n"
    "  --out FILE    write that JSON to FILE (atomically) instead of printing it\n"
    "  --photons N   Monte Carlo photons per band of a spectral skin's colour (default 5000)\n"
    "  --swatches IMAGE\n"
    "                write a row of colour swatches, one per material, showing its total\n"
    "                diffuse reflectance Rd under white light (PNG, EXR or PFM by extension)\n"
    "  -h, --help    show this help\n"
    "\n"
    "examples:\n"
    "  lucent materials\n"
    "  lucent materials skin1 marble --json\n"
    "  lucent materials my_jade.json --out out/jade.json\n"
    "  lucent materials --swatches out/materials.png\n"
    "  lucent materials skin-light skin-dark\n";

typedef struct options {
    lucent_cache *cache; /* the skins' Monte Carlo colours */
    int photons;         /* per band for them (0: LUCENT_SKIN_COLOR_PHOTONS) */
    bool json;
    const char *out;
    const char *swatches;
    lucent_material *list;
    int count, capacity;
} options;

static lucent_status append(options *o, const lucent_material *m, int n)
{
    if (o->count + n > o->capacity) {
        int cap = o->capacity * 2 + n + 16;
        lucent_material *grown = realloc(o->list, (size_t)cap * sizeof *grown);
        if (!grown) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
        o->list = grown;
        o->capacity = cap;
    }
    memcpy(o->list + o->count, m, (size_t)n * sizeof *m);
    for (int i = 0; i < n; i++) { /* a spectral skin: its equivalent medium (lucent/skin.h) */
        lucent_status s = lucent_skin_resolve(&o->list[o->count + i]);
        if (s != LUCENT_OK) return s;
    }
    o->count += n;
    return LUCENT_OK;
}

static bool is_file_spec(const char *spec)
{
    size_t len = strlen(spec);
    return strchr(spec, '/') || strchr(spec, '#') || (len > 5 && strcasecmp(spec + len - 5, ".json") == 0);
}

/* Adds what spec names: one preset, one material of a file (FILE#NAME) or a whole file. */
static lucent_status add_spec(options *o, const char *spec)
{
    if (is_file_spec(spec) && !strchr(spec, '#')) {
        lucent_material *m;
        int n;
        lucent_status s = lucent_material_load(spec, &m, &n);
        if (s == LUCENT_OK) s = append(o, m, n);
        free(m);
        return s;
    }
    lucent_material m;
    lucent_status s = lucent_material_resolve(spec, &m);
    return s == LUCENT_OK ? append(o, &m, 1) : s;
}

static lucent_status add_presets(options *o)
{
    int n = lucent_material_preset_count();
    if (n == 0) return lucent_error(LUCENT_ERR_INTERNAL, "no presets: %s", lucent_last_error());
    for (int i = 0; i < n; i++) {
        lucent_material m;
        lucent_status s = lucent_material_preset(i, &m);
        if (s == LUCENT_OK) s = append(o, &m, 1);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

/* ---- tables ---- */

typedef struct row {
    lucent_material m;
    lucent_material_derived d;
} row;

typedef struct quantity {
    const char *title;
    size_t offset; /* of a double (the scalar) or double[3] in row */
} quantity;

typedef struct table {
    const char *title;
    quantity scalar;
    quantity rgb[3];
} table;

static const table k_tables[] = {
    {"Coefficients (mm^-1)",
     {"eta", offsetof(row, m.eta)},
     {{"sigma_a", offsetof(row, m.sigma_a)},
      {"sigma_s' = sigma_s(1-g)", offsetof(row, d.sigma_s_prime)},
      {"sigma_tr=sqrt(3 sa st')", offsetof(row, d.sigma_tr)}}},
    {"Albedos and total diffuse reflectance (classical dipole, Jensen et al. 2001)",
     {"Fdr", offsetof(row, d.fdr)},
     {{"albedo ss/st", offsetof(row, d.albedo)},
      {"reduced albedo a'", offsetof(row, d.albedo_prime)},
      {"Rd", offsetof(row, d.rd)}}},
    {"Lengths (mm)",
     {"A", offsetof(row, d.a)},
     {{"l' = 1/sigma_t'", offsetof(row, d.mfp_prime)},
      {"ld = 1/sigma_tr", offsetof(row, d.mfp_diffuse)},
      {"D = 1/(3 sigma_t')", offsetof(row, d.diffusion)}}},
};

static const double *at(const row *r, size_t offset) { return (const double *)((const char *)r + offset); }

/* Prints v in exactly 8 columns (a space, then 7 characters), as many decimals as fit. */
static void print_value(double v)
{
    double a = fabs(v);
    if (!isfinite(v) || a >= 1e5)
        printf(" %7.2g", v);
    else if (a >= 100)
        printf(" %7.1f", v);
    else
        printf(" %7.4f", v);
}

static void print_header(const table *t, int name_width)
{
    printf("%s\n%*s%6s", t->title, name_width, "", "");
    for (int q = 0; q < 3; q++) printf(q < 2 ? "  %-24.24s" : "  %.24s", t->rgb[q].title);
    printf("\n%-*s%6s", name_width, "name", t->scalar.title);
    for (int q = 0; q < 3; q++) printf("  %8s%8s%8s", "R", "G", "B");
    putchar('\n');
}

static void print_table(const table *t, const row *rows, int count, int name_width)
{
    print_header(t, name_width);
    for (int i = 0; i < count; i++) {
        printf("%-*s%6.3f", name_width, rows[i].m.name, *at(&rows[i], t->scalar.offset));
        for (int q = 0; q < 3; q++) {
            const double *v = at(&rows[i], t->rgb[q].offset);
            printf("  ");
            for (int c = 0; c < 3; c++) print_value(v[c]);
        }
        putchar('\n');
    }
    putchar('\n');
}

static void print_anisotropic(const row *rows, int count)
{
    for (int i = 0; i < count; i++) {
        const lucent_material *m = &rows[i].m;
        if (m->g[0] == 0 && m->g[1] == 0 && m->g[2] == 0) continue;
        printf("%s: g = (%.4g, %.4g, %.4g), sigma_s = (%.4g, %.4g, %.4g) mm^-1\n", m->name, m->g[0], m->g[1], m->g[2],
               m->sigma_s[0], m->sigma_s[1], m->sigma_s[2]);
    }
}

/* A skin's colour by the Monte Carlo per band (the truth; kept in the disk cache). */
static lucent_status skin_color(const options *o, const lucent_material *m, lucent_skin_color *c)
{
    lucent_skin_desc d = {
        .transport = "mc", .photons = (uint64_t)o->photons, .seed = 1, .pool = cli_pool(), .cache = o->cache};
    return lucent_skin_color_of(m, &d, c);
}

/* Prints a length in mm, or "inf" for a semi-infinite layer, in 8 columns. */
static void print_thickness(double v)
{
    if (isfinite(v))
        print_value(v);
    else
        printf(" %7s", "inf");
}

/* The spectral skins: their layers, then the colour of their total diffuse reflectance. */
static lucent_status print_skins(const options *o, int name_width)
{
    int skins = 0;
    for (int i = 0; i < o->count; i++) skins += o->list[i].skin.layer_count > 0;
    if (!skins) return LUCENT_OK;
    printf("Spectral skin layers (docs/skin.md; thickness in mm, inf: semi-infinite)\n"
           "%-*s %7s %7s %7s %7s %7s %7s %7s %7s\n",
           name_width, "name", "epi mm", "melanin", "eumel.", "derm mm", "blood", "oxy", "hypo mm", "blood");
    for (int i = 0; i < o->count; i++) {
        const lucent_skin *sk = &o->list[i].skin;
        if (!sk->layer_count) continue;
        printf("%-*s", name_width, o->list[i].name);
        for (int kind = 0; kind < 3; kind++) {
            const lucent_skin_layer *l = NULL;
            for (int k = 0; k < sk->layer_count; k++)
                if (sk->layer[k].kind == kind) l = &sk->layer[k];
            int columns = kind == 2 ? 2 : 3;
            if (!l) {
                for (int c = 0; c < columns; c++) printf(" %7s", "-");
                continue;
            }
            print_thickness(l->thickness);
            print_value(kind == LUCENT_SKIN_EPIDERMIS ? l->melanin : l->blood);
            if (columns == 3) print_value(kind == LUCENT_SKIN_EPIDERMIS ? l->eumelanin : l->oxygenation);
        }
        putchar('\n');
    }
    printf("\nSpectral skin colour: total diffuse reflectance (Monte Carlo, %d photons per band), %d bands over\n"
           "380-780 nm, CIE 1931 2 deg under D65\n"
           "%-*s %7s %7s %7s %7s  %-13s %7s %7s %7s\n",
           o->photons ? o->photons : LUCENT_SKIN_COLOR_PHOTONS, LUCENT_BANDS_DEFAULT, name_width, "name", "L*", "a*",
           "b*", "ITA", "ITA category", "R", "G", "B");
    for (int i = 0; i < o->count; i++) {
        const lucent_material *m = &o->list[i];
        if (!m->skin.layer_count) continue;
        lucent_skin_color c;
        lucent_status s = skin_color(o, m, &c);
        if (s != LUCENT_OK) return s;
        printf("%-*s %7.2f %7.2f %7.2f %7.2f  %-13s", name_width, m->name, c.lab[0], c.lab[1], c.lab[2], c.ita,
               c.category);
        for (int k = 0; k < 3; k++) print_value(c.rgb[k]);
        putchar('\n');
    }
    printf("(R G B: linear sRGB, white balanced: a flat reflector R gives R R R)\n\n");
    return LUCENT_OK;
}

static lucent_status print_tables(const options *o)
{
    row *rows = calloc((size_t)o->count, sizeof *rows);
    if (!rows) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    int name_width = 12;
    for (int i = 0; i < o->count; i++) {
        rows[i].m = o->list[i];
        lucent_material_derive(&rows[i].m, &rows[i].d);
        int len = (int)strlen(rows[i].m.name) + 1;
        if (len > name_width) name_width = len;
    }
    for (size_t t = 0; t < sizeof k_tables / sizeof k_tables[0]; t++)
        print_table(&k_tables[t], rows, o->count, name_width);
    print_anisotropic(rows, o->count);
    free(rows);
    return print_skins(o, name_width);
}

/* ---- JSON ---- */

static lucent_status emit_json(const options *o)
{
    char *text;
    lucent_status s = lucent_material_to_json(o->list, o->count, true, &text);
    if (s != LUCENT_OK) return s;
    if (o->out) {
        s = lucent_write_file(o->out, text, strlen(text));
        if (s == LUCENT_OK) cli_wrote("wrote %s", o->out);
    } else {
        fputs(text, stdout);
    }
    free(text);
    return s;
}

/* ---- swatches ---- */

enum { SWATCH_SIZE = 96, SWATCH_GAP = 8, SWATCH_LABEL = 14 };

/* Draws one swatch: the material's dipole Rd (a spectral skin: its bands' total reflectance through the
 * colour weights) as a linear RGB colour, its name below. */
static lucent_status draw_swatch(const options *o, lucent_image *img, int index, const lucent_material *m)
{
    lucent_material_derived d;
    lucent_material_derive(m, &d);
    lucent_skin_color sc;
    if (m->skin.layer_count > 0) {
        lucent_status s = skin_color(o, m, &sc);
        if (s != LUCENT_OK) return s;
        memcpy(d.rd, sc.rgb, sizeof d.rd);
    }
    int x0 = SWATCH_GAP + index * (SWATCH_SIZE + SWATCH_GAP);
    for (int y = SWATCH_GAP; y < SWATCH_GAP + SWATCH_SIZE; y++)
        for (int x = x0; x < x0 + SWATCH_SIZE; x++)
            for (int c = 0; c < 3; c++) lucent_image_set(img, x, y, c, (float)d.rd[c]);
    static const float ink[3] = {0.85f, 0.85f, 0.85f};
    int tw = lucent_image_text_width(m->name, 1);
    lucent_image_draw_text(img, x0 + (SWATCH_SIZE - tw) / 2, SWATCH_GAP + SWATCH_SIZE + 4, 1, ink, m->name);
    return LUCENT_OK;
}

static lucent_status write_swatches(const options *o)
{
    lucent_image *img;
    int width = SWATCH_GAP + o->count * (SWATCH_SIZE + SWATCH_GAP);
    lucent_status s = lucent_image_create(width, SWATCH_SIZE + 2 * SWATCH_GAP + SWATCH_LABEL, 3, &img);
    if (s != LUCENT_OK) return s;
    for (int c = 0; c < 3; c++) lucent_image_fill(img, c, 0.18f); /* middle grey backdrop */
    for (int i = 0; i < o->count && s == LUCENT_OK; i++) s = draw_swatch(o, img, i, &o->list[i]);
    if (s == LUCENT_OK) s = lucent_image_write(o->swatches, img, NULL);
    lucent_image_destroy(img);
    if (s != LUCENT_OK) return s;
    char names[2048] = "";
    for (int i = 0; i < o->count; i++)
        snprintf(names + strlen(names), sizeof names - strlen(names), " %s", o->list[i].name);
    cli_wrote("wrote %s (Rd swatches: dipole, or a skin's spectral colour; left to right:%s)", o->swatches, names);
    return LUCENT_OK;
}

/* Writes what was asked: files (--out, --swatches) or, when none, tables or JSON on stdout. */
static lucent_status emit(const options *o)
{
    lucent_status s = LUCENT_OK;
    if (o->swatches) s = write_swatches(o);
    if (s == LUCENT_OK && (o->json || o->out) && (o->out || !o->swatches)) s = emit_json(o);
    if (s == LUCENT_OK && !o->json && !o->out && !o->swatches) s = print_tables(o);
    return s;
}

/* ---- the command ---- */

/* Reads the options; positional arguments stay in argv (their count in *specs). */
static int parse_args(int argc, char **argv, options *o, int *specs)
{
    *specs = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--json") == 0) {
            o->json = true;
        } else if (strcmp(a, "--out") == 0 || strncmp(a, "--out=", 6) == 0) {
            o->out = a[5] == '=' ? a + 6 : (i + 1 < argc ? argv[++i] : NULL);
            if (!o->out || !o->out[0]) return cli_usage_error("materials", "--out needs a file name");
        } else if (strcmp(a, "--swatches") == 0 || strncmp(a, "--swatches=", 11) == 0) {
            o->swatches = a[10] == '=' ? a + 11 : (i + 1 < argc ? argv[++i] : NULL);
            if (!o->swatches || !o->swatches[0])
                return cli_usage_error("materials", "--swatches needs an image file name");
        } else if (strcmp(a, "--photons") == 0 || strncmp(a, "--photons=", 10) == 0) {
            const char *v = a[9] == '=' ? a + 10 : (i + 1 < argc ? argv[++i] : NULL);
            if (!v || !cli_parse_int(v, &o->photons) || o->photons < 1)
                return cli_usage_error("materials", "--photons needs a whole number > 0");
        } else if (a[0] == '-' && a[1]) {
            return cli_usage_error("materials", "unknown option '%s'", a);
        } else {
            argv[1 + (*specs)++] = argv[i];
        }
    }
    return CLI_OK;
}

/* Reads every named material (all presets when none is named) before anything is printed. */
static lucent_status gather(options *o, char **specs, int count)
{
    if (count == 0) return add_presets(o);
    for (int i = 0; i < count; i++) {
        lucent_status s = add_spec(o, specs[i]);
        if (s != LUCENT_OK) return s;
    }
    return LUCENT_OK;
}

/* --out and --swatches: two files, neither a material file named (FILE or FILE#NAME); a usage error. */
static int check_outputs(const options *o, char **specs, int count)
{
    const char *outs[2] = {o->out, o->swatches};
    static const char *const flags[2] = {"--out", "--swatches"};
    int rc = cli_check_outputs("materials", NULL, 0, outs, flags, 2);
    for (int i = 0; rc == CLI_OK && i < count; i++) {
        char file[1024];
        const char *ins[1] = {cli_spec_file(specs[i], file, sizeof file)};
        rc = cli_check_outputs("materials", ins, 1, outs, flags, 2);
    }
    return rc;
}

int cmd_materials(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {0};
    int specs;
    int rc = parse_args(argc, argv, &o, &specs);
    if (rc == CLI_OK) rc = check_outputs(&o, argv + 1, specs);
    if (rc == CLI_OK) {
        char buf[4096];
        const char *cdir = cli_cache_dir(NULL, false, buf, sizeof buf);
        lucent_status s = cdir ? lucent_cache_create(cdir, &o.cache) : LUCENT_OK;
        if (s == LUCENT_OK) s = gather(&o, argv + 1, specs);
        if (s == LUCENT_OK) s = emit(&o);
        if (s != LUCENT_OK) rc = cli_fail();
    }
    lucent_cache_destroy(o.cache);
    free(o.list);
    return rc;
}
