/* Benchmark of per-vertex curvature (issue 5): the Stanford dragon res1-res4, each method on
 * one and two threads, beside the trimesh2 anchor measured on this kind of machine (its
 * curvature step on res1: 0.18-0.25 s on one thread, 0.11-0.15 s on two), and the accuracy on
 * the acceptance torus (R = 3, r = 1, 192 x 64; trimesh2 as shipped: 8.2% mean-curvature RMS).
 * Times are the best (and median) of `repeats` runs, normals included, loading excluded; the
 * load average is printed before and after, since other work on the machine shows in them.
 * Usage: bench_curvature [repeats] [mesh_dir] */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lucent/mesh.h"

/* ", load average 1.23 0.98 0.70" from /proc/loadavg where there is one, then a newline. */
static void print_load(void)
{
    FILE *f = fopen("/proc/loadavg", "r");
    double l[3];
    if (f && fscanf(f, "%lf %lf %lf", l, l + 1, l + 2) == 3) printf(", load average %.2f %.2f %.2f", l[0], l[1], l[2]);
    if (f) fclose(f);
    printf("\n");
}

static int finite_all(const lucent_curvature *c)
{
    for (size_t v = 0; v < c->count; v++)
        if (!isfinite(c->k1[v] + c->k2[v] + c->mean[v] + c->gauss[v])) return 0;
    return 1;
}

/* Times of `repeats` runs: best and median wall time, best process CPU time; *ok is cleared on
 * failure or non-finite output. CPU time shows what a loaded machine hides in wall time. */
typedef struct timing {
    double best, median, cpu;
} timing;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static timing time_curvature_desc(const lucent_mesh *m, const lucent_curvature_desc *d, int repeats, int *ok)
{
    double wall[64];
    timing t = {INFINITY, INFINITY, INFINITY};
    if (repeats > 64) repeats = 64;
    for (int r = 0; r < repeats; r++) {
        lucent_curvature c = {0};
        double t0 = lucent_clock_seconds(), c0 = lucent_cpu_seconds();
        lucent_status s = lucent_mesh_curvature(m, d, &c);
        wall[r] = lucent_clock_seconds() - t0, t.cpu = fmin(t.cpu, lucent_cpu_seconds() - c0);
        if (s != LUCENT_OK || !finite_all(&c) || c.invalid_count > m->vertex_count / 100) *ok = 0;
        lucent_curvature_free(&c);
    }
    qsort(wall, (size_t)repeats, sizeof *wall, cmp_double);
    t.best = wall[0], t.median = wall[repeats / 2];
    return t;
}

/* One method (fast: Rusinkiewicz's first pass only) on one and two threads, one line. */
static void bench_method(const lucent_mesh *m, int method, int fast, int repeats, lucent_pool *one, lucent_pool *two,
                         const char *anchor)
{
    int ok = 1;
    lucent_curvature_desc d = {.method = method, .fast = fast, .pool = one};
    timing t1 = time_curvature_desc(m, &d, repeats, &ok);
    d.pool = two;
    timing t2 = time_curvature_desc(m, &d, repeats, &ok);
    printf("    %-13s 1 thread %.3f s (median %.3f, cpu %.3f), 2 threads %.3f s (median %.3f, cpu %.3f)  %s%s\n",
           fast ? "rusink. fast" : lucent_curvature_method_name(method), t1.best, t1.median, t1.cpu, t2.best, t2.median,
           t2.cpu, ok ? "finite" : "NON-FINITE OR FAILED", anchor);
}

static void bench_mesh(const char *dir, const char *file, int raw, int repeats, lucent_pool *one, lucent_pool *two)
{
    char path[2048];
    snprintf(path, sizeof path, "%s/%s", dir, file);
    lucent_mesh *m;
    double t0 = lucent_clock_seconds();
    if (lucent_mesh_load(path, &(lucent_mesh_load_desc){.keep_duplicates = raw}, &m) != LUCENT_OK) {
        printf("  %-26s skipped: %s\n", file, lucent_last_error());
        return;
    }
    double tl = lucent_clock_seconds() - t0;
    lucent_mesh_stats st;
    lucent_mesh_stats_compute(m, &st);
    printf("  %-24s %-6s %7zu vertices, load %.2f s; %zu boundary / %zu non-manifold edges, %zu zero-area faces\n",
           file, raw ? "(raw)" : "(weld)", m->vertex_count, tl, st.boundary_edges, st.nonmanifold_edges,
           st.degenerate_faces);
    int res1 = strcmp(file, "dragon_vrip.ply.gz") == 0;
    for (int method = 0; method < 3; method++)
        bench_method(m, method, 0, repeats, one, two,
                     res1 && method == 0 ? "   [trimesh2 res1: 0.18-0.25 s / 0.11-0.15 s]" : "");
    bench_method(m, 0, 1, repeats, one, two, "");
    lucent_mesh_destroy(m);
}

