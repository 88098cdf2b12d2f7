/* Tests of src/base: errors, logging, progress, thread pool, RNG streams, atomic files, mkdir -p,
 * JSON, the clocks, the vector and matrix helpers, %.Pg text and the radix sort (the optics:
 * test_optics.c). */
#include <float.h>
#include <pthread.h>
#include <stdatomic.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/format_g.h"
#include "base/json.h"
#include "base/mat4.h"
#include "base/radix_sort.h"
#include "base/vec3.h"
#include "lucent/base.h"
#include "lucent/dist.h"
#include "test.h"

/* ---- errors ---- */

TEST(error_message_and_context)
{
    lucent_clear_error();
    CHECK(lucent_last_status() == LUCENT_OK);
    CHECK(strcmp(lucent_last_error(), "") == 0);
    CHECK(lucent_error(LUCENT_ERR_PARSE, "sigma_a: expected %d numbers", 3) == LUCENT_ERR_PARSE);
    CHECK(lucent_error_context(LUCENT_ERR_PARSE, "%s", "skin.json") == LUCENT_ERR_PARSE);
    CHECK(strcmp(lucent_last_error(), "skin.json: sigma_a: expected 3 numbers") == 0);
    CHECK(lucent_last_status() == LUCENT_ERR_PARSE);
    CHECK(strcmp(lucent_status_string(LUCENT_ERR_IO), "input/output error") == 0);
    CHECK(strcmp(lucent_status_string((lucent_status)999), "unknown status") == 0);
}

static void *set_error_in_thread(void *arg)
{
    (void)arg;
    lucent_error(LUCENT_ERR_IO, "from another thread");
    return NULL;
}

TEST(error_is_per_thread)
{
    lucent_error(LUCENT_ERR_NUMERIC, "mine");
    pthread_t t;
    pthread_create(&t, NULL, set_error_in_thread, NULL);
    pthread_join(t, NULL);
    CHECK(strcmp(lucent_last_error(), "mine") == 0);
    CHECK(lucent_last_status() == LUCENT_ERR_NUMERIC);
}

/* ---- logging ---- */

static void capture_sink(lucent_log_level level, const char *message, void *user)
{
    char *buf = user;
    snprintf(buf + strlen(buf), 256 - strlen(buf), "%d:%s;", (int)level, message);
}

TEST(log_filters_by_level)
{
    char buf[256] = "";
    lucent_log_set_sink(capture_sink, buf, LUCENT_LOG_INFO);
    lucent_log(LUCENT_LOG_DEBUG, "hidden");
    lucent_log(LUCENT_LOG_INFO, "shown %d", 1);
    lucent_log(LUCENT_LOG_WARN, "warned");
    lucent_log_set_sink(NULL, NULL, LUCENT_LOG_OFF);
    lucent_log(LUCENT_LOG_ERROR, "dropped");
    CHECK(strcmp(buf, "1:shown 1;2:warned;") == 0);
}

/* ---- progress ---- */

TEST(progress_silent_by_default_and_draws_when_asked)
{
    lucent_progress *p = lucent_progress_begin("silent", 10);
    lucent_progress_add(p, 10);
    CHECK(lucent_progress_done(p) == 10);
    lucent_progress_end(p);
    lucent_progress_add(NULL, 1); /* NULL is accepted */
    lucent_progress_end(NULL);

    FILE *f = tmpfile();
    lucent_progress_set_output(f);
    p = lucent_progress_begin("photons", 1000);
    for (int i = 0; i < 1000; i++) lucent_progress_add(p, 1);
    lucent_progress_end(p);
    lucent_progress_set_output(NULL);
    char text[512] = "";
    rewind(f);
    size_t n = fread(text, 1, sizeof text - 1, f);
    fclose(f);
    text[n] = '\0';
    CHECK_MSG(strstr(text, "photons") && strstr(text, "100.0%") && strstr(text, "took"), "final bar: %s", text);
    CHECK(n > 0 && text[n - 1] == '\n');
}

/* ---- thread pool ---- */

typedef struct sum_ctx {
    _Atomic uint64_t visits[1000];
    _Atomic uint64_t sum;
    int max_thread;
} sum_ctx;

static lucent_status visit_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    sum_ctx *c = ctx;
    (void)chunk;
    for (uint64_t i = begin; i < end; i++) {
        atomic_fetch_add(&c->visits[i], 1);
        atomic_fetch_add(&c->sum, i);
    }
    if (thread > c->max_thread) c->max_thread = thread;
    return LUCENT_OK;
}

TEST(parallel_for_visits_every_item_once)
{
    for (int threads = 1; threads <= 4; threads++) {
        lucent_pool *pool = lucent_pool_create(threads);
        CHECK(lucent_pool_threads(pool) == threads);
        static sum_ctx c;
        memset(&c, 0, sizeof c);
        CHECK_OK(lucent_parallel_for(pool, 1000, 7, visit_chunk, &c));
        int once = 0;
        for (int i = 0; i < 1000; i++) once += c.visits[i] == 1;
        CHECK(once == 1000);
        CHECK(c.sum == 999u * 1000u / 2u); /* Gauss: sum of 0..999 */
        CHECK(c.max_thread < threads);
        lucent_pool_destroy(pool);
    }
    CHECK_OK(lucent_parallel_for(NULL, 0, 1, visit_chunk, NULL)); /* nothing to do */
    CHECK_ERR(lucent_parallel_for(NULL, 10, 0, visit_chunk, NULL), LUCENT_ERR_INVALID_ARGUMENT, "chunk size");
}

static lucent_status fail_some_chunks(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)ctx, (void)begin, (void)end, (void)thread;
    if (chunk == 13 || chunk == 40) return lucent_error(LUCENT_ERR_NUMERIC, "chunk %d failed", (int)chunk);
    usleep(100);
    return LUCENT_OK;
}

