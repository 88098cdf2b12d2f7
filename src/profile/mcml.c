/* MCML files: the .mci input reader and the .mco output writer (Wang, Jacques & Zheng 1995,
 * "MCML - Monte Carlo modeling of light transport in multi-layered tissues", the MCML manual's
 * chapters on the input and output files). MCML speaks cm and cm^-1; Lucent speaks mm and
 * mm^-1: values are converted here and nowhere else. */
#include <ctype.h>
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "mcml_internal.h"

#define CM MCML_CM

lucent_status mcml_fail(const mcml_reader *r, const char *fmt, ...)
{
    char msg[512];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    return lucent_error(LUCENT_ERR_PARSE, "%s: line %d: %s", r->name, r->at, msg);
}

lucent_status mcml_next_line(mcml_reader *r, const char *what)
{
    while (*r->p) {
        const char *end = strchr(r->p, '\n');
        size_t len = end ? (size_t)(end - r->p) : strlen(r->p);
        r->line++;
        r->at = r->line;
        const char *hash = memchr(r->p, '#', len);
        size_t data = hash ? (size_t)(hash - r->p) : len;
        if (data >= sizeof r->buf) return mcml_fail(r, "line too long");
        memcpy(r->buf, r->p, data);
        r->buf[data] = '\0';
        r->p += len + (end ? 1 : 0);
        for (char *c = r->buf; *c; c++)
            if (!isspace((unsigned char)*c)) return LUCENT_OK;
    }
    r->at = r->line + 1;
    return mcml_fail(r, "unexpected end of file, expected %s", what);
}

lucent_status mcml_numbers(mcml_reader *r, int count, double *dest, const char *what)
{
    char *p = r->buf;
    for (int i = 0; i < count; i++) {
        while (isspace((unsigned char)*p)) p++;
        if (!*p) return mcml_fail(r, "expected %s (%d number%s), got %d", what, count, count > 1 ? "s" : "", i);
        char *end;
        errno = 0;
        dest[i] = strtod(p, &end);
        if (end == p || (*end && !isspace((unsigned char)*end)))
            return mcml_fail(r, "expected %s, got '%.*s'", what, (int)strcspn(p, " \t\r"), p);
        if (isnan(dest[i]) || errno == ERANGE) return mcml_fail(r, "%s: not a usable number", what);
        p = end;
    }
    while (isspace((unsigned char)*p)) p++;
    if (*p) return mcml_fail(r, "unexpected '%.*s' after %s", (int)strcspn(p, " \t\r"), p, what);
    return LUCENT_OK;
}

static lucent_status whole(mcml_reader *r, double v, double lo, double hi, const char *what, int *dest)
{
    if (v != floor(v) || v < lo) return mcml_fail(r, "%s must be a whole number >= %g, got %g", what, lo, v);
    if (v > hi) return mcml_fail(r, "too many %s: %g (at most %g)", what, v, hi);
    *dest = (int)v;
    return LUCENT_OK;
}

static lucent_status read_output(mcml_reader *r, lucent_mcml_run *run)
{
    lucent_status s = mcml_next_line(r, "the output file name and format (A)");
    if (s != LUCENT_OK) return s;
    char name[1024], fmt[16] = "A", extra[16];
    int n = sscanf(r->buf, "%1023s %15s %15s", name, fmt, extra);
    if (n == 3) return mcml_fail(r, "unexpected '%s' after the output file name and format", extra);
    if (strcasecmp(fmt, "A") != 0)
        return mcml_fail(r, "output format '%s' is not supported (only A, ASCII, as in MCML)", fmt);
    run->line = r->at;
    run->output = strdup(name);
    return run->output ? LUCENT_OK : lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
}

/* The line of each part of a run, so that the whole run's check (lucent_mc_validate) names the field's line. */
typedef struct run_lines {
    int photons, grid, bins, layer[LUCENT_MC_MAX_LAYERS];
} run_lines;

