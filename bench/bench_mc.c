/* Benchmark of the photon Monte Carlo (issue 33): photons per second per core on one thread, for each
 * SIMD path this CPU has, beside MCML 1.2.2 measured here, in the same run, on the same inputs.
 *
 * The cases (each an .mci, run by both programs; MCML needs a finite last layer, so the half-spaces
 * are 10 km deep):
 *   Skin1 red, g 0      n 1.3, mua 0.032 mm^-1, mus 0.74 mm^-1 (Jensen et al. 2001's Skin1, red),
 *                       dr = dz = MFP / 20, 640 x 640 A(r, z), na 30 (Wang's thesis, Table 6.1)
 *   Skin1 red, g 0.9    the same layer with g 0.9
 *   three-layer skin    tests/fixtures/mcml/peer/tissue3.mci (g 0.8 / 0.9 / 0.7; 200 x 200 A(r, z))
 *   MCML's example      the layers and grid of the example.mci that MCML's Unix distribution ships
 *                       (mcR5unix/Sample/example.mci: 1.37 1 100 0.9 0.1 / 1.37 1 10 0 0.1 /
 *                       1.37 2 10 0.7 0.2 [n mua/cm mus/cm g d/cm], dz = dr = 0.01 cm, 40 x 50, na 1)
 *
 * How: MCML is the program named by the environment variable MCML (MCML 1.2.2 built from its
 * published source with gcc -O2: docs/mcml.md, "Benchmark", says where to get it; its source is
 * never in this repository). For each case and each of `reps` rounds, interleaved: MCML on the .mci
 * with 1 photon and with N_M photons, then Lucent (lucent_mc_run on the same .mci, one thread) with
 * 1 photon and N_L photons on each SIMD path. Times are user CPU (MCML: the child's, from wait4;
 * Lucent: this process's, getrusage), net of start-up: rate = (N - 1) / (t(N) - t(1)). Printed: the
 * median over the rounds of each rate and of each per-round ratio, with the rounds' range, and the
 * load average. Then two threads: CPU time per photon against one thread, and the wall-clock speed-up.
 * Usage: MCML=/path/to/mcml bench_mc [seconds_per_run (1.5)] [rounds (5)] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lucent/mc.h"

#define MAX_REPS 32

typedef struct bench_case {
    const char *name;
    const char *file; /* the .mci's name in the temporary folder */
    char mci[1024];   /* its text, photons as %llu */
} bench_case;

/* Skin1 red (Jensen et al. 2001): mua 0.032 mm^-1 = 0.32 cm^-1, mus 0.74 mm^-1 = 7.4 cm^-1; MFP = 1 / 0.772 mm. */
static void skin1(bench_case *c, const char *name, const char *file, double g)
{
    double d = 0.1 / 0.772 / 20.0; /* MFP / 20 in cm */
    c->name = name, c->file = file;
    snprintf(c->mci, sizeof c->mci,
             "1.0\n1\n%s.mco A\n%%llu\n%.8g %.8g\n640 640 30\n1\n1.0\n1.3 0.32 7.4 %g 1e6\n1.0\n", file, d, d, g);
}

static void cases(bench_case c[4])
{
    skin1(&c[0], "Skin1 red, g 0", "skin_g0", 0.0);
    skin1(&c[1], "Skin1 red, g 0.9", "skin_g09", 0.9);
    c[2].name = "three-layer skin", c[2].file = "tissue3";
    snprintf(c[2].mci, sizeof c[2].mci,
             "1.0\n1\ntissue3.mco A\n%%llu\n0.005 0.005\n200 200 30\n3\n1.0\n1.4 1.0 100 0.8 0.01\n"
             "1.4 0.5 200 0.9 0.1\n1.45 0.2 50 0.7 10\n1.0\n");
    c[3].name = "MCML's example", c[3].file = "example";
    snprintf(c[3].mci, sizeof c[3].mci,
             "1.0\n1\nexample.mco A\n%%llu\n0.01 0.01\n40 50 1\n3\n1.0\n1.37 1 100 0.90 0.1\n1.37 1 10 0 0.1\n"
             "1.37 2 10 0.70 0.2\n1.0\n");
}

static char g_dir[256];

static double user_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec;
}

static void write_mci(const bench_case *c, unsigned long long photons, char *path, size_t size)
{
    snprintf(path, size, "%s/%s-%llu.mci", g_dir, c->file, photons);
    FILE *f = fopen(path, "w");
    if (!f) {
        perror(path);
        exit(1);
    }
    fprintf(f, c->mci, photons);
    fclose(f);
}