TEST(parallel_for_reports_lowest_failing_chunk)
{
    lucent_pool *pool = lucent_pool_create(2);
    for (int rep = 0; rep < 20; rep++) {
        lucent_clear_error();
        CHECK_ERR(lucent_parallel_for(pool, 64, 1, fail_some_chunks, NULL), LUCENT_ERR_NUMERIC, "chunk 13 failed");
    }
    lucent_pool_destroy(pool);
}

typedef struct share_ctx {
    _Atomic uint64_t visits[1000];
    _Atomic uint64_t wrong_chunk; /* chunks run outside the share */
    uint64_t offset, stride;
} share_ctx;

static lucent_status visit_share(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    share_ctx *c = ctx;
    (void)thread;
    if (chunk % c->stride != c->offset || begin != chunk * 7) atomic_fetch_add(&c->wrong_chunk, 1);
    for (uint64_t i = begin; i < end; i++) atomic_fetch_add(&c->visits[i], 1);
    return LUCENT_OK;
}

/* The chunks of processes 0 .. P-1 (lucent/dist.h: chunk % P == p) together are every chunk once,
 * with the same chunk numbers and bounds as one process's loop. */
TEST(parallel_for_share_splits_the_same_chunks)
{
    lucent_pool *pool = lucent_pool_create(3);
    static share_ctx c;
    for (uint64_t stride = 1; stride <= 5; stride++) {
        memset(&c, 0, sizeof c);
        for (uint64_t offset = 0; offset < stride; offset++) {
            c.offset = offset, c.stride = stride;
            CHECK_OK(lucent_parallel_for_share(pool, 1000, 7, visit_share, &c, (lucent_share){offset, stride}));
        }
        int once = 0;
        for (int i = 0; i < 1000; i++) once += c.visits[i] == 1;
        CHECK_MSG(once == 1000 && c.wrong_chunk == 0, "stride %d: %d items once, %d chunks outside the share",
                  (int)stride, once, (int)c.wrong_chunk);
    }
    memset(&c, 0, sizeof c);
    c.stride = 1;
    CHECK_OK(lucent_parallel_for_share(pool, 1000, 7, visit_share, &c, (lucent_share){0, 0}));     /* a merge: none */
    CHECK_OK(lucent_parallel_for_share(pool, 1000, 7, visit_share, &c, (lucent_share){200, 300})); /* past the end */
    int none = 0;
    for (int i = 0; i < 1000; i++) none += c.visits[i] == 0;
    CHECK(none == 1000);
    /* the lowest failing chunk of the share: 13 (odd) for offset 1 of 2, 40 for offset 0 */
    CHECK_ERR(lucent_parallel_for_share(pool, 64, 1, fail_some_chunks, NULL, (lucent_share){1, 2}), LUCENT_ERR_NUMERIC,
              "chunk 13 failed");
    CHECK_ERR(lucent_parallel_for_share(pool, 64, 1, fail_some_chunks, NULL, (lucent_share){0, 2}), LUCENT_ERR_NUMERIC,
              "chunk 40 failed");
    lucent_pool_destroy(pool);
}

/* One process (no MPI launcher, no part): sums are the values themselves and errors pass through. */
TEST(dist_one_process_is_the_identity)
{
    CHECK(lucent_dist_rank() == 0 && lucent_dist_size() == 1 && !lucent_dist_active());
    lucent_share sh = lucent_dist_share();
    CHECK(sh.offset == 0 && sh.stride == 1);
    int64_t v[3] = {1, -2, 3};
    CHECK_OK(lucent_dist_sum(LUCENT_OK, LUCENT_DIST_I64, v, 3));
    CHECK(v[0] == 1 && v[1] == -2 && v[2] == 3);
    lucent_error(LUCENT_ERR_IO, "disk on fire");
    CHECK_ERR(lucent_dist_sum(LUCENT_ERR_IO, LUCENT_DIST_I64, v, 3), LUCENT_ERR_IO, "disk on fire");
    CHECK_OK(lucent_dist_agree(LUCENT_OK)); /* one process does not latch a failure */
    CHECK(lucent_dist_writes_outputs());
}

static lucent_status inner_loop(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)thread;
    sum_ctx *c = ctx;
    for (uint64_t i = begin; i < end; i++) atomic_fetch_add(&c->sum, 1);
    return LUCENT_OK;
}

static lucent_pool *g_nested_pool;

static lucent_status outer_loop(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)chunk, (void)begin, (void)end, (void)thread;
    return lucent_parallel_for(g_nested_pool, 100, 10, inner_loop, ctx);
}

TEST(parallel_for_nested_runs_without_deadlock)
{
    g_nested_pool = lucent_pool_create(2);
    static sum_ctx c;
    memset(&c, 0, sizeof c);
    CHECK_OK(lucent_parallel_for(g_nested_pool, 8, 1, outer_loop, &c));
    CHECK(c.sum == 800);
    lucent_pool_destroy(g_nested_pool);
}

static char g_logged[512];

static void capture_log(lucent_log_level level, const char *message, void *user)
{
    (void)level, (void)user;
    snprintf(g_logged, sizeof g_logged, "%s", message);
}