static lucent_status read_grid(mcml_reader *r, lucent_mc_desc *d, run_lines *at)
{
    double v[3];
    lucent_status s = mcml_next_line(r, "the number of photons");
    if (s == LUCENT_OK) s = mcml_numbers(r, 1, v, "the number of photons");
    if (s != LUCENT_OK) return s;
    at->photons = r->at;
    if (v[0] != floor(v[0]) || v[0] < 1 || v[0] > LUCENT_MC_MAX_PHOTONS)
        return mcml_fail(r, "the number of photons must be a whole number in [1, 1e12], got %g", v[0]);
    d->photons = (uint64_t)v[0];
    if ((s = mcml_next_line(r, "dz and dr [cm]")) != LUCENT_OK) return s;
    if ((s = mcml_numbers(r, 2, v, "dz and dr [cm]")) != LUCENT_OK) return s;
    at->grid = r->at;
    if (!(v[0] > 0 && v[1] > 0 && isfinite(v[0]) && isfinite(v[1])))
        return mcml_fail(r, "dz and dr must be > 0, got %g and %g", v[0], v[1]);
    d->grid.dz = v[0] * CM;
    d->grid.dr = v[1] * CM;
    if ((s = mcml_next_line(r, "the numbers of bins nz, nr, na")) != LUCENT_OK) return s;
    if ((s = mcml_numbers(r, 3, v, "the numbers of bins nz, nr, na")) != LUCENT_OK) return s;
    at->bins = r->at;
    if ((s = whole(r, v[0], 1, LUCENT_MC_MAX_RADIAL_BINS, "depth bins (nz)", &d->grid.nz)) ||
        (s = whole(r, v[1], 1, LUCENT_MC_MAX_RADIAL_BINS, "radial bins (nr)", &d->grid.nr)) ||
        (s = whole(r, v[2], 1, LUCENT_MC_MAX_ANGLE_BINS, "angle bins (na)", &d->grid.na)))
        return s;
    double cells = v[0] * v[1] > v[1] * v[2] ? v[0] * v[1] : v[1] * v[2];
    if (cells > LUCENT_MC_MAX_GRID_CELLS)
        return mcml_fail(r, "too many bins: nr x nz = %g cells (at most %d)", cells, LUCENT_MC_MAX_GRID_CELLS);
    return LUCENT_OK;
}

static lucent_status read_index(mcml_reader *r, const char *what, double *dest)
{
    lucent_status s = mcml_next_line(r, what);
    if (s == LUCENT_OK) s = mcml_numbers(r, 1, dest, what);
    if (s == LUCENT_OK && !(*dest >= 1.0 && *dest <= 10.0))
        return mcml_fail(r, "%s must be in [1, 10], got %g", what, *dest);
    return s;
}

/* One layer line: n mua mus g d (cm^-1, cm). The last layer may say d = inf (a half-space,
 * a Lucent extension). */
static lucent_status read_layer(mcml_reader *r, int i, int count, lucent_mc_layer *l)
{
    char what[64];
    snprintf(what, sizeof what, "layer %d (n mua mus g d)", i + 1);
    double v[5];
    lucent_status s = mcml_next_line(r, what);
    if (s == LUCENT_OK) s = mcml_numbers(r, 5, v, what);
    if (s != LUCENT_OK) return s;
    if (!(v[0] >= 1.0 && v[0] <= 10.0)) return mcml_fail(r, "layer %d: n must be in [1, 10], got %g", i + 1, v[0]);
    if (!(v[1] >= 0 && isfinite(v[1])) || !(v[2] >= 0 && isfinite(v[2])))
        return mcml_fail(r, "layer %d: mua and mus must be >= 0, got %g and %g", i + 1, v[1], v[2]);
    if (!(v[3] >= -1.0 && v[3] <= 1.0)) return mcml_fail(r, "layer %d: g must be in [-1, 1], got %g", i + 1, v[3]);
    if (!(v[4] > 0)) return mcml_fail(r, "layer %d: thickness d must be > 0, got %g", i + 1, v[4]);
    if (isinf(v[4]) && i != count - 1) return mcml_fail(r, "layer %d: only the last layer may be semi-infinite", i + 1);
    if (isinf(v[4]) && v[1] + v[2] == 0)
        return mcml_fail(r, "layer %d: a semi-infinite layer must absorb or scatter", i + 1);
    *l = (lucent_mc_layer){v[0], v[1] / CM, v[2] / CM, v[3], v[4] * CM};
    return LUCENT_OK;
}

