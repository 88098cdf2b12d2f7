/* The output set of a command (lucent/output.h): its completed temporaries wait for lucent_outputs_end,
 * which renames all of them or none; the targets it has claimed and the files it has read, so that no two
 * outputs name one file and no output replaces an input; the signal handler that removes every temporary
 * (a table of fixed slots it can read without locks or allocation). */
#include <errno.h>
#include <limits.h>
#include <pthread.h>
#include <signal.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/file_internal.h"
#include "lucent/output.h"

/* ---- the signal handler's table of temporaries ---- */

enum { SLOT_FREE, SLOT_BUSY, SLOT_LIVE, SLOTS = 256 };

static struct {
    atomic_int state;
    char path[PATH_MAX];
} g_slots[SLOTS];

int outputs_track(const char *tmp)
{
    if (strlen(tmp) >= PATH_MAX) return -1; /* open fails on such a name anyway */
    for (int i = 0; i < SLOTS; i++) {
        int expected = SLOT_FREE;
        if (!atomic_compare_exchange_strong(&g_slots[i].state, &expected, SLOT_BUSY)) continue;
        memcpy(g_slots[i].path, tmp, strlen(tmp) + 1);
        atomic_store(&g_slots[i].state, SLOT_LIVE);
        return i;
    }
    return -1;
}

void outputs_untrack(int slot)
{
    if (slot >= 0 && slot < SLOTS) atomic_store(&g_slots[slot].state, SLOT_FREE);
}

/* Async-signal-safe: unlink only. */
static void remove_temporaries(void)
{
    for (int i = 0; i < SLOTS; i++)
        if (atomic_load(&g_slots[i].state) == SLOT_LIVE) unlink(g_slots[i].path);
}

/* ---- signals ---- */

/* IDLE: a signal removes the temporaries and ends the process; RENAMING: lucent_outputs_end is committing
 * the set, and a signal waits for it (held) so that the set lands whole; DYING: a handler is ending the
 * process, and no rename may start. */
enum { PHASE_IDLE, PHASE_RENAMING, PHASE_DYING };
static atomic_int g_phase;
static volatile sig_atomic_t g_held;

static void die_of(int sig)
{
    remove_temporaries();
    signal(sig, SIG_DFL);
    raise(sig);
}

static void on_signal(int sig)
{
    int phase = PHASE_IDLE;
    if (!atomic_compare_exchange_strong(&g_phase, &phase, PHASE_DYING) && phase == PHASE_RENAMING) {
        g_held = sig;
        return;
    }
    die_of(sig);
}

void lucent_outputs_handle_signals(void)
{
    static const int sigs[] = {SIGINT, SIGTERM, SIGHUP};
    for (size_t i = 0; i < sizeof sigs / sizeof sigs[0]; i++) {
        struct sigaction sa = {.sa_handler = on_signal};
        sigfillset(&sa.sa_mask);
        sigaction(sigs[i], &sa, NULL);
    }
}

/* ---- the set ---- */

typedef struct file_id {
    dev_t dev;
    ino_t ino;
} file_id;

enum { MAX_INPUTS = 1024 };

static struct {
    bool open;
    lucent_atomic_file *done; /* completed temporaries, newest first */
    char **claims;            /* canonical target paths */
    size_t claim_count, claim_cap;
    file_id inputs[MAX_INPUTS]; /* beyond MAX_INPUTS, inputs are not remembered */
    int input_count;
    file_id planned[MAX_INPUTS]; /* existing files checked as outputs (lucent_output_check) */
    int planned_count;
} g_set;

/* Guards g_set: outputs may be opened, and inputs read, on any thread. */
static pthread_mutex_t g_lock = PTHREAD_MUTEX_INITIALIZER;

void lucent_outputs_begin(void)
{
    pthread_mutex_lock(&g_lock);
    g_set.open = true;
    g_set.input_count = g_set.planned_count = 0;
    pthread_mutex_unlock(&g_lock);
}

lucent_status outputs_note_input(const char *path, const struct stat *st)
{
    pthread_mutex_lock(&g_lock);
    bool planned = false;
    for (int i = 0; g_set.open && i < g_set.planned_count; i++)
        planned |= g_set.planned[i].dev == st->st_dev && g_set.planned[i].ino == st->st_ino;
    if (g_set.open && !planned && g_set.input_count < MAX_INPUTS)
        g_set.inputs[g_set.input_count++] = (file_id){st->st_dev, st->st_ino};
    pthread_mutex_unlock(&g_lock);
    if (planned)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: this file is read by the command and named as one of its outputs: refusing to "
                            "overwrite an input",
                            path);
    return LUCENT_OK;
}

void outputs_plan(const struct stat *st)
{
    pthread_mutex_lock(&g_lock);
    if (g_set.open && g_set.planned_count < MAX_INPUTS)
        g_set.planned[g_set.planned_count++] = (file_id){st->st_dev, st->st_ino};
    pthread_mutex_unlock(&g_lock);
}

static bool is_input(const char *path)
{
    struct stat st; /* lstat: renaming onto a symbolic link replaces the link, not the file it names */
    if (lstat(path, &st) != 0 || !S_ISREG(st.st_mode)) return false;
    for (int i = 0; i < g_set.input_count; i++)
        if (g_set.inputs[i].dev == st.st_dev && g_set.inputs[i].ino == st.st_ino) return true;
    return false;
}