TEST(pool_size_from_environment)
{
    setenv("LUCENT_THREADS", "3", 1);
    lucent_pool *pool = lucent_pool_create(0);
    CHECK(lucent_pool_threads(pool) == 3);
    lucent_pool_destroy(pool);
    /* a value that is not a whole number from 1 to 256 is said, not silently replaced (issue 32) */
    static const char *const bad[] = {"garbage", "-3", "257"};
    for (int i = 0; i < 3; i++) {
        setenv("LUCENT_THREADS", bad[i], 1);
        g_logged[0] = '\0';
        lucent_log_set_sink(capture_log, NULL, LUCENT_LOG_WARN);
        pool = lucent_pool_create(0);
        lucent_log_set_sink(NULL, NULL, LUCENT_LOG_ERROR);
        CHECK(lucent_pool_threads(pool) == lucent_cpu_count());
        char want[96];
        snprintf(want, sizeof want, "LUCENT_THREADS='%s' is not a whole number from 1 to 256: using all", bad[i]);
        CHECK_MSG(strstr(g_logged, want) != NULL, "logged \"%s\"", g_logged);
        lucent_pool_destroy(pool);
    }
    unsetenv("LUCENT_THREADS");
}

/* ---- random numbers ---- */

TEST(rng_matches_xoshiro256starstar_reference)
{
    /* Expected values computed independently (a Python transcription of the published
     * algorithm) from the state {1, 2, 3, 4}. */
    lucent_rng r = {{1, 2, 3, 4}};
    CHECK(lucent_rng_next(&r) == 11520u);
    CHECK(lucent_rng_next(&r) == 0u);
    CHECK(lucent_rng_next(&r) == 1509978240u);
    CHECK(lucent_rng_next(&r) == 1215971899390074240u);
}

/* Pearson's chi-square of n uniform draws over `bins` equal bins. */
static double chi_square_uniform(lucent_rng *r, int bins, int n)
{
    int *count = calloc((size_t)bins, sizeof *count);
    for (int i = 0; i < n; i++) {
        double u = lucent_rng_uniform(r);
        CHECK(u >= 0.0 && u < 1.0);
        count[(int)(u * bins)]++;
    }
    double expect = (double)n / bins, chi2 = 0;
    for (int b = 0; b < bins; b++) chi2 += (count[b] - expect) * (count[b] - expect) / expect;
    free(count);
    return chi2;
}

TEST(rng_streams_are_uniform)
{
    /* 100 bins: 99 degrees of freedom; the 0.1% critical value of chi-square(99) is 148.23
     * (NIST/SEMATECH e-Handbook, Table 1.3.6.7.4). Eight streams of one seed, each tested. */
    for (uint64_t stream = 0; stream < 8; stream++) {
        lucent_rng r;
        lucent_rng_init(42, stream, &r);
        double chi2 = chi_square_uniform(&r, 100, 200000);
        CHECK_MSG(chi2 < 148.23, "stream %d: chi2 = %.1f", (int)stream, chi2);
    }
    lucent_rng r;
    lucent_rng_init(7, 0, &r);
    int n = 200000, bins = 100, count[100] = {0};
    for (int i = 0; i < n; i++) {
        float u = lucent_rng_uniformf(&r);
        CHECK(u >= 0.0f && u < 1.0f);
        count[(int)(u * (float)bins)]++;
    }
    double chi2 = 0, e = (double)n / bins;
    for (int b = 0; b < bins; b++) chi2 += (count[b] - e) * (count[b] - e) / e;
    CHECK_MSG(chi2 < 148.23, "float chi2 = %.1f", chi2);
}

TEST(rng_neighbouring_streams_are_independent)
{
    /* Stream k and k+1 of one seed: (1) Pearson correlation of paired draws; under
     * independence r ~ N(0, 1/n), so |r| < 4/sqrt(n) fails by chance with p = 6e-5;
     * (2) chi-square of the joint 16x16 histogram of pairs (255 dof; 0.1% critical value
     * 330.5, Wilson-Hilferty approximation), which also sees non-linear dependence. */
    enum { N = 100000, G = 16 };
    for (uint64_t k = 0; k < 16; k++) {
        lucent_rng a, b;
        lucent_rng_init(2024, k, &a);
        lucent_rng_init(2024, k + 1, &b);
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        static int joint[G][G];
        memset(joint, 0, sizeof joint);
        for (int i = 0; i < N; i++) {
            double x = lucent_rng_uniform(&a), y = lucent_rng_uniform(&b);
            sx += x, sy += y, sxx += x * x, syy += y * y, sxy += x * y;
            joint[(int)(x * G)][(int)(y * G)]++;
        }
        double cov = sxy / N - sx / N * sy / N;
        double corr = cov / sqrt((sxx / N - sx * sx / N / N) * (syy / N - sy * sy / N / N));
        CHECK_MSG(fabs(corr) < 4 / sqrt(N), "streams %d,%d: r = %.5f", (int)k, (int)k + 1, corr);
        double e = (double)N / (G * G), chi2 = 0;
        for (int i = 0; i < G; i++)
            for (int j = 0; j < G; j++) chi2 += (joint[i][j] - e) * (joint[i][j] - e) / e;
        CHECK_MSG(chi2 < 330.5, "streams %d,%d: joint chi2 = %.1f", (int)k, (int)k + 1, chi2);
    }
}

TEST(rng_same_seed_same_numbers_other_seed_differs)
{
    lucent_rng a, b, c;
    lucent_rng_init(1, 5, &a);
    lucent_rng_init(1, 5, &b);
    lucent_rng_init(2, 5, &c);
    int same = 0, differ = 0;
    for (int i = 0; i < 100; i++) {
        uint64_t x = lucent_rng_next(&a);
        same += x == lucent_rng_next(&b);
        differ += x != lucent_rng_next(&c);
    }
    CHECK(same == 100);
    CHECK(differ == 100);
    lucent_rng j = a;
    lucent_rng_jump(&j);
    CHECK(memcmp(&j, &a, sizeof j) != 0);
    lucent_rng j2 = a;
    lucent_rng_jump(&j2);
    CHECK(memcmp(&j, &j2, sizeof j) == 0);
}