/* MCML's user CPU seconds on the case with `photons` photons (-1 when it failed). */
static double mcml_run(const char *mcml, const bench_case *c, unsigned long long photons)
{
    char path[512];
    write_mci(c, photons, path, sizeof path);
    fflush(NULL); /* nothing buffered is written twice */
    pid_t pid = fork();
    if (pid == 0) {
        if (chdir(g_dir) != 0 || !freopen("/dev/null", "w", stdout)) _exit(127);
        execl(mcml, mcml, path, (char *)NULL);
        _exit(127);
    }
    int status = 0;
    struct rusage ru;
    if (pid < 0 || wait4(pid, &status, 0, &ru) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec;
}

/* Lucent's user CPU seconds on the case (its .mci parsed by lucent_mcml_parse) on `threads` threads;
 * *wall receives the wall-clock seconds, *rd Rd. */
static double lucent_run(const bench_case *c, unsigned long long photons, int threads, double *wall, double *rd)
{
    char text[1200];
    snprintf(text, sizeof text, c->mci, photons);
    lucent_mcml_file f;
    if (lucent_mcml_parse(text, c->file, &f) != LUCENT_OK) {
        fprintf(stderr, "bench_mc: %s\n", lucent_last_error());
        exit(1);
    }
    lucent_pool *pool = threads > 1 ? lucent_pool_create(threads) : NULL;
    lucent_mc_desc d = f.runs[0].desc;
    d.seed = 1;
    d.pool = pool;
    lucent_mc_result r;
    double t0 = user_seconds(), w0 = lucent_clock_seconds();
    lucent_status s = lucent_mc_run(&d, &r);
    double t = user_seconds() - t0;
    if (wall) *wall = lucent_clock_seconds() - w0;
    lucent_pool_destroy(pool);
    lucent_mcml_file_free(&f);
    if (s != LUCENT_OK) {
        fprintf(stderr, "bench_mc: %s\n", lucent_last_error());
        exit(1);
    }
    if (rd) *rd = r.rd;
    lucent_mc_result_free(&r);
    return t;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(const double *v, int n, double *lo, double *hi)
{
    double s[MAX_REPS];
    memcpy(s, v, (size_t)n * sizeof *v);
    qsort(s, (size_t)n, sizeof *s, cmp_double);
    *lo = s[0], *hi = s[n - 1];
    return n % 2 ? s[n / 2] : 0.5 * (s[n / 2 - 1] + s[n / 2]);
}

/* Photons for a run of about `seconds` user CPU, from a probe. */
static unsigned long long calibrate(double (*run)(const bench_case *, unsigned long long), const bench_case *c,
                                    unsigned long long probe, double seconds)
{
    double t1 = run(c, 1), t = run(c, probe);
    if (t < 0 || t1 < 0) return 0;
    double per = (t - t1) / (double)probe;
    if (!(per > 0)) per = 1e-7;
    unsigned long long n = (unsigned long long)(seconds / per);
    return n < 2 * probe ? 2 * probe : n;
}

static const char *g_mcml;
static double mcml_t(const bench_case *c, unsigned long long n) { return mcml_run(g_mcml, c, n); }
static double lucent_t(const bench_case *c, unsigned long long n) { return lucent_run(c, n, 1, NULL, NULL); }

static void print_load(const char *when)
{
    double l[3];
    if (getloadavg(l, 3) == 3)
        printf("load average %s: %.2f %.2f %.2f (%d cores)\n", when, l[0], l[1], l[2], lucent_cpu_count());
}

static void cpu_name(char *dest, size_t size)
{
    snprintf(dest, size, "unknown CPU");
    FILE *f = fopen("/proc/cpuinfo", "r");
    char line[512];
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, "model name", 10) && strchr(line, ':')) {
            snprintf(dest, size, "%s", strchr(line, ':') + 2);
            dest[strcspn(dest, "\n")] = '\0';
            break;
        }
    if (f) fclose(f);
}

/* Two threads against one on the case: CPU time per photon and wall-clock speed-up. */
static void threads_line(const bench_case *c, unsigned long long n, int reps)
{
    double cpu1[MAX_REPS], cpu2[MAX_REPS], sp[MAX_REPS], lo, hi;
    for (int r = 0; r < reps; r++) {
        double w1, w2, t1 = lucent_run(c, n, 1, &w1, NULL), t2 = lucent_run(c, 2 * n, 2, &w2, NULL);
        cpu1[r] = t1 / (double)n * 1e6, cpu2[r] = t2 / (double)(2 * n) * 1e6;
        sp[r] = (2.0 * (double)n / w2) / ((double)n / w1);
    }
    double a = median(cpu1, reps, &lo, &hi), b = median(cpu2, reps, &lo, &hi), s = median(sp, reps, &lo, &hi);
    printf("\ntwo threads, %s, %s path: CPU per photon %.3f us (1 thread) and %.3f us (2 threads, %+.1f%%); wall-clock "
           "speed-up %.2fx (range %.2f-%.2f; the machine's other load takes its share of the wall clock)\n",
           c->name, lucent_isa_name(lucent_isa_active()), a, b, 100.0 * (b / a - 1.0), s, lo, hi);
}