/* The folder resolved (realpath), then the name: two spellings of one target give one string. */
static char *canonical(const char *path)
{
    const char *slash = strrchr(path, '/');
    const char *base = slash ? slash + 1 : path;
    char *dir = slash ? strndup(path, (size_t)(slash == path ? 1 : slash - path)) : strdup(".");
    char *real = dir ? realpath(dir, NULL) : NULL;
    const char *head = real ? real : dir ? dir : "";
    size_t n = strlen(head) + strlen(base) + 2;
    char *c = malloc(n);
    if (c) snprintf(c, n, "%s/%s", head, base);
    free(real);
    free(dir);
    return c;
}

static size_t find_claim(const char *canon)
{
    for (size_t i = 0; i < g_set.claim_count; i++)
        if (strcmp(g_set.claims[i], canon) == 0) return i;
    return (size_t)-1;
}

static lucent_status claim(lucent_atomic_file *af)
{
    if (!g_set.open) return LUCENT_OK;
    if (is_input(af->path))
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT,
                            "%s: the output names a file this command reads: refusing to overwrite an input", af->path);
    char *canon = canonical(af->path);
    if (!canon) return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", af->path);
    if (find_claim(canon) != (size_t)-1) {
        free(canon);
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "%s: two outputs of this command name the same file",
                            af->path);
    }
    if (g_set.claim_count == g_set.claim_cap) {
        size_t cap = g_set.claim_cap ? 2 * g_set.claim_cap : 16;
        char **bigger = realloc(g_set.claims, cap * sizeof *bigger);
        if (!bigger) {
            free(canon);
            return lucent_error(LUCENT_ERR_OUT_OF_MEMORY, "%s: out of memory", af->path);
        }
        g_set.claims = bigger, g_set.claim_cap = cap;
    }
    g_set.claims[g_set.claim_count++] = canon;
    af->claimed = true;
    return LUCENT_OK;
}

lucent_status outputs_claim(lucent_atomic_file *af)
{
    pthread_mutex_lock(&g_lock);
    lucent_status s = claim(af);
    pthread_mutex_unlock(&g_lock);
    return s;
}

void outputs_release(lucent_atomic_file *af)
{
    if (!af->claimed) return;
    af->claimed = false;
    char *canon = canonical(af->path);
    pthread_mutex_lock(&g_lock);
    size_t i = canon ? find_claim(canon) : (size_t)-1;
    if (i != (size_t)-1) {
        free(g_set.claims[i]);
        g_set.claims[i] = g_set.claims[--g_set.claim_count];
    }
    pthread_mutex_unlock(&g_lock);
    free(canon);
}

bool outputs_defer(lucent_atomic_file *af)
{
    pthread_mutex_lock(&g_lock);
    bool open = g_set.open;
    if (open) af->next = g_set.done, g_set.done = af;
    pthread_mutex_unlock(&g_lock);
    return open;
}

static void free_file(lucent_atomic_file *af)
{
    if (af->fp) fclose(af->fp); /* a through output's bytes */
    outputs_untrack(af->slot);
    free(af->path);
    free(af->tmp);
    free(af);
}

/* Renames the completed temporaries, oldest first, with signals held until the last is done. A rename
 * writes no data, so once every temporary is complete (synced) the renames do not fail for want of space;
 * should one fail, the others are still renamed and the error names the one that did not land. */
static lucent_status rename_all(lucent_atomic_file *list)
{
    int phase = PHASE_IDLE;
    if (!atomic_compare_exchange_strong(&g_phase, &phase, PHASE_RENAMING)) {
        for (;;) pause(); /* a signal handler is ending the process and removing the temporaries */
    }
    lucent_status s = LUCENT_OK;
    for (lucent_atomic_file *af = list; af; af = af->next)
        if (af->tmp && rename(af->tmp, af->path) != 0) {
            int e = errno;
            unlink(af->tmp);
            if (s == LUCENT_OK)
                s = lucent_error(LUCENT_ERR_IO, "%s: cannot rename into place: %s", af->path, strerror(e));
        }
    for (lucent_atomic_file *af = list; af; af = af->next) outputs_untrack(af->slot), af->slot = -1;
    atomic_store(&g_phase, PHASE_IDLE);
    if (g_held) die_of(g_held);
    return s;
}

lucent_status lucent_outputs_end(bool commit)
{
    pthread_mutex_lock(&g_lock);
    lucent_atomic_file *list = NULL; /* oldest first */
    while (g_set.done) {
        lucent_atomic_file *af = g_set.done;
        g_set.done = af->next;
        af->next = list;
        list = af;
    }
    lucent_status s = LUCENT_OK;
    /* Devices and FIFOs first (a reader that left fails the command before any file is replaced), then the
     * renames. */
    for (lucent_atomic_file *af = list; commit && s == LUCENT_OK && af; af = af->next)
        if (af->through) s = base_write_through(af);
    if (commit && s == LUCENT_OK)
        s = rename_all(list);
    else
        for (lucent_atomic_file *af = list; af; af = af->next)
            if (af->tmp) unlink(af->tmp);
    while (list) {
        lucent_atomic_file *next = list->next;
        free_file(list);
        list = next;
    }
    for (size_t i = 0; i < g_set.claim_count; i++) free(g_set.claims[i]);
    free(g_set.claims);
    g_set.claims = NULL, g_set.claim_count = g_set.claim_cap = 0;
    g_set.open = false;
    g_set.input_count = g_set.planned_count = 0;
    pthread_mutex_unlock(&g_lock);
    return s;
}