typedef struct mc_ctx {
    double chunk_sum[256];
} mc_ctx;

static lucent_status mc_chunk(void *ctx, uint64_t chunk, uint64_t begin, uint64_t end, int thread)
{
    (void)thread;
    mc_ctx *c = ctx;
    lucent_rng r;
    lucent_rng_init(99, chunk, &r);
    double s = 0;
    for (uint64_t i = begin; i < end; i++) s += lucent_rng_uniform(&r);
    c->chunk_sum[chunk] = s;
    return LUCENT_OK;
}

TEST(rng_per_chunk_streams_independent_of_thread_count)
{
    static mc_ctx one, two;
    lucent_pool *p1 = lucent_pool_create(1), *p2 = lucent_pool_create(2);
    CHECK_OK(lucent_parallel_for(p1, 256 * 1000, 1000, mc_chunk, &one));
    CHECK_OK(lucent_parallel_for(p2, 256 * 1000, 1000, mc_chunk, &two));
    CHECK(memcmp(one.chunk_sum, two.chunk_sum, sizeof one.chunk_sum) == 0);
    double total = 0;
    for (int i = 0; i < 256; i++) total += one.chunk_sum[i];
    /* mean of 256000 uniforms: 0.5 +- sqrt(1/12/256000) = 5.7e-4; 5 sigma */
    CHECK_NEAR(total / 256000, 0.5, 5 * 5.7e-4);
    lucent_pool_destroy(p1);
    lucent_pool_destroy(p2);
}

/* ---- files ---- */

static bool only_file_in_dir(const char *dir, const char *name)
{
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "test \"$(ls -A '%s')\" = '%s'", dir, name);
    return system(cmd) == 0;
}

TEST(atomic_write_replaces_only_when_complete)
{
    char dir[1024];
    snprintf(dir, sizeof dir, "%s", test_path("atomic"));
    mkdir(dir, 0755);
    char path[1100];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    CHECK_OK(lucent_write_file(path, "first", 5));
    char *text;
    size_t size;
    CHECK_OK(lucent_read_file(path, &text, &size));
    CHECK(size == 5 && strcmp(text, "first") == 0);
    free(text);

    lucent_atomic_file *af;
    FILE *fp;
    CHECK_OK(lucent_atomic_open(path, &af, &fp));
    fputs("half", fp);
    lucent_atomic_abort(af); /* a failed writer: the old content stays */
    CHECK_OK(lucent_read_file(path, &text, &size));
    CHECK(strcmp(text, "first") == 0);
    free(text);
    CHECK(only_file_in_dir(dir, "out.txt"));

    struct stat st;
    CHECK(stat(path, &st) == 0 && (st.st_mode & 0444) == 0444); /* readable, not 0600 */
}

TEST(atomic_write_errors_name_the_path)
{
    char path[1100];
    snprintf(path, sizeof path, "%s", test_path("no/such/dir/out.txt"));
    CHECK_ERR(lucent_write_file(path, "x", 1), LUCENT_ERR_IO, path, "No such file or directory");
    CHECK(access(path, F_OK) != 0);

    /* A regular file used as a directory fails for root too. */
    snprintf(path, sizeof path, "%s", test_path("plain"));
    CHECK_OK(lucent_write_file(path, "x", 1));
    strcat(path, "/out.txt");
    CHECK_ERR(lucent_write_file(path, "x", 1), LUCENT_ERR_IO, path, "Not a directory");

    CHECK_ERR(lucent_write_file(test_tmpdir(), "x", 1), LUCENT_ERR_IO, "is a directory");
    CHECK_ERR(lucent_read_file(test_path("missing.txt"), &(char *){0}, NULL), LUCENT_ERR_IO, "missing.txt",
              "cannot open");
}

/* Writes into dir/out.txt and checks the failure; returns the number of failed checks. */
static int write_into_read_only(const char *dir)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/out.txt", dir);
    CHECK_ERR(lucent_write_file(path, "x", 1), LUCENT_ERR_IO, path, "Permission denied");
    CHECK(access(path, F_OK) != 0);
    CHECK(only_file_in_dir(dir, "keep.txt")); /* no temporary left behind */
    return test_failures_;
}

TEST(atomic_write_into_read_only_directory)
{
    char dir[1100], keep[1200];
    snprintf(dir, sizeof dir, "%s", test_path("readonly"));
    mkdir(dir, 0755);
    snprintf(keep, sizeof keep, "%s/keep.txt", dir);
    CHECK_OK(lucent_write_file(keep, "k", 1));
    chmod(dir, 0555);
    if (geteuid() != 0) {
        write_into_read_only(dir);
    } else {
        /* root ignores directory permissions: try as the unprivileged user nobody. */
        chmod(test_tmpdir(), 0755);
        pid_t pid = fork();
        if (pid == 0) {
            if (setgid(65534) != 0 || setuid(65534) != 0) _exit(99);
            _exit(write_into_read_only(dir) ? 1 : 0);
        }
        int status = 0;
        waitpid(pid, &status, 0);
        CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child as nobody: status %d", status);
    }
    chmod(dir, 0755);
}

TEST(mkdir_p_creates_parents_and_names_what_blocks_it)
{
    char dir[1100], file[1100], deep[1200];
    snprintf(dir, sizeof dir, "%s", test_path("mk/a/b/c"));
    CHECK_OK(lucent_mkdir_p(dir));
    struct stat st;
    CHECK(stat(dir, &st) == 0 && S_ISDIR(st.st_mode));
    CHECK_OK(lucent_mkdir_p(dir)); /* there already: fine */
    snprintf(deep, sizeof deep, "%s/", dir);
    CHECK_OK(lucent_mkdir_p(deep)); /* a trailing slash */
    snprintf(file, sizeof file, "%s", test_path("mk/file"));
    CHECK_OK(lucent_write_file(file, "x", 1));
    snprintf(deep, sizeof deep, "%s/sub", file);
    CHECK_ERR(lucent_mkdir_p(deep), LUCENT_ERR_IO, file, "cannot create the folder", "Not a directory");
    CHECK_ERR(lucent_mkdir_p(file), LUCENT_ERR_IO, file, "Not a directory");
    CHECK_ERR(lucent_mkdir_p(""), LUCENT_ERR_INVALID_ARGUMENT, "empty");
}

