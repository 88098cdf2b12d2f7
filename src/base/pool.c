/* A pthread pool with a parallel-for over fixed chunks. The caller works as thread 0;
 * chunks are claimed in increasing order from an atomic counter, so which chunks exist
 * never depends on the number of threads, only who runs them does. */
#include <errno.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/dist_internal.h"
#include "lucent/dist.h"

enum { POOL_MAX_THREADS = LUCENT_POOL_MAX_THREADS };

typedef struct pool_job {
    uint64_t count, chunk_size, chunks;
    uint64_t offset, stride, local; /* the chunks offset + j stride, j < local, run here */
    lucent_chunk_fn fn;
    void *ctx;
    _Atomic uint64_t next;
    _Atomic bool failed;
    pthread_mutex_t error_lock;
    uint64_t error_chunk; /* lowest failing chunk so far */
    lucent_status error_status;
    char error_message[2048];
} pool_job;

struct lucent_pool {
    int threads;
    pthread_t *workers;
    pthread_mutex_t lock, call_lock;
    pthread_cond_t work_cv, done_cv;
    uint64_t generation;
    pool_job *job;
    int active;
    bool quit;
};

static _Thread_local bool t_in_pool_work;

int lucent_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (int)n;
}

static int threads_from_environment(void)
{
    const char *env = getenv("LUCENT_THREADS");
    if (env && *env) {
        char *end;
        errno = 0;
        long n = strtol(env, &end, 10);
        if (*end == '\0' && !errno && n >= 1 && n <= POOL_MAX_THREADS) return (int)n;
        lucent_log(LUCENT_LOG_WARN, "LUCENT_THREADS='%.32s' is not a whole number from 1 to %d: using all %d cores",
                   env, POOL_MAX_THREADS, lucent_cpu_count());
    }
    return lucent_cpu_count();
}

static void record_failure(pool_job *job, uint64_t chunk, lucent_status status)
{
    pthread_mutex_lock(&job->error_lock);
    if (!atomic_load(&job->failed) || chunk < job->error_chunk) {
        job->error_chunk = chunk;
        job->error_status = status;
        snprintf(job->error_message, sizeof job->error_message, "%s", lucent_last_error());
        atomic_store(&job->failed, true);
    }
    pthread_mutex_unlock(&job->error_lock);
}

static void run_chunks(pool_job *job, int thread)
{
    bool was_inside = t_in_pool_work;
    t_in_pool_work = true;
    while (!atomic_load(&job->failed)) {
        uint64_t j = atomic_fetch_add(&job->next, 1);
        if (j >= job->local) break;
        uint64_t c = job->offset + j * job->stride;
        uint64_t begin = c * job->chunk_size;
        uint64_t end = begin + job->chunk_size < job->count ? begin + job->chunk_size : job->count;
        lucent_status s = job->fn(job->ctx, c, begin, end, thread);
        if (s != LUCENT_OK) record_failure(job, c, s);
    }
    t_in_pool_work = was_inside;
}

typedef struct worker_arg {
    lucent_pool *pool;
    int index;
} worker_arg;

static void *worker_main(void *arg)
{
    worker_arg wa = *(worker_arg *)arg;
    free(arg);
    lucent_pool *pool = wa.pool;
    uint64_t seen = 0;
    for (;;) {
        pthread_mutex_lock(&pool->lock);
        while (!pool->quit && pool->generation == seen) pthread_cond_wait(&pool->work_cv, &pool->lock);
        if (pool->quit) {
            pthread_mutex_unlock(&pool->lock);
            return NULL;
        }
        seen = pool->generation;
        pool_job *job = pool->job;
        pthread_mutex_unlock(&pool->lock);
        run_chunks(job, wa.index);
        pthread_mutex_lock(&pool->lock);
        if (--pool->active == 0) pthread_cond_signal(&pool->done_cv);
        pthread_mutex_unlock(&pool->lock);
    }
}

