/* `lucent mcml`: runs the simulations of an MCML input file (.mci) and writes MCML output
 * files (.mco), so MCML users can switch without changing their scripts (docs/mcml.md). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/mc.h"
#include "lucent/mcml.h"

static const char k_usage[] =
    "usage: lucent mcml FILE.mci [--seed S] [--out-dir DIR] [--threads N] [--quiet]\n"
    "       lucent mcml [FILE.mci] --compare MCML.mco [--photons N] [--seed S] [--csv FILE]\n"
    "                   [--json FILE] [--threads N]\n"
    "\n"
    "Runs every run of an MCML input file (Wang, Jacques & Zheng 1995) with Lucent's Monte\n"
    "Carlo transport and writes each run's MCML output file (.mco: the same sections, cm units\n"
    "and normalisations as MCML 1.2, the last radial and depth bins collecting everything beyond\n"
    "the grid). The whole input file is checked before anything runs. A last layer of\n"
    "thickness 'inf' is a half-space. Results depend on the seed only, not on --threads.\n"
    "\n"
    "With --compare, reads an existing MCML output file, runs Lucent on the simulation it\n"
    "describes (its InParm section, or the run of FILE.mci that matches it), and prints the\n"
    "differences section by section (Rsp, RAT, A_l, A_z, Rd_r, Rd_a, Tt_r, Tt_a) in standard\n"
    "errors, with how many bins lie beyond 3 standard errors. MCML writes no standard errors:\n"
    "MCML's are estimated from Lucent's, scaled by the square root of the photon ratio. No .mco\n"
    "is written. See docs/mcml.md.\n"
    "\n"
    "options:\n"
    "  --seed S        random seed (default 1); run k of the file uses seed S + k - 1\n"
    "  --out-dir DIR   write the outputs into DIR (the file names of the .mci, without their\n"
    "                  directories) instead of where the .mci names them\n"
    "  --compare FILE  compare Lucent with this MCML output file (.mco)\n"
    "  --photons N     with --compare: Lucent's photons (default: as many as the .mco's)\n"
    "  --csv FILE      with --compare: write every bin's comparison as CSV\n"
    "  --json FILE     with --compare: write the comparison (summary and bins) as JSON\n"
    "  --threads N     worker threads (default: LUCENT_THREADS, else all cores)\n"
    "  -q, --quiet     no progress bar, no report lines (the comparison is still printed)\n"
    "  -h, --help      show this help\n"
    "\n"
    "examples:\n"
    "  lucent mcml sample.mci\n"
    "  lucent mcml tissue.mci --seed 42 --out-dir out/\n"
    "  lucent mcml --compare tissue.mco --photons 1000000 --csv diff.csv\n";

typedef struct options {
    const char *input;
    const char *out_dir;
    const char *compare; /* the .mco to compare with */
    const char *csv, *json;
    unsigned long long seed, photons;
} options;

static bool parse_seed(const char *text, unsigned long long *dest)
{
    if (!text || !*text || *text == '-') return false;
    char *end;
    *dest = strtoull(text, &end, 10);
    return !*end;
}

/* --seed, --photons: whole numbers (photons > 0). */
static int parse_count(const char *name, const char *v, unsigned long long *dest, bool positive)
{
    if (!parse_seed(v, dest) || (positive && *dest == 0) || (positive && (double)*dest > LUCENT_MC_MAX_PHOTONS))
        return cli_usage_error("mcml", "%s needs a whole number %s", name, positive ? "in [1, 1e12]" : ">= 0");
    return CLI_OK;
}

static int parse_option(int argc, char **argv, int *i, options *o)
{
    const char *v;
    if (cli_option(argc, argv, i, "--seed", &v)) return parse_count("--seed", v, &o->seed, false);
    if (cli_option(argc, argv, i, "--photons", &v)) return parse_count("--photons", v, &o->photons, true);
    struct {
        const char *name;
        const char **dest;
        const char *what;
    } files[] = {
        {"--out-dir", &o->out_dir, "a directory"},
        {"--compare", &o->compare, "an MCML output file (.mco)"},
        {"--csv", &o->csv, "a file name"},
        {"--json", &o->json, "a file name"},
    };
    for (size_t k = 0; k < sizeof files / sizeof *files; k++) {
        if (!cli_option(argc, argv, i, files[k].name, &v)) continue;
        if (!v) return cli_usage_error("mcml", "%s needs %s", files[k].name, files[k].what);
        *files[k].dest = v;
        return CLI_OK;
    }
    return cli_usage_error("mcml", "unknown option '%s'", argv[*i]);
}