static lucent_status read_layers(mcml_reader *r, lucent_mcml_run *run, run_lines *at)
{
    double v;
    lucent_status s = mcml_next_line(r, "the number of layers");
    if (s == LUCENT_OK) s = mcml_numbers(r, 1, &v, "the number of layers");
    int count = 0;
    if (s == LUCENT_OK) s = whole(r, v, 1, LUCENT_MC_MAX_LAYERS, "layers", &count);
    if (s != LUCENT_OK) return s;
    run->layers = calloc((size_t)count, sizeof *run->layers);
    if (!run->layers) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    run->desc.layers = run->layers;
    run->desc.layer_count = count;
    if ((s = read_index(r, "n for the medium above", &run->desc.n_above)) != LUCENT_OK) return s;
    for (int i = 0; i < count; i++) {
        if ((s = read_layer(r, i, count, &run->layers[i])) != LUCENT_OK) return s;
        at->layer[i] = r->at;
    }
    return read_index(r, "n for the medium below", &run->desc.n_below);
}

/* The line holding the field that lucent_mc_validate's message starts with ("grid.dr: ...", "layers[1].g: ..."),
 * else the run's first line. */
static int line_of_field(const char *message, const run_lines *at, int run_line)
{
    int i;
    if (!strncmp(message, "grid.n", 6) || !strncmp(message, "grid: too many bins", 19)) return at->bins;
    if (!strncmp(message, "grid", 4)) return at->grid;
    if (!strncmp(message, "photons", 7)) return at->photons;
    if (sscanf(message, "layers[%d]", &i) == 1 && i >= 0 && i < LUCENT_MC_MAX_LAYERS && at->layer[i])
        return at->layer[i];
    return run_line;
}

lucent_status mcml_read_run(mcml_reader *r, lucent_mcml_run *run)
{
    run_lines at = {0};
    lucent_status s = read_output(r, run);
    if (s == LUCENT_OK) s = read_grid(r, &run->desc, &at);
    if (s == LUCENT_OK) s = read_layers(r, run, &at);
    if (s != LUCENT_OK) return s;
    run->desc.score_a_rz = true;        /* MCML always scores A(r, z) */
    run->desc.last_bin_collects = true; /* and collects beyond the grid in the last bins */
    s = lucent_mc_validate(&run->desc);
    if (s == LUCENT_OK) return s;
    int line = line_of_field(lucent_last_error(), &at, run->line);
    return line == run->line ? lucent_error_context(s, "%s: line %d (run)", r->name, run->line)
                             : lucent_error_context(s, "%s: line %d (the run of line %d)", r->name, line, run->line);
}

lucent_status lucent_mcml_parse(const char *text, const char *name, lucent_mcml_file *dest)
{
    memset(dest, 0, sizeof *dest);
    mcml_reader r = {.name = name, .p = text};
    double v;
    lucent_status s = mcml_next_line(&r, "the file version (1.0)");
    if (s == LUCENT_OK) s = mcml_numbers(&r, 1, &v, "the file version");
    if (s == LUCENT_OK && v != 1.0) s = mcml_fail(&r, "file version %g is not supported (1.0 is)", v);
    if (s != LUCENT_OK) return s;
    dest->version = v;
    if ((s = mcml_next_line(&r, "the number of runs")) != LUCENT_OK ||
        (s = mcml_numbers(&r, 1, &v, "the number of runs")) != LUCENT_OK ||
        (s = whole(&r, v, 1, 10000, "runs", &dest->run_count)) != LUCENT_OK)
        return s;
    dest->runs = calloc((size_t)dest->run_count, sizeof *dest->runs);
    if (!dest->runs) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    for (int i = 0; i < dest->run_count && s == LUCENT_OK; i++) s = mcml_read_run(&r, &dest->runs[i]);
    if (s == LUCENT_OK) { /* anything but comments after the last run is a mistake */
        mcml_reader tail = r;
        if (mcml_next_line(&tail, "") == LUCENT_OK)
            s = mcml_fail(&tail, "unexpected data after the last of %d run%s", dest->run_count,
                          dest->run_count > 1 ? "s" : "");
        else
            lucent_clear_error();
    }
    if (s != LUCENT_OK) lucent_mcml_file_free(dest);
    return s;
}

lucent_status lucent_mcml_load(const char *path, lucent_mcml_file *dest)
{
    memset(dest, 0, sizeof *dest);
    if (!path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "mcml: no .mci file given (NULL path)");
    char *text;
    lucent_status s = lucent_read_text_file(path, &text);
    if (s != LUCENT_OK) return s;
    s = lucent_mcml_parse(text, path, dest);
    free(text);
    return s;
}