static void bench_torus(double jitter, const char *anchor)
{
    lucent_primitive_desc d = {.kind = LUCENT_PRIMITIVE_TORUS,
                               .major_radius = 3,
                               .radius = 1,
                               .u_count = 192,
                               .v_count = 64,
                               .jitter = jitter,
                               .seed = 7};
    lucent_mesh *m;
    if (lucent_mesh_primitive(&d, &m) != LUCENT_OK) return;
    printf("  torus 192x64%s:", jitter > 0 ? " jittered 1/4 cell" : "");
    for (int method = 0; method < 3; method++) {
        lucent_curvature c = {0};
        if (lucent_mesh_curvature(m, &(lucent_curvature_desc){.method = method}, &c) != LUCENT_OK) continue;
        double s = 0;
        for (size_t v = 0; v < m->vertex_count; v++) {
            lucent_curvature_value truth;
            lucent_primitive_curvature(&d, m->positions + 3 * v, &truth);
            double e = (c.mean[v] - truth.mean) / truth.mean;
            s += e * e;
        }
        printf(" %s %.3f%%", lucent_curvature_method_name(method), 100 * sqrt(s / (double)m->vertex_count));
        lucent_curvature_free(&c);
    }
    lucent_curvature c = {0};
    if (lucent_mesh_curvature(m, &(lucent_curvature_desc){.fast = 1}, &c) == LUCENT_OK) {
        double s = 0;
        for (size_t v = 0; v < m->vertex_count; v++) {
            lucent_curvature_value truth;
            lucent_primitive_curvature(&d, m->positions + 3 * v, &truth);
            s += pow((c.mean[v] - truth.mean) / truth.mean, 2);
        }
        printf(" rusinkiewicz --fast %.3f%%", 100 * sqrt(s / (double)m->vertex_count));
        lucent_curvature_free(&c);
    }
    printf("   [%s]\n", anchor);
    lucent_mesh_destroy(m);
}

/* data/meshes beside this source file (__FILE__ is absolute in the CMake build), else ./data/meshes. */
static const char *default_mesh_dir(void)
{
    static char dir[2048];
    const char *slash = strrchr(__FILE__, '/');
    if (!slash || __FILE__[0] != '/') return "data/meshes";
    snprintf(dir, sizeof dir, "%.*s/../data/meshes", (int)(slash - __FILE__), __FILE__);
    return dir;
}

int main(int argc, char **argv)
{
    int repeats = argc > 1 ? atoi(argv[1]) : 3;
    const char *dir = argc > 2 ? argv[2] : default_mesh_dir();
    if (repeats < 1) repeats = 3;
    lucent_pool *one = lucent_pool_create(1), *two = lucent_pool_create(2);
    printf("bench_curvature: best of %d, %d cores", repeats, lucent_cpu_count());
    print_load();
    printf("accuracy, mean curvature relative RMS error:\n");
    bench_torus(0, "trimesh2 as shipped: 8.2%; target <= 0.1% (rusinkiewicz)");
    bench_torus(0.25, "target <= 4% (rusinkiewicz)");
    printf("speed (curvature step, normals included):\n");
    static const char *const files[] = {"dragon_vrip.ply.gz", "dragon_vrip_res2.ply.gz", "dragon_vrip_res3.ply.gz",
                                        "dragon_vrip_res4.ply.gz"};
    printf("  (weld: as lucent_mesh_load gives it, duplicate positions merged; raw: the file's own\n"
           "  vertices, keep_duplicates, holes and zero-area faces as scanned)\n");
    bench_mesh(dir, files[0], 1, repeats, one, two);
    for (int i = 0; i < 4; i++) bench_mesh(dir, files[i], 0, repeats, one, two);
    printf("done");
    print_load();
    lucent_pool_destroy(one), lucent_pool_destroy(two);
    return 0;
}