static int check_modes(const options *o)
{
    if (!o->compare) {
        if (o->photons || o->csv || o->json)
            return cli_usage_error("mcml", "--%s goes with --compare",
                                   o->photons ? "photons"
                                   : o->csv   ? "csv"
                                              : "json");
        if (!o->input) return cli_usage_error("mcml", "missing the input file (FILE.mci)");
    } else if (o->out_dir) {
        return cli_usage_error("mcml", "--out-dir does not go with --compare (no .mco is written)");
    }
    return CLI_OK;
}

static int parse_args(int argc, char **argv, options *o)
{
    o->seed = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        int rc = CLI_OK;
        if (a[0] == '-' && a[1])
            rc = parse_option(argc, argv, &i, o);
        else if (o->input)
            rc = cli_usage_error("mcml", "one input file, please (got '%s' and '%s')", o->input, a);
        else
            o->input = a;
        if (rc != CLI_OK) return rc;
    }
    return check_modes(o);
}

/* Where run's output goes: as named in the .mci, or its base name inside --out-dir. */
static char *output_path(const options *o, const lucent_mcml_run *run)
{
    const char *name = run->output;
    if (!o->out_dir) return strdup(name);
    const char *slash = strrchr(name, '/');
    const char *base = slash ? slash + 1 : name;
    size_t n = strlen(o->out_dir) + strlen(base) + 2;
    char *p = malloc(n);
    if (p) snprintf(p, n, "%s%s%s", o->out_dir, o->out_dir[strlen(o->out_dir) - 1] == '/' ? "" : "/", base);
    return p;
}

/* The runs' output files, before any runs: distinct, none of them the .mci (a usage error). */
static int check_run_outputs(const options *o, const lucent_mcml_file *file)
{
    int n = file->run_count, rc = CLI_OK;
    char **paths = calloc((size_t)n + 1, sizeof *paths), (*labels)[32] = calloc((size_t)n + 1, sizeof *labels);
    const char **flags = calloc((size_t)n + 1, sizeof *flags);
    if (!paths || !labels || !flags) rc = (lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory"), cli_fail());
    for (int k = 0; rc == CLI_OK && k < n; k++) {
        snprintf(labels[k], sizeof labels[k], "run %d's output", k + 1);
        flags[k] = labels[k];
        if (!(paths[k] = output_path(o, &file->runs[k])))
            rc = (lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory"), cli_fail());
    }
    const char *ins[1] = {o->input};
    if (rc == CLI_OK) rc = cli_check_outputs("mcml", ins, 1, (const char *const *)paths, flags, n);
    for (int k = 0; paths && k < n; k++) free(paths[k]);
    free(paths), free(labels), free(flags);
    return rc;
}

static lucent_status run_one(const options *o, lucent_mcml_run *run, int k, int count)
{
    char label[64];
    snprintf(label, sizeof label, "mcml run %d/%d", k + 1, count);
    char *path = output_path(o, run);
    if (!path) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "out of memory");
    run->desc.seed = o->seed + (unsigned long long)k;
    run->desc.pool = cli_pool();
    run->desc.label = label;
    lucent_mc_result r;
    double t0 = lucent_clock_seconds();
    lucent_status s = lucent_mc_run(&run->desc, &r);
    double t = lucent_clock_seconds() - t0;
    if (s != LUCENT_OK) s = lucent_error_context(s, "%s: run %d", o->input, k + 1);
    if (s == LUCENT_OK) {
        s = lucent_mcml_write(path, run, &r);
        char rate[64] = "";
        if (!g_cli.merging && t > 0) snprintf(rate, sizeof rate, "; %.0f photons/s", (double)r.photons / t);
        if (s == LUCENT_OK)
            cli_wrote("wrote %s (Rsp %.5f, Rd %.5f +- %.5f, A %.5f +- %.5f, Tt %.5f +- %.5f; %llu photons%s)", path,
                      r.rsp, r.rd, r.rd_se, r.a, r.a_se, r.tt, r.tt_se, (unsigned long long)r.photons, rate);
        lucent_mc_result_free(&r);
    }
    free(path);
    return s;
}

/* ---- --compare: Lucent against an existing MCML output ---- */

/* The simulation to run: the .mco's InParm, or the run of the .mci that describes it. */
static lucent_status compare_desc(const options *o, const lucent_mco *mco, lucent_mcml_file *mci, lucent_mc_desc *dest)
{
    *dest = mco->run.desc;
    if (!o->input) return LUCENT_OK;
    lucent_status s = lucent_mcml_load(o->input, mci);
    if (s != LUCENT_OK) return s;
    char first[512] = "";
    for (int k = 0; k < mci->run_count; k++) {
        if (lucent_mco_check_run(mco, &mci->runs[k].desc) == LUCENT_OK) {
            *dest = mci->runs[k].desc;
            lucent_clear_error();
            return LUCENT_OK;
        }
        if (k == 0) snprintf(first, sizeof first, "%s", lucent_last_error());
    }
    return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                        "%s: no run describes the simulation of %s "
                        "(run 1: %s)",
                        o->input, o->compare, first);
}