void lucent_mcml_file_free(lucent_mcml_file *f)
{
    for (int i = 0; f->runs && i < f->run_count; i++) {
        free(f->runs[i].output);
        free(f->runs[i].layers);
    }
    free(f->runs);
    memset(f, 0, sizeof *f);
}

/* ---- the writer: format A1 of MCML 1.2 ---- */

static void write_column(FILE *f, const char *head, const double *v, int n, double k)
{
    fprintf(f, "%s\n", head);
    for (int i = 0; i < n; i++) fprintf(f, "%12.4E\n", v ? v[i] * k : 0.0);
    fputc('\n', f);
}

/* A 2-D array, row-major, 5 numbers per line (MCML's layout); value i is scaled by k, and by
 * col[i % cols] when col is given. */
static void write_grid(FILE *f, const char *comment, const char *head, const double *v, size_t n, double k,
                       const double *col, size_t cols)
{
    fprintf(f, "%s%s\n", comment, head);
    for (size_t i = 0; i < n; i++)
        fprintf(f, "%12.4E%s", v ? v[i] * k * (col ? col[i % cols] : 1.0) : 0.0,
                (i + 1) % 5 == 0 || i + 1 == n ? "\n" : " ");
    fputc('\n', f);
}

static void write_inparm(FILE *f, const lucent_mcml_run *run, const lucent_mc_desc *d)
{
    fprintf(f, "InParm \t\t\t# Input parameters. cm is used.\n");
    fprintf(f, "%s \tA\t\t# output file name, ASCII.\n", run->output);
    fprintf(f, "%llu \t\t\t# No. of photons\n", (unsigned long long)d->photons);
    fprintf(f, "%G\t%G\t\t# dz, dr [cm]\n", d->grid.dz / CM, d->grid.dr / CM);
    fprintf(f, "%d\t%d\t%d\t# No. of dz, dr, da.\n\n", d->grid.nz, d->grid.nr, d->grid.na);
    fprintf(f, "%d\t\t\t\t# Number of layers\n", d->layer_count);
    fprintf(f, "#n\tmua\tmus\tg\td\t# One line for each layer\n");
    fprintf(f, "%G\t\t\t\t# n for medium above\n", d->n_above > 0 ? d->n_above : 1.0);
    for (int i = 0; i < d->layer_count; i++) {
        const lucent_mc_layer *l = &d->layers[i];
        fprintf(f, "%G\t%G\t%G\t%G\t%G\t# layer %d\n", l->n > 0 ? l->n : 1.0, l->sigma_a * CM, l->sigma_s * CM, l->g,
                l->thickness / CM, i + 1);
    }
    fprintf(f, "%G\t\t\t\t# n for medium below\n\n", d->n_below > 0 ? d->n_below : 1.0);
}

/* The last radial / depth bins hold everything beyond the grid when the run collected it there
 * (MCML's convention); a run that did not is written with the weight beyond added back, so the
 * file always follows MCML. */
static void fold_beyond(const lucent_mc_result *r, double *rd_r, double *tt_r, double *a_z)
{
    int nr = r->grid.nr, nz = r->grid.nz;
    double dr = r->grid.dr;
    double ring = 2.0 * M_PI * (nr - 0.5) * dr * dr;
    rd_r[nr - 1] += r->rd_beyond / ring;
    tt_r[nr - 1] += r->tt_beyond / ring;
    a_z[nz - 1] += r->a_z_beyond / r->grid.dz;
}