int main(int argc, char **argv)
{
    double seconds = argc > 1 ? atof(argv[1]) : 1.5;
    int reps = argc > 2 ? atoi(argv[2]) : 5;
    if (!(seconds > 0)) seconds = 1.5;
    if (reps < 1 || reps > MAX_REPS) reps = 5;
    g_mcml = getenv("MCML");
    if (g_mcml && !*g_mcml) g_mcml = NULL;
    snprintf(g_dir, sizeof g_dir, "%s/lucent-bench-mc-XXXXXX", getenv("TMPDIR") ? getenv("TMPDIR") : "/tmp");
    if (!mkdtemp(g_dir)) {
        perror("bench_mc: mkdtemp");
        return 1;
    }
    char cpu[256];
    cpu_name(cpu, sizeof cpu);
    lucent_isa isas[LUCENT_ISA_COUNT];
    int n_isa = 0;
    for (int i = LUCENT_ISA_SCALAR; i < LUCENT_ISA_COUNT; i++)
        if (lucent_isa_supported((lucent_isa)i)) isas[n_isa++] = (lucent_isa)i;
    printf("bench_mc: photons per second on one thread (user CPU, net of start-up), %d rounds per case, interleaved\n"
           "CPU: %s; SIMD paths: ",
           reps, cpu);
    for (int i = 0; i < n_isa; i++) printf("%s%s", lucent_isa_name(isas[i]), i + 1 < n_isa ? ", " : "\n");
    if (g_mcml)
        printf("MCML: %s (MCML 1.2.2 from its published source, gcc -O2), run beside Lucent in every round\n", g_mcml);
    else
        printf("MCML: not measured (set MCML=/path/to/mcml: MCML 1.2.2 built from its published source with gcc -O2, "
               "as docs/mcml.md, \"Benchmark\", says); Lucent's figures alone\n");
    print_load("at the start");
    bench_case c[4];
    cases(c);
    lucent_isa best = isas[n_isa - 1];
    for (int k = 0; k < 4; k++) {
        unsigned long long nm = 0, nl[LUCENT_ISA_COUNT] = {0};
        if (g_mcml && !(nm = calibrate(mcml_t, &c[k], 2000, seconds))) {
            fprintf(stderr, "bench_mc: %s failed on %s/%s-2000.mci\n", g_mcml, g_dir, c[k].file);
            return 1;
        }
        for (int i = 0; i < n_isa; i++) {
            lucent_isa_set(isas[i]);
            nl[i] = calibrate(lucent_t, &c[k], 20000, seconds);
        }
        double rm[MAX_REPS], rl[LUCENT_ISA_COUNT][MAX_REPS], ratio[LUCENT_ISA_COUNT][MAX_REPS], rd = 0;
        for (int r = 0; r < reps; r++) {
            if (g_mcml) {
                double t1 = mcml_run(g_mcml, &c[k], 1), t = mcml_run(g_mcml, &c[k], nm);
                rm[r] = (double)(nm - 1) / (t - t1);
            }
            for (int i = 0; i < n_isa; i++) {
                lucent_isa_set(isas[i]);
                double t1 = lucent_run(&c[k], 1, 1, NULL, NULL), t = lucent_run(&c[k], nl[i], 1, NULL, &rd);
                rl[i][r] = (double)(nl[i] - 1) / (t - t1);
                ratio[i][r] = g_mcml ? rl[i][r] / rm[r] : 0;
            }
        }
        double lo, hi;
        printf("\n%s (%s.mci)\n", c[k].name, c[k].file);
        if (g_mcml) {
            double m = median(rm, reps, &lo, &hi);
            printf("  MCML 1.2.2       %9.0f photons/s  (range %.0f-%.0f; %llu photons per run)\n", m, lo, hi, nm);
        }
        for (int i = 0; i < n_isa; i++) {
            double m = median(rl[i], reps, &lo, &hi);
            printf("  Lucent %-9s %9.0f photons/s  (range %.0f-%.0f; %llu photons per run)", lucent_isa_name(isas[i]),
                   m, lo, hi, nl[i]);
            if (g_mcml) {
                double q = median(ratio[i], reps, &lo, &hi);
                printf("  = %.1fx MCML (range %.1f-%.1f)", q, lo, hi);
            }
            printf("\n");
        }
        printf("  Rd %.4f (Lucent, %s, the last run)\n", rd, lucent_isa_name(isas[n_isa - 1]));
    }
    lucent_isa_set(best);
    threads_line(&c[1], 200000, reps);
    print_load("at the end");
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", g_dir);
    if (system(cmd) != 0) fprintf(stderr, "bench_mc: could not remove %s\n", g_dir);
    return 0;
}