static const char *mark(const lucent_mco_bin *b)
{
    return b->state != LUCENT_MCO_COMPARED ? lucent_mco_bin_state_name(b->state)
           : fabs(b->z) > 3.0              ? "beyond 3 SE"
                                           : "";
}

/* Lucent's mm-based densities in the .mco's cm-based units. */
static double to_cm(lucent_mco_section_id id)
{
    return id == LUCENT_MCO_A_Z ? 10.0 : id == LUCENT_MCO_RD_R || id == LUCENT_MCO_TT_R ? 100.0 : 1.0;
}

/* RAT and A_l: one line per value. */
static void print_values(const lucent_mco_section *sec)
{
    for (int i = 0; i < sec->count; i++) {
        const lucent_mco_bin *b = &sec->bins[i];
        char name[24];
        if (sec->id == LUCENT_MCO_RAT)
            snprintf(name, sizeof name, "%s", lucent_mco_rat_name(i));
        else
            snprintf(name, sizeof name, "layer %d", i + 1);
        printf("%-6s %-8s Lucent %.6f +- %.6f   MCML %.6f +- %.6f   ", i ? "" : lucent_mco_section_name(sec->id), name,
               b->lucent, b->lucent_se, b->mcml, b->mcml_se);
        if (b->state == LUCENT_MCO_COMPARED)
            printf("%+6.2f SE  %s\n", b->z, mark(b));
        else
            printf("%s\n", mark(b));
    }
}

/* A profile: one summary line, and the bins beyond 3 SE (the first few). */
static void print_profile(const lucent_mco_section *sec)
{
    double u = to_cm(sec->id);
    printf("%-6s %d bins [%s]: %d compared, %d beyond 3 SE (%.1f expected by chance)", lucent_mco_section_name(sec->id),
           sec->count, lucent_mco_section_unit(sec->id), sec->compared, sec->beyond3, 0.0027 * sec->compared);
    if (sec->compared) printf(", chi2/bin %.2f", sec->chi2 / sec->compared);
    if (sec->worst >= 0)
        printf(", largest %+.2f SE at %s %.4g", sec->bins[sec->worst].z, lucent_mco_section_axis(sec->id),
               (sec->worst + 0.5) * sec->width);
    if (sec->sparse || sec->unresolved) printf("; not counted: %d sparse, %d unresolved", sec->sparse, sec->unresolved);
    putchar('\n');
    int shown = 0;
    for (int i = 0; i < sec->count && shown < 5; i++) {
        const lucent_mco_bin *b = &sec->bins[i];
        if (b->state != LUCENT_MCO_COMPARED || fabs(b->z) <= 3.0) continue;
        printf("         bin %d (%s %.4g): Lucent %.5G +- %.2G, MCML %.5G +- %.2G: %+.2f SE\n", i,
               lucent_mco_section_axis(sec->id), (i + 0.5) * sec->width, b->lucent * u, b->lucent_se * u, b->mcml * u,
               b->mcml_se * u, b->z);
        shown++;
    }
    if (sec->beyond3 > shown) printf("         ... and %d more beyond 3 SE\n", sec->beyond3 - shown);
}