/* ---- JSON ---- */

TEST(json_errors_carry_file_and_path)
{
    const char *text = "{\"scene\": {\"lights\": [ {\"direction\": [0, 1, 0]},\n"
                       "  {\"direction\": [0, 1], \"kind\": 3, \"on\": true} ]}}";
    cJSON *root;
    CHECK_OK(lucent_json_parse_text(text, "scene.json", &root));
    lucent_json_node doc = lucent_json_root(root, "scene.json", ""), scene, lights, light;
    int count;
    CHECK_OK(lucent_json_object(&doc, "scene", true, &scene));
    CHECK_OK(lucent_json_array(&scene, "lights", true, &lights, &count));
    CHECK(count == 2);
    double dir[3];
    CHECK_OK(lucent_json_element(&lights, 0, &light));
    CHECK_OK(lucent_json_numbers(&light, "direction", 3, false, dir));
    CHECK(dir[1] == 1.0);
    CHECK_OK(lucent_json_element(&lights, 1, &light));
    CHECK_ERR(lucent_json_numbers(&light, "direction", 3, false, dir), LUCENT_ERR_PARSE,
              "scene.json: scene.lights[1].direction: expected 3 numbers");
    const char *s;
    CHECK_ERR(lucent_json_string(&light, "kind", &s), LUCENT_ERR_PARSE,
              "scene.json: scene.lights[1].kind: expected a string, got a number");
    CHECK_ERR(lucent_json_number(&light, "power", dir), LUCENT_ERR_PARSE, "scene.lights[1].power: missing field");
    bool on;
    CHECK_OK(lucent_json_bool_or(&light, "on", false, &on));
    CHECK(on);
    double def;
    CHECK_OK(lucent_json_number_or(&light, "power", 2.5, &def));
    CHECK(def == 2.5);
    lucent_json_node absent;
    CHECK_ERR(lucent_json_element(&lights, 2, &absent), LUCENT_ERR_PARSE, "scene.lights: has no element 2");
    const char *known[] = {"direction", "on", NULL};
    CHECK_ERR(lucent_json_check_keys(&light, known), LUCENT_ERR_PARSE,
              "scene.lights[1].kind: unknown field (known: direction, on)");
    cJSON_Delete(root);
}

TEST(json_rejects_broken_text_nan_and_infinity)
{
    cJSON *root;
    CHECK_ERR(lucent_json_parse_text("{\n \"a\": 1,\n \"b\": }", "m.json", &root), LUCENT_ERR_PARSE, "m.json: line 3",
              "invalid JSON");
    CHECK_ERR(lucent_json_parse_text("{\"a\": 1,\n \"sigma_a\": [0.1, NaN, 2]}", "m.json", &root), LUCENT_ERR_PARSE,
              "m.json: line 2, column 19 (in field \"sigma_a\"): not a number JSON allows");
    CHECK_ERR(lucent_json_parse_text("{\"a\": [1, 2", "m.json", &root), LUCENT_ERR_PARSE, "unexpected end of file");
    CHECK_OK(lucent_json_parse_text("{\"a\": 1e999, \"a2\": 1, \"a2\": 2}", "m.json", &root));
    lucent_json_node doc = lucent_json_root(root, "m.json", "");
    double v;
    CHECK_ERR(lucent_json_number(&doc, "a", &v), LUCENT_ERR_PARSE, "m.json: a: expected a finite number");
    const char *known[] = {"a", "a2", NULL};
    CHECK_ERR(lucent_json_check_keys(&doc, known), LUCENT_ERR_PARSE, "a2: field given twice");
    cJSON_Delete(root);
    CHECK_ERR(lucent_json_parse_file(test_path("absent.json"), &root), LUCENT_ERR_IO, "absent.json");
}

TEST(json_numbers_accept_scalar_when_allowed_and_write_round_trip)
{
    cJSON *root;
    CHECK_OK(lucent_json_parse_text("{\"g\": 0.5}", "x.json", &root));
    lucent_json_node doc = lucent_json_root(root, "x.json", "material");
    double g[3];
    CHECK_OK(lucent_json_numbers(&doc, "g", 3, true, g));
    CHECK(g[0] == 0.5 && g[2] == 0.5);
    CHECK_ERR(lucent_json_numbers(&doc, "g", 3, false, g), LUCENT_ERR_PARSE, "material.g: expected 3 numbers");
    double v[3] = {1, 0.25, -3};
    CHECK(lucent_json_add_numbers(root, "v", v, 3) != NULL);
    CHECK_OK(lucent_json_write_file(test_path("rt.json"), root));
    cJSON_Delete(root);
    CHECK_OK(lucent_json_parse_file(test_path("rt.json"), &root));
    doc = lucent_json_root(root, "rt.json", "");
    double w[3];
    CHECK_OK(lucent_json_numbers(&doc, "v", 3, false, w));
    CHECK(w[0] == 1 && w[1] == 0.25 && w[2] == -3);
    cJSON_Delete(root);
}

/* ---- clocks ---- */