lucent_pool *lucent_pool_create(int threads)
{
    if (threads <= 0) threads = threads_from_environment();
    if (threads > POOL_MAX_THREADS) {
        lucent_log(LUCENT_LOG_WARN, "a pool of %d threads asked: at most %d, using %d", threads, POOL_MAX_THREADS,
                   POOL_MAX_THREADS);
        threads = POOL_MAX_THREADS;
    }
    lucent_pool *pool = calloc(1, sizeof *pool);
    if (!pool) return NULL;
    pool->threads = 1;
    pool->workers = calloc((size_t)threads, sizeof *pool->workers);
    pthread_mutex_init(&pool->lock, NULL);
    pthread_mutex_init(&pool->call_lock, NULL);
    pthread_cond_init(&pool->work_cv, NULL);
    pthread_cond_init(&pool->done_cv, NULL);
    for (int i = 1; pool->workers && i < threads; i++) {
        worker_arg *wa = malloc(sizeof *wa);
        if (!wa) break;
        *wa = (worker_arg){pool, i};
        if (pthread_create(&pool->workers[i], NULL, worker_main, wa) != 0) {
            free(wa);
            break; /* fewer threads than asked: still correct, only slower */
        }
        pool->threads++;
    }
    return pool;
}

void lucent_pool_destroy(lucent_pool *pool)
{
    if (!pool) return;
    pthread_mutex_lock(&pool->lock);
    pool->quit = true;
    pthread_cond_broadcast(&pool->work_cv);
    pthread_mutex_unlock(&pool->lock);
    for (int i = 1; i < pool->threads; i++) pthread_join(pool->workers[i], NULL);
    pthread_mutex_destroy(&pool->lock);
    pthread_mutex_destroy(&pool->call_lock);
    pthread_cond_destroy(&pool->work_cv);
    pthread_cond_destroy(&pool->done_cv);
    free(pool->workers);
    free(pool);
}

int lucent_pool_threads(const lucent_pool *pool) { return pool ? pool->threads : 1; }

/* Hands the job to the workers, works on it too, and waits for them. */
static void run_on_pool(lucent_pool *pool, pool_job *job)
{
    pthread_mutex_lock(&pool->call_lock);
    pthread_mutex_lock(&pool->lock);
    pool->job = job;
    pool->active = pool->threads - 1;
    pool->generation++;
    pthread_cond_broadcast(&pool->work_cv);
    pthread_mutex_unlock(&pool->lock);
    run_chunks(job, 0);
    pthread_mutex_lock(&pool->lock);
    while (pool->active > 0) pthread_cond_wait(&pool->done_cv, &pool->lock);
    pool->job = NULL;
    pthread_mutex_unlock(&pool->lock);
    pthread_mutex_unlock(&pool->call_lock);
}

lucent_status lucent_parallel_for_share(lucent_pool *pool, uint64_t count, uint64_t chunk_size, lucent_chunk_fn fn,
                                        void *ctx, lucent_share share)
{
    if (!fn || chunk_size == 0)
        return lucent_error(LUCENT_ERR_INVALID_ARGUMENT, "parallel_for: no function or zero chunk size");
    if (count == 0) return LUCENT_OK;
    pool_job job = {.count = count, .chunk_size = chunk_size, .fn = fn, .ctx = ctx};
    job.chunks = count / chunk_size + (count % chunk_size != 0);
    job.offset = share.offset, job.stride = share.stride;
    job.local = share.stride && share.offset < job.chunks ? (job.chunks - share.offset - 1) / share.stride + 1 : 0;
    if (job.local == 0) return LUCENT_OK;
    pthread_mutex_init(&job.error_lock, NULL);
    /* Serial when there is nothing to share, or when called from inside a pool's work
     * (nested loops run on the calling worker rather than deadlocking). */
    if (!pool || pool->threads == 1 || job.local == 1 || t_in_pool_work)
        run_chunks(&job, 0);
    else
        run_on_pool(pool, &job);
    pthread_mutex_destroy(&job.error_lock);
    if (!atomic_load(&job.failed)) return LUCENT_OK;
    dist_note_failed_chunk(job.error_chunk);
    return lucent_error(job.error_status, "%s", job.error_message);
}

lucent_status lucent_parallel_for(lucent_pool *pool, uint64_t count, uint64_t chunk_size, lucent_chunk_fn fn, void *ctx)
{
    return lucent_parallel_for_share(pool, count, chunk_size, fn, ctx, (lucent_share){0, 1});
}