static void print_comparison(const options *o, const lucent_mc_desc *d, const lucent_mco_comparison *c)
{
    printf("Lucent (%llu photons, seed %llu) against %s (MCML, %llu photons)\n", (unsigned long long)c->lucent_photons,
           (unsigned long long)d->seed, o->compare, (unsigned long long)c->mcml_photons);
    printf("MCML writes no standard errors: they are estimated as Lucent's x %.4g, the square root\n"
           "of the photon ratio (the same estimator per photon on both sides).\n",
           c->se_scale);
    printf("Values in the .mco's units (cm). diff/SE = (Lucent - MCML) / sqrt(se_L^2 + se_M^2).\n\n");
    printf("%-6s %-8s Lucent %.7f   MCML %.7f   %s\n", "Rsp", "", c->rsp_lucent, c->rsp_mcml,
           c->rsp_equal ? "equal (exact on both sides)" : "DIFFERS (both are exact)");
    for (int k = 0; k < LUCENT_MCO_SECTION_COUNT; k++) {
        const lucent_mco_section *sec = &c->sections[k];
        if (sec->id == LUCENT_MCO_RAT || sec->id == LUCENT_MCO_A_L)
            print_values(sec);
        else
            print_profile(sec);
        if (sec->id == LUCENT_MCO_A_L && !c->a_l_on_grid)
            printf("         (not counted: MCML sums the depth bins by the layer of their centre, and a\n"
                   "          layer boundary is off the dz grid, so its A_l is not the absorption per layer)\n");
    }
    printf("\nsummary: %d bins compared, %d beyond 3 SE (%.1f expected by chance)", c->compared, c->beyond3,
           0.0027 * c->compared);
    if (c->compared) printf(", chi2/bin %.2f", c->chi2 / c->compared);
    printf("%s\n", c->rsp_equal ? "" : "; Rsp differs");
}

static lucent_status write_outputs(const options *o, const lucent_mco_comparison *c)
{
    lucent_status s = LUCENT_OK;
    if (o->csv && (s = lucent_mco_comparison_write_csv(o->csv, c)) == LUCENT_OK) cli_wrote("wrote %s", o->csv);
    if (s == LUCENT_OK && o->json && (s = lucent_mco_comparison_write_json(o->json, c)) == LUCENT_OK)
        cli_wrote("wrote %s", o->json);
    return s;
}

static lucent_status run_compare(const options *o, const lucent_mco *mco, lucent_mc_desc *d)
{
    if (o->photons) d->photons = o->photons;
    d->seed = o->seed;
    d->pool = cli_pool();
    d->label = "mcml --compare";
    d->score_a_rz = false; /* not compared: the 2-D arrays carry no standard errors */
    lucent_mc_result r;
    lucent_status s = lucent_mc_run(d, &r);
    if (s != LUCENT_OK) return s;
    lucent_mco_comparison c;
    s = lucent_mco_compare(mco, &r, &c);
    if (s == LUCENT_OK) {
        print_comparison(o, d, &c);
        s = write_outputs(o, &c);
        lucent_mco_comparison_free(&c);
    }
    lucent_mc_result_free(&r);
    return s;
}

static int cmd_compare_mco(const options *o)
{
    const char *ins[2] = {o->compare, o->input}, *outs[2] = {o->csv, o->json};
    static const char *const flags[2] = {"--csv", "--json"};
    int rc = cli_check_outputs("mcml", ins, 2, outs, flags, 2);
    if (rc != CLI_OK) return rc;
    lucent_mco mco;
    if (lucent_mco_load(o->compare, &mco) != LUCENT_OK) return cli_fail();
    lucent_mcml_file mci = {0};
    lucent_mc_desc d;
    lucent_status s = compare_desc(o, &mco, &mci, &d);
    if (s == LUCENT_OK) s = run_compare(o, &mco, &d);
    lucent_mcml_file_free(&mci);
    lucent_mco_free(&mco);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}

int cmd_mcml(int argc, char **argv)
{
    if (cli_wants_help(argc, argv)) {
        fputs(k_usage, stdout);
        return CLI_OK;
    }
    options o = {0};
    int rc = parse_args(argc, argv, &o);
    if (rc != CLI_OK) return rc;
    if (o.compare) return cmd_compare_mco(&o);
    lucent_mcml_file file;
    if (lucent_mcml_load(o.input, &file) != LUCENT_OK) return cli_fail();
    if ((rc = check_run_outputs(&o, &file)) != CLI_OK) {
        lucent_mcml_file_free(&file);
        return rc;
    }
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < file.run_count && s == LUCENT_OK; k++) s = run_one(&o, &file.runs[k], k, file.run_count);
    lucent_mcml_file_free(&file);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