/* per_cos[j] = mcml_2d_per_lucent(j, na): the angular 2-D arrays' factor. */
static void write_results(FILE *f, const lucent_mc_result *r, double *rd_r, double *tt_r, double *a_z,
                          const double *per_cos)
{
    int nr = r->grid.nr, nz = r->grid.nz, na = r->grid.na;
    fprintf(f, "RAT #Reflectance, absorption, transmission. \n");
    fprintf(f, "%-14.6G \t#Specular reflectance [-]\n", r->rsp);
    fprintf(f, "%-14.6G \t#Diffuse reflectance [-]\n", r->rd);
    fprintf(f, "%-14.6G \t#Absorbed fraction [-]\n", r->a);
    fprintf(f, "%-14.6G \t#Transmittance [-]\n\n", r->tt);
    fprintf(f, "A_l #Absorption as a function of layer. [-]\n");
    for (int i = 0; i < r->layer_count; i++) fprintf(f, "%12.4G\n", r->a_layer[i]);
    fputc('\n', f);
    /* densities: per mm^k -> per cm^k */
    write_column(f, "A_z #A[0], [1],..A[nz-1]. [1/cm]", a_z, nz, CM);
    write_column(f, "Rd_r #Rd[0], [1],..Rd[nr-1]. [1/cm2]", rd_r, nr, CM * CM);
    double k_a = mcml_1d_per_lucent(na);
    write_column(f, "Rd_a #Rd[0], [1],..Rd[na-1]. [sr-1]", r->rd_a, na, k_a);
    write_column(f, "Tt_r #Tt[0], [1],..Tt[nr-1]. [1/cm2]", tt_r, nr, CM * CM);
    write_column(f, "Tt_a #Tt[0], [1],..Tt[na-1]. [sr-1]", r->tt_a, na, k_a);
    write_grid(f,
               "# A[r][z]. [1/cm3]\n# A[0][0], [0][1],..[0][nz-1]\n# A[1][0], [1][1],..[1][nz-1]\n"
               "# ...\n# A[nr-1][0], [nr-1][1],..[nr-1][nz-1]\n",
               "A_rz", r->a_rz, (size_t)nr * (size_t)nz, CM * CM * CM, NULL, 1);
    write_grid(f,
               "# Rd[r][angle]. [1/(cm2sr)].\n# Rd[0][0], [0][1],..[0][na-1]\n"
               "# Rd[1][0], [1][1],..[1][na-1]\n# ...\n# Rd[nr-1][0], [nr-1][1],..[nr-1][na-1]\n",
               "Rd_ra", r->rd_ra, (size_t)nr * (size_t)na, CM * CM, per_cos, (size_t)na);
    write_grid(f,
               "# T[r][angle]. [1/(cm2sr)].\n# T[0][0], [0][1],..[0][na-1]\n"
               "# T[1][0], [1][1],..[1][na-1]\n# ...\n# T[nr-1][0], [nr-1][1],..[nr-1][na-1]\n",
               "Tt_ra", r->tt_ra, (size_t)nr * (size_t)na, CM * CM, per_cos, (size_t)na);
}

lucent_status lucent_mcml_write(const char *path, const lucent_mcml_run *run, const lucent_mc_result *result)
{
    if (!path) return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "mcml: no .mco file given (NULL path)");
    const lucent_mc_result *r = result;
    size_t nr = (size_t)r->grid.nr, nz = (size_t)r->grid.nz, na = (size_t)r->grid.na;
    double *buf = malloc((2 * nr + nz + na) * sizeof *buf);
    if (!buf) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    double *rd_r = buf, *tt_r = buf + nr, *a_z = buf + 2 * nr, *per_cos = buf + 2 * nr + nz;
    for (size_t j = 0; j < na; j++) per_cos[j] = mcml_2d_per_lucent((int)j, (int)na);
    memcpy(rd_r, r->rd_r, nr * sizeof *buf);
    memcpy(tt_r, r->tt_r, nr * sizeof *buf);
    memcpy(a_z, r->a_z, nz * sizeof *buf);
    fold_beyond(r, rd_r, tt_r, a_z);
    lucent_atomic_file *af;
    FILE *f;
    lucent_status s = lucent_atomic_open(path, &af, &f);
    if (s != LUCENT_OK) {
        free(buf);
        return s;
    }
    fprintf(f, "A1 \t# Version number of the file format.\n\n####\n# Data categories include: \n"
               "# InParm, RAT, \n# A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a, \n# A_rz, Rd_ra, Tt_ra \n"
               "####\n\n");
    fprintf(f,
            "# Written by Lucent %s (lucent mcml, the %s kernel), %d batches for the standard errors:\n"
            "# Rd %.6G +- %.2G, A %.6G +- %.2G, Tt %.6G +- %.2G%s\n\n",
            LUCENT_VERSION_STRING, lucent_isa_name(lucent_isa_active()), r->batches, r->rd, r->rd_se, r->a, r->a_se,
            r->tt, r->tt_se, r->a_rz ? "" : "\n# A(r,z) was not scored: A_rz holds zeros.");
    write_inparm(f, run, &run->desc);
    write_results(f, r, rd_r, tt_r, a_z, per_cos);
    free(buf);
    if (ferror(f)) {
        lucent_atomic_abort(af);
        return lucent_error(LUCENT_ERR_IO, "%s: write failed", path);
    }
    return lucent_atomic_commit(af);
}
