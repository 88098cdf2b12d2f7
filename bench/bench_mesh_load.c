/* Benchmark of mesh loading (issue 17): the Stanford dragon res1 (data/meshes/dragon_vrip.ply.gz, 34 MB
 * of ASCII PLY inflated) through Lucent's own PLY reader and through assimp (today's path before issue
 * 17, run the same way: in a child process on a closed file system), weld and normals included; then
 * the work of `lucent curvature MESH --out x.csv` (load, curvature, statistics, CSV) in this process
 * through each reader, side by side, and `lucent curvature` itself as a whole process, beside
 * trimesh2's anchor for the same command (0.9 s on this kind of machine, issue 17). Times: best and
 * median of `repeats` runs, wall and CPU (user + sys, children included: first-order insensitive to
 * other work on the machine, which wall times are not; the spread is printed); the load average too.
 * Usage: bench_mesh_load [repeats] [mesh_dir] [lucent binary] */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/time.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lucent/mesh.h"

static void print_load(void)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double l[3];
    if (f && fscanf(f, "%lf %lf %lf", l, l + 1, l + 2) == 3)
        printf("  (load average %.2f %.2f %.2f)\n", l[0], l[1], l[2]);
    if (f) fclose(f);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double tv(struct timeval t) { return (double)t.tv_sec + 1e-6 * (double)t.tv_usec; }

/* CPU seconds of this process and its waited-for children so far. */
static double cpu_all(void)
{
    struct rusage a, b;
    getrusage(RUSAGE_SELF, &a);
    getrusage(RUSAGE_CHILDREN, &b);
    return tv(a.ru_utime) + tv(a.ru_stime) + tv(b.ru_utime) + tv(b.ru_stime);
}

static void bench_load(const char *path, int assimp, int repeats)
{
    double wall[32], cpu = 1e30;
    size_t nv = 0, nf = 0;
    for (int r = 0; r < repeats; r++) {
        lucent_mesh *m;
        double t0 = lucent_clock_seconds(), c0 = cpu_all();
        lucent_status s = lucent_mesh_load(path, &(lucent_mesh_load_desc){.use_assimp = assimp}, &m);
        wall[r] = lucent_clock_seconds() - t0;
        double c = cpu_all() - c0;
        if (c < cpu) cpu = c;
        if (s != LUCENT_OK) {
            printf("  %s: failed: %s\n", assimp ? "assimp" : "lucent", lucent_last_error());
            return;
        }
        nv = m->vertex_count, nf = m->face_count;
        lucent_mesh_destroy(m);
    }
    qsort(wall, (size_t)repeats, sizeof *wall, cmp_double);
    printf("  load %-22s %.3f s (median %.3f), cpu %.3f s; %zu vertices, %zu faces\n",
           assimp ? "through assimp:" : "Lucent's PLY reader:", wall[0], wall[repeats / 2], cpu, nv, nf);
}

/* The command's work in this process: load (through assimp or not), curvature with two threads as
 * the command runs it, statistics, CSV. */
static int pipeline(const char *path, int assimp, const char *out, lucent_pool *pool)
{
    lucent_mesh *m;
    if (lucent_mesh_load(path, &(lucent_mesh_load_desc){.use_assimp = assimp}, &m) != LUCENT_OK) return 0;
    lucent_curvature c = {0};
    lucent_mesh_stats st;
    int ok = lucent_mesh_curvature(m, &(lucent_curvature_desc){.pool = pool}, &c) == LUCENT_OK &&
             lucent_mesh_stats_compute(m, &st) == LUCENT_OK && lucent_curvature_write_csv(out, m, &c) == LUCENT_OK;
    lucent_curvature_free(&c);
    lucent_mesh_destroy(m);
    return ok;
}

static void bench_pipeline(const char *path, int assimp, const char *out, int repeats)
{
    double wall[32], cpu[32];
    lucent_pool *pool = lucent_pool_create(2);
    int n = 0;
    for (int r = 0; r < repeats; r++) {
        double t0 = lucent_clock_seconds(), c0 = cpu_all();
        if (!pipeline(path, assimp, out, pool)) break;
        wall[n] = lucent_clock_seconds() - t0, cpu[n++] = cpu_all() - c0;
    }
    lucent_pool_destroy(pool);
    if (n == 0) {
        printf("  curvature work through %s: failed: %s\n", assimp ? "assimp" : "Lucent's reader", lucent_last_error());
        return;
    }
    qsort(wall, (size_t)n, sizeof *wall, cmp_double), qsort(cpu, (size_t)n, sizeof *cpu, cmp_double);
    printf("  curvature work (load, curvature, stats, CSV) through %-15s %.3f s (median %.3f), cpu %.3f s "
           "(median %.3f, max %.3f)\n",
           assimp ? "assimp:" : "Lucent's reader:", wall[0], wall[n / 2], cpu[0], cpu[n / 2], cpu[n - 1]);
}

/* `lucent curvature PATH --out OUT` as a child process: wall and CPU of the child. */
static int run_curvature(const char *lucent, const char *path, const char *out, double *wall, double *cpu)
{
    double t0 = lucent_clock_seconds();
    fflush(stdout); /* the child must not write this process's buffered lines again */
    pid_t pid = fork();
    if (pid == 0) {
        freopen("/dev/null", "w", stdout), freopen("/dev/null", "w", stderr);
        execl(lucent, lucent, "curvature", path, "--out", out, (char *)NULL);
        _exit(127);
    }
    int st;
    struct rusage ru;
    if (pid < 0 || wait4(pid, &st, 0, &ru) < 0) return 0;
    *wall = lucent_clock_seconds() - t0;
    *cpu = tv(ru.ru_utime) + tv(ru.ru_stime);
    return WIFEXITED(st) && WEXITSTATUS(st) == 0;
}

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 3;
    if (repeats < 1) repeats = 1;
    if (repeats > 32) repeats = 32;
    const char *dir = argc > 2 ? argv[2] : "data/meshes";
    const char *lucent = argc > 3 ? argv[3] : "build/lucent";
    char path[2048];
    snprintf(path, sizeof path, "%s/dragon_vrip.ply.gz", dir);
    if (access(path, R_OK) != 0) {
        printf("bench_mesh_load: %s missing (scripts/fetch_meshes.sh); skipped\n", path);
        return 0;
    }
    printf("mesh load, dragon res1 (%s), best of %d\n", path, repeats);
    print_load();
    bench_load(path, 0, repeats);
    bench_load(path, 1, repeats);
    char out[] = "/tmp/bench_mesh_load_XXXXXX.csv";
    int fd = mkstemps(out, 4);
    if (fd >= 0) close(fd);
    bench_pipeline(path, 0, out, repeats);
    bench_pipeline(path, 1, out, repeats);
    double wall[32], cpu[32];
    int n = 0;
    for (int r = 0; r < repeats; r++) {
        if (!run_curvature(lucent, path, out, &wall[n], &cpu[n])) break;
        n++;
    }
    unlink(out);
    if (n == 0) {
        printf("  `%s curvature` failed or is missing\n", lucent);
        return 0;
    }
    qsort(wall, (size_t)n, sizeof *wall, cmp_double), qsort(cpu, (size_t)n, sizeof *cpu, cmp_double);
    printf("  `lucent curvature dragon res1 --out x.csv`, whole process: %.3f s (median %.3f), cpu %.3f s "
           "(median %.3f, max %.3f)   [trimesh2 anchor 0.9 s; 2.2 s through assimp before issue 17]\n",
           wall[0], wall[n / 2], cpu[0], cpu[n / 2], cpu[n - 1]);
    print_load();
    return 0;
}