TEST(clocks_are_monotonic_and_agree_in_units)
{
    /* No wall time is asserted: only that the clock never goes back and that ms = 1000 s. */
    double prev = lucent_clock_seconds(), cpu = lucent_cpu_seconds();
    for (int i = 0; i < 1000; i++) {
        double t = lucent_clock_seconds();
        CHECK(t >= prev);
        prev = t;
    }
    double s0 = lucent_clock_seconds(), ms = lucent_clock_ms(), s1 = lucent_clock_seconds();
    CHECK(s0 * 1e3 <= ms * (1 + 1e-15) && ms <= s1 * 1e3 * (1 + 1e-15));
    CHECK(cpu >= 0 && lucent_cpu_seconds() >= cpu);
}

/* ---- vectors and matrices ---- */

TEST(vectors_follow_their_definitions_and_zero_normalises_to_zero)
{
    v3 a = v3_make(1, 2, 3), b = v3_make(-4, 0.5, 2);
    v3 s = v3_add(a, b), d = v3_sub(a, b), k = v3_scale(a, -2), m = v3_madd(a, b, 2);
    CHECK(s.x == -3 && s.y == 2.5 && s.z == 5 && d.x == 5 && d.y == 1.5 && d.z == 1);
    CHECK(k.x == -2 && k.y == -4 && k.z == -6 && m.x == -7 && m.y == 3 && m.z == 7);
    CHECK(v3_dot(a, b) == -4 + 1 + 6);
    CHECK(v3_length(v3_make(3, 4, 12)) == 13);
    /* a x b = (2 * 2 - 3 * 0.5, 3 * -4 - 1 * 2, 1 * 0.5 - 2 * -4); x x y = z (right-handed) */
    v3 c = v3_cross(a, b), z = v3_cross(v3_make(1, 0, 0), v3_make(0, 1, 0));
    CHECK(c.x == 2.5 && c.y == -14 && c.z == 8.5 && z.x == 0 && z.y == 0 && z.z == 1);
    CHECK(v3_dot(c, a) == 0 && v3_dot(c, b) == 0);
    v3 u = v3_normalize(v3_make(0, -3, 4));
    CHECK_NEAR(u.y, -0.6, 4e-16); /* |(0, -3, 4)| = 5; two roundings (1 / 5, then the product) */
    CHECK_NEAR(u.z, 0.8, 4e-16);
    /* degenerate input: zero, and non-finite lengths, normalise to the zero vector */
    const v3 bad[] = {{0, 0, 0}, {-0.0, 0, 0}, {INFINITY, 0, 0}, {NAN, 1, 0}, {1e300, 1e300, 0}};
    for (int i = 0; i < 5; i++) {
        v3 n = v3_normalize(bad[i]);
        CHECK(n.x == 0 && n.y == 0 && n.z == 0);
    }
    double arr[3] = {0};
    v3_store(v3_load((const double[3]){7, 8, 9}), arr);
    CHECK(arr[0] == 7 && arr[1] == 8 && arr[2] == 9);
}

TEST(mat4_multiplies_column_major)
{
    /* A translation T(1, 2, 3) (column 3) times a scale S(2, 3, 4): T S maps p to S p + t. */
    double T[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 2, 3, 1};
    double S[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 0, 0, 0, 1}, TS[16], ST[16];
    lucent_mat4_mul(T, S, TS);
    lucent_mat4_mul(S, T, ST);
    const double want_ts[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 1, 2, 3, 1};
    const double want_st[16] = {2, 0, 0, 0, 0, 3, 0, 0, 0, 0, 4, 0, 2, 6, 12, 1};
    CHECK(memcmp(TS, want_ts, sizeof TS) == 0 && memcmp(ST, want_st, sizeof ST) == 0);
    /* a general product, element (r, c) = sum_k a(r, k) b(k, c), with dest aliasing a */
    double A[16], B[16], R[16];
    for (int i = 0; i < 16; i++) A[i] = i + 1, B[i] = (i % 5) - 2.0;
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) {
            R[4 * c + r] = 0;
            for (int k = 0; k < 4; k++) R[4 * c + r] += A[4 * k + r] * B[4 * c + k];
        }
    lucent_mat4_mul(A, B, A);
    CHECK(memcmp(A, R, sizeof R) == 0);
    float f[16];
    lucent_mat4_to_float(want_st, f);
    CHECK(f[14] == 12.0f && f[15] == 1.0f);
}

/* ---- number text and sorting (the curvature CSV, mesh statistics) ---- */

/* lucent_format_g against glibc's snprintf "%.*g" (the independent reference): the same bytes,
 * or the first difference is printed. Returns 1 when they agree. */
static int format_g_agrees(double x, int p)
{
    char mine[LUCENT_FORMAT_G_MAX], libc[64];
    int n = lucent_format_g(mine, x, p);
    snprintf(libc, sizeof libc, "%.*g", p, x);
    if (n == (int)strlen(libc) && strcmp(mine, libc) == 0) return 1;
    TEST_FAIL_("%%.%dg of %a: '%s' (length %d), snprintf '%s'", p, x, mine, n, libc);
    return 0;
}

