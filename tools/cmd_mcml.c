/* `lucent mcml`: runs the simulations of an MCML input file (.mci) and writes MCML output
 * files (.mco), so MCML users can switch without changing their scripts (docs/mcml.md). */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "lucent/mc.h"

static const char k_usage[] =
    "usage: lucent mcml FILE.mci [--seed S] [--out-dir DIR] [--threads N] [--quiet]\n"
    "\n"
    "Runs every run of an MCML input file (Wang, Jacques & Zheng 1995) with Lucent's Monte\n"
    "Carlo transport and writes each run's MCML output file (.mco: the same sections, cm units\n"
    "and normalisations as MCML 1.2, the last radial and depth bins collecting everything beyond\n"
    "the grid). The whole input file is checked before anything runs. A last layer of\n"
    "thickness 'inf' is a half-space. Results depend on the seed only, not on --threads.\n"
    "\n"
    "options:\n"
    "  --seed S      random seed (default 1); run k of the file uses seed S + k - 1\n"
    "  --out-dir DIR write the outputs into DIR (the file names of the .mci, without their\n"
    "                directories) instead of where the .mci names them\n"
    "  --threads N   worker threads (default: LUCENT_THREADS, else all cores)\n"
    "  -q, --quiet   no progress bar, no report lines\n"
    "  -h, --help    show this help\n"
    "\n"
    "examples:\n"
    "  lucent mcml sample.mci\n"
    "  lucent mcml tissue.mci --seed 42 --out-dir out/\n";

typedef struct options {
    const char *input;
    const char *out_dir;
    unsigned long long seed;
} options;

static bool parse_seed(const char *text, unsigned long long *dest)
{
    if (!text || !*text || *text == '-') return false;
    char *end;
    *dest = strtoull(text, &end, 10);
    return !*end;
}

static int parse_args(int argc, char **argv, options *o)
{
    o->seed = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (strcmp(a, "--seed") == 0 || strncmp(a, "--seed=", 7) == 0) {
            const char *v = a[6] == '=' ? a + 7 : (i + 1 < argc ? argv[++i] : NULL);
            if (!parse_seed(v, &o->seed))
                return cli_usage_error("mcml", "--seed needs a whole number >= 0");
        } else if (strcmp(a, "--out-dir") == 0 || strncmp(a, "--out-dir=", 10) == 0) {
            o->out_dir = a[9] == '=' ? a + 10 : (i + 1 < argc ? argv[++i] : NULL);
            if (!o->out_dir || !o->out_dir[0])
                return cli_usage_error("mcml", "--out-dir needs a directory");
        } else if (a[0] == '-' && a[1]) {
            return cli_usage_error("mcml", "unknown option '%s'", a);
        } else if (o->input) {
            return cli_usage_error("mcml", "one input file, please (got '%s' and '%s')",
                                   o->input, a);
        } else {
            o->input = a;
        }
    }
    if (!o->input) return cli_usage_error("mcml", "missing the input file (FILE.mci)");
    return CLI_OK;
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
    if (p) snprintf(p, n, "%s%s%s", o->out_dir,
                    o->out_dir[strlen(o->out_dir) - 1] == '/' ? "" : "/", base);
    return p;
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
        if (s == LUCENT_OK)
            cli_info("wrote %s (Rsp %.5f, Rd %.5f +- %.5f, A %.5f +- %.5f, Tt %.5f +- %.5f; "
                     "%.0f photons/s)",
                     path, r.rsp, r.rd, r.rd_se, r.a, r.a_se, r.tt, r.tt_se,
                     t > 0 ? (double)r.photons / t : 0.0);
        lucent_mc_result_free(&r);
    }
    free(path);
    return s;
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
    lucent_mcml_file file;
    if (lucent_mcml_read(o.input, &file) != LUCENT_OK) return cli_fail();
    lucent_status s = LUCENT_OK;
    for (int k = 0; k < file.run_count && s == LUCENT_OK; k++)
        s = run_one(&o, &file.runs[k], k, file.run_count);
    lucent_mcml_file_free(&file);
    return s == LUCENT_OK ? CLI_OK : cli_fail();
}
