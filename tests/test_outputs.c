/* The output set and the signal cleanup (lucent/output.h; issue 17 items 5 and 6): a command's outputs land
 * together or not at all, no two outputs name one file, no output replaces an input, and SIGINT/SIGTERM
 * leave no temporary and the previous outputs as they were. */
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "lucent/base.h"
#include "lucent/output.h"
#include "test.h"

/* The directory holds exactly the files named (space-separated, in ls order): no temporary beside them. */
static bool dir_holds(const char *dir, const char *names)
{
    char cmd[1400];
    snprintf(cmd, sizeof cmd, "test \"$(ls -A '%s' | tr '\\n' ' ')\" = '%s '", dir, names);
    return system(cmd) == 0;
}

/* The file holds exactly text. */
static bool holds(const char *path, const char *text)
{
    char *got = NULL;
    size_t size = 0;
    bool ok = lucent_read_file(path, &got, &size) == LUCENT_OK && size == strlen(text) && !memcmp(got, text, size);
    free(got);
    return ok;
}

static const char *make_dir(const char *name, char *dir, size_t size)
{
    snprintf(dir, size, "%s", test_path(name));
    mkdir(dir, 0755);
    return dir;
}

TEST(set_lands_all_outputs_or_none)
{
    char dir[1024], a[1100], b[1100];
    make_dir("set", dir, sizeof dir);
    snprintf(a, sizeof a, "%s/a.txt", dir);
    snprintf(b, sizeof b, "%s/b.txt", dir);
    CHECK_OK(lucent_write_file(a, "old a", 5));
    CHECK_OK(lucent_write_file(b, "old b", 5));

    lucent_outputs_begin();
    CHECK_OK(lucent_write_file(a, "new a", 5));
    CHECK(holds(a, "old a")); /* complete, but waiting for the set */
    CHECK_OK(lucent_write_file(b, "new b", 5));
    CHECK_OK(lucent_outputs_end(true));
    CHECK(holds(a, "new a") && holds(b, "new b"));
    CHECK(dir_holds(dir, "a.txt b.txt"));

    lucent_outputs_begin(); /* a command that fails after writing its first output */
    CHECK_OK(lucent_write_file(a, "bad a", 5));
    lucent_outputs_end(false);
    CHECK(holds(a, "new a") && holds(b, "new b"));
    CHECK(dir_holds(dir, "a.txt b.txt"));
}

TEST(set_refuses_one_file_twice_and_inputs)
{
    char dir[1024], out[1100], again[1100], in[1100];
    make_dir("refuse", dir, sizeof dir);
    snprintf(out, sizeof out, "%s/out.txt", dir);
    snprintf(again, sizeof again, "%s/./out.txt", dir); /* another spelling of the same file */
    snprintf(in, sizeof in, "%s/in.txt", dir);
    CHECK_OK(lucent_write_file(in, "input", 5));

    lucent_outputs_begin();
    char *text = NULL;
    CHECK_OK(lucent_read_file(in, &text, NULL));
    free(text);
    CHECK_OK(lucent_write_file(out, "first", 5));
    CHECK_ERR(lucent_write_file(again, "second", 6), LUCENT_ERR_INVALID_ARGUMENT, again, "same file");
    CHECK_ERR(lucent_write_file(in, "over", 4), LUCENT_ERR_INVALID_ARGUMENT, in, "refusing to overwrite an input");
    lucent_atomic_file *af;
    FILE *fp;
    char other[1100];
    snprintf(other, sizeof other, "%s/other.txt", dir);
    CHECK_OK(lucent_atomic_open(other, &af, &fp));
    lucent_atomic_abort(af); /* an abandoned output frees its name */
    CHECK_OK(lucent_write_file(other, "other", 5));
    CHECK_OK(lucent_outputs_end(true));
    CHECK(holds(in, "input") && holds(out, "first") && holds(other, "other"));
    CHECK(dir_holds(dir, "in.txt other.txt out.txt"));

    CHECK_OK(lucent_write_file(in, "over", 4)); /* outside a set: no such rule */
    CHECK(holds(in, "over"));
}

/* The disk cache's entries are not outputs of the command: they land at once, inside a set too. */
TEST(cache_entries_land_at_once)
{
    char dir[1024];
    make_dir("cache", dir, sizeof dir);
    lucent_cache *cache;
    CHECK_OK(lucent_cache_create(dir, &cache));
    lucent_outputs_begin();
    double v = 0.25, got = 0;
    lucent_cache_put(cache, "t", "key", &(lucent_cache_field){"v", &v, 1}, 1);
    CHECK(lucent_cache_get(cache, "t", "key", "v", 1, &got) && got == 0.25);
    lucent_outputs_end(false);
    CHECK(lucent_cache_get(cache, "t", "key", "v", 1, &got) && got == 0.25);
    lucent_cache_destroy(cache);
}

/* A child begins a set, completes one output, writes 4 MiB of a second without finishing it, and sends itself
 * sig: it must die of sig, leave both targets as they were and no temporary. */
static void interrupted_writer(int sig, const char *a, const char *b)
{
    lucent_outputs_handle_signals();
    lucent_outputs_begin();
    if (lucent_write_file(a, "new a", 5) != LUCENT_OK) _exit(10);
    lucent_atomic_file *af;
    FILE *fp;
    if (lucent_atomic_open(b, &af, &fp) != LUCENT_OK) _exit(11);
    static char block[1 << 16];
    memset(block, 'x', sizeof block);
    for (int i = 0; i < 64; i++) fwrite(block, 1, sizeof block, fp);
    fflush(fp);
    raise(sig);
    _exit(12); /* not reached: the handler ends the process by the signal */
}

TEST(signal_leaves_no_temporary_and_the_old_outputs)
{
    static const int sigs[] = {SIGTERM, SIGINT};
    for (int k = 0; k < 2; k++) {
        char dir[1024], a[1100], b[1100];
        make_dir(k ? "sigint" : "sigterm", dir, sizeof dir);
        snprintf(a, sizeof a, "%s/a.txt", dir);
        snprintf(b, sizeof b, "%s/b.bin", dir);
        CHECK_OK(lucent_write_file(a, "old a", 5));
        CHECK_OK(lucent_write_file(b, "old b", 5));
        fflush(NULL);
        pid_t pid = fork();
        if (pid == 0) interrupted_writer(sigs[k], a, b);
        int status = 0;
        CHECK(pid > 0 && waitpid(pid, &status, 0) == pid);
        CHECK(WIFSIGNALED(status) && WTERMSIG(status) == sigs[k]);
        CHECK(holds(a, "old a") && holds(b, "old b"));
        CHECK(dir_holds(dir, "a.txt b.bin"));
    }
}

TEST_MAIN(TEST_ENTRY(set_lands_all_outputs_or_none), TEST_ENTRY(set_refuses_one_file_twice_and_inputs),
          TEST_ENTRY(cache_entries_land_at_once), TEST_ENTRY(signal_leaves_no_temporary_and_the_old_outputs))