TEST(format_g_matches_snprintf_on_edge_values)
{
    double edge[] = {0.0,
                     -0.0,
                     INFINITY,
                     -INFINITY,
                     NAN,
                     -NAN,
                     DBL_MIN,
                     -DBL_MIN,
                     DBL_TRUE_MIN,
                     4 * DBL_TRUE_MIN,
                     DBL_MIN / 3,
                     DBL_MAX,
                     -DBL_MAX,
                     FLT_MIN,
                     FLT_MAX,
                     FLT_TRUE_MIN,
                     1,
                     -1,
                     0.5,
                     0.25,
                     0.125,
                     0x1p-13, /* 0.0001220703125: ten digits ending in 5, a tie at 9 */
                     0x1p-14,
                     0x1p-27,
                     1.5,
                     2.5,
                     0.15,
                     0.35,
                     9007199254740992.0,
                     9007199254740993.0,
                     18014398509481988.0,
                     123456789,
                     999999999,
                     999999999.5,
                     9999999995,
                     99999999.95,
                     0.00009999999995,
                     0.0001,
                     0.0000999999999,
                     1e-5,
                     1e15,
                     1e16,
                     1e17,
                     1e22,
                     1e23,
                     1e-300};
    int bad = 0;
    for (size_t i = 0; i < sizeof edge / sizeof edge[0]; i++)
        for (int p = 1; p <= 17; p++) bad += !format_g_agrees(edge[i], p) || !format_g_agrees(-edge[i], p);
    /* Powers of ten and their neighbours, where the exponent estimate and the carry into a new
     * digit (9.99999999e4 -> 1e+05) are decided. */
    for (int k = -40; k <= 40; k++) {
        double t = pow(10, k), near[] = {t,
                                         nextafter(t, 0),
                                         nextafter(t, INFINITY),
                                         t * (1 - 5e-10),
                                         t * (1 + 5e-10),
                                         t * (1 - 4.9e-9),
                                         t * (1 - 5.1e-9)};
        for (int j = 0; j < 7; j++)
            for (int p = 1; p <= 17; p++) bad += !format_g_agrees(near[j], p);
    }
    /* Subnormals, walking down the exponents. */
    for (double x = DBL_MIN; x > 0; x /= 7) bad += !format_g_agrees(x, 9) + !format_g_agrees(-x, 17);
    CHECK(bad == 0);
}

TEST(format_g_matches_snprintf_on_two_million_random_values)
{
    lucent_rng r;
    lucent_rng_init(17, 0, &r);
    long bad = 0;
    for (long k = 0; k < 2000000 && bad < 10; k++) {
        uint64_t bits = lucent_rng_next(&r);
        double x;
        switch (k % 5) {
        case 0: memcpy(&x, &bits, sizeof x); break; /* any bit pattern: every exponent, nan, inf */
        case 1: x = ldexp((double)(bits >> 44), (int)(lucent_rng_next(&r) % 90) - 70); break; /* short: ties */
        case 2: x = (lucent_rng_uniform(&r) - 0.5) * pow(10, (int)(lucent_rng_next(&r) % 50) - 25); break;
        case 3: { /* floats */
            float f;
            uint32_t u = (uint32_t)bits;
            memcpy(&f, &u, sizeof f);
            x = f;
            break;
        }
        default: x = (lucent_rng_uniform(&r) - 0.5) * 2000; break; /* the curvature CSV's range */
        }
        int p = k % 2 ? 9 : 1 + (int)(lucent_rng_next(&r) % 17);
        bad += !format_g_agrees(x, p);
    }
    CHECK(bad == 0);
}

TEST(format_g_nine_digits_read_back_a_float_and_seventeen_a_double)
{
    lucent_rng r;
    lucent_rng_init(18, 0, &r);
    int bad = 0;
    for (int k = 0; k < 200000; k++) {
        uint64_t bits = lucent_rng_next(&r);
        float f;
        uint32_t u = (uint32_t)bits;
        memcpy(&f, &u, sizeof f);
        double d;
        memcpy(&d, &bits, sizeof d);
        char t[LUCENT_FORMAT_G_MAX];
        if (isfinite(f)) {
            lucent_format_g(t, f, 9);
            bad += strtof(t, NULL) != f; /* 9 digits identify a float (IEEE 754-2008, 5.12.2) */
        }
        if (isfinite(d)) {
            lucent_format_g(t, d, 17);
            bad += strtod(t, NULL) != d; /* 17 a double */
        }
    }
    CHECK(bad == 0);
}

TEST(format_u64_matches_snprintf)
{
    uint64_t v[] = {0,         1, 9, 10, 99, 100, 4294967295u, 4294967296u, 9999999999999999999u, 10000000000000000000u,
                    UINT64_MAX};
    lucent_rng r;
    lucent_rng_init(19, 0, &r);
    for (int k = 0; k < 10000 + 11; k++) {
        uint64_t x = k < 11 ? v[k] : lucent_rng_next(&r) >> (k % 64);
        char mine[24], libc[24];
        int n = lucent_format_u64(mine, x);
        mine[n] = 0;
        snprintf(libc, sizeof libc, "%llu", (unsigned long long)x);
        CHECK_MSG(strcmp(mine, libc) == 0, "%s vs %s", mine, libc);
    }
}

static int cmp_u64_ref(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* The radix sort against qsort on one key set. */
static int radix_agrees(const uint64_t *keys, size_t n)
{
    uint64_t *a = malloc((n + 1) * sizeof *a), *b = malloc((n + 1) * sizeof *b), *scratch = malloc((n + 1) * 8);
    memcpy(a, keys, n * sizeof *a), memcpy(b, keys, n * sizeof *b);
    lucent_radix_sort_u64(a, scratch, n);
    qsort(b, n, sizeof *b, cmp_u64_ref);
    int same = n == 0 || memcmp(a, b, n * sizeof *a) == 0;
    free(a), free(b), free(scratch);
    return same;
}

TEST(radix_sort_matches_qsort_on_random_and_adversarial_keys)
{
    enum { N = 100003 };
    uint64_t *k = malloc(N * sizeof *k);
    lucent_rng r;
    lucent_rng_init(20, 0, &r);
    size_t sizes[] = {0, 1, 2, 3, 2047, 2048, 2049, N};
    for (int kind = 0; kind < 10; kind++)
        for (size_t si = 0; si < sizeof sizes / sizeof sizes[0]; si++) {
            size_t n = sizes[si];
            for (size_t i = 0; i < n; i++) {
                uint64_t x = lucent_rng_next(&r);
                switch (kind) {
                case 0: k[i] = x; break;                                       /* random, all digits vary */
                case 1: k[i] = 42; break;                                      /* all equal: every pass skipped */
                case 2: k[i] = i; break;                                       /* sorted */
                case 3: k[i] = UINT64_MAX - i; break;                          /* reverse sorted */
                case 4: k[i] = (x % 3) << 61; break;                           /* only the top digit, 3 values */
                case 5: k[i] = (x & 0x7ff) << 22 | 5; break;                   /* one middle digit */
                case 6: k[i] = x % 7; break;                                   /* few distinct, many duplicates */
                case 7: k[i] = (i & 1) ? UINT64_MAX : 0; break;                /* the extremes alternating */
                case 8: k[i] = (x % 500000) * 500000 + x % 499999; break;      /* edge keys as the stats make them */
                default: k[i] = i % 2 ? x >> 1 : (uint64_t)1 << 63 | i; break; /* the top bit splits halves */
                }
            }
            CHECK_MSG(radix_agrees(k, n), "key kind %d, %zu keys", kind, n);
        }
    free(k);
}

/* The SIMD paths' names, parsing and choice (lucent/base.h, "SIMD paths"). */
TEST(isa_names_parse_and_choice)
{
    for (int i = 0; i < LUCENT_ISA_COUNT; i++) {
        lucent_isa back;
        CHECK_OK(lucent_isa_parse(lucent_isa_name((lucent_isa)i), &back));
        CHECK(back == (lucent_isa)i);
    }
    lucent_isa isa;
    CHECK_ERR(lucent_isa_parse("sse9", &isa), LUCENT_ERR_INVALID_ARGUMENT, "sse9", "scalar, avx2, avx512");
    CHECK(lucent_isa_name(LUCENT_ISA_COUNT) == NULL);
    CHECK(lucent_isa_supported(LUCENT_ISA_SCALAR) && lucent_isa_supported(LUCENT_ISA_AUTO));
    /* a CPU with AVX-512 has AVX2 */
    CHECK(!lucent_isa_supported(LUCENT_ISA_AVX512) || lucent_isa_supported(LUCENT_ISA_AVX2));
    lucent_isa was = lucent_isa_active();
    CHECK(was != LUCENT_ISA_AUTO);
    for (int i = LUCENT_ISA_SCALAR; i < LUCENT_ISA_COUNT; i++) {
        if (lucent_isa_supported((lucent_isa)i)) {
            CHECK_OK(lucent_isa_set((lucent_isa)i));
            CHECK(lucent_isa_active() == (lucent_isa)i);
        } else {
            CHECK_ERR(lucent_isa_set((lucent_isa)i), LUCENT_ERR_UNSUPPORTED, lucent_isa_name((lucent_isa)i), "lacks");
            CHECK(lucent_isa_active() != (lucent_isa)i);
        }
    }
    CHECK_ERR(lucent_isa_set(LUCENT_ISA_COUNT), LUCENT_ERR_INVALID_ARGUMENT, "no such path");
    CHECK_OK(lucent_isa_set(was));
    printf("  SIMD paths on this CPU:");
    for (int i = LUCENT_ISA_SCALAR; i < LUCENT_ISA_COUNT; i++)
        if (lucent_isa_supported((lucent_isa)i)) printf(" %s", lucent_isa_name((lucent_isa)i));
    printf("\n");
}

TEST_MAIN(TEST_ENTRY(error_message_and_context), TEST_ENTRY(error_is_per_thread), TEST_ENTRY(log_filters_by_level),
          TEST_ENTRY(progress_silent_by_default_and_draws_when_asked), TEST_ENTRY(parallel_for_visits_every_item_once),
          TEST_ENTRY(parallel_for_reports_lowest_failing_chunk), TEST_ENTRY(parallel_for_share_splits_the_same_chunks),
          TEST_ENTRY(dist_one_process_is_the_identity), TEST_ENTRY(parallel_for_nested_runs_without_deadlock),
          TEST_ENTRY(pool_size_from_environment), TEST_ENTRY(rng_matches_xoshiro256starstar_reference),
          TEST_ENTRY(rng_streams_are_uniform), TEST_ENTRY(rng_neighbouring_streams_are_independent),
          TEST_ENTRY(rng_same_seed_same_numbers_other_seed_differs),
          TEST_ENTRY(rng_per_chunk_streams_independent_of_thread_count), TEST_ENTRY(isa_names_parse_and_choice),
          TEST_ENTRY(atomic_write_replaces_only_when_complete), TEST_ENTRY(atomic_write_errors_name_the_path),
          TEST_ENTRY(atomic_write_into_read_only_directory),
          TEST_ENTRY(mkdir_p_creates_parents_and_names_what_blocks_it), TEST_ENTRY(json_errors_carry_file_and_path),
          TEST_ENTRY(json_rejects_broken_text_nan_and_infinity),
          TEST_ENTRY(json_numbers_accept_scalar_when_allowed_and_write_round_trip),
          TEST_ENTRY(clocks_are_monotonic_and_agree_in_units),
          TEST_ENTRY(vectors_follow_their_definitions_and_zero_normalises_to_zero),
          TEST_ENTRY(mat4_multiplies_column_major), TEST_ENTRY(format_g_matches_snprintf_on_edge_values),
          TEST_ENTRY(format_g_matches_snprintf_on_two_million_random_values),
          TEST_ENTRY(format_g_nine_digits_read_back_a_float_and_seventeen_a_double),
          TEST_ENTRY(format_u64_matches_snprintf), TEST_ENTRY(radix_sort_matches_qsort_on_random_and_adversarial_keys))
