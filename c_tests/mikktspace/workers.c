/*
 * How many worker threads each call of libtbasis_mikktspace starts, against what
 * include/tbasis_mikktspace.h says of tbasis_mikktspace_set_threads: a call reads the count once,
 * when it starts, and calls running at the same time each use up to that many workers
 * (tests/mikktspace_dropin.rs builds it against the shared library and runs it).
 *
 * This program defines pthread_create and pthread_join, which the shared library's calls reach
 * before the C library's (an executable's definitions come first), and hands both on to the C
 * library's own (dlsym(RTLD_NEXT)). While a call runs, its calling thread points `current` at
 * the call's record, and every thread the call starts inherits it, so that each thread started
 * is counted for the call that started it, whichever other calls run at the same time. What is
 * counted follows from the order of the starts and joins on the calling thread, not from timing:
 * - `started`: the threads the call started;
 * - `most`: the most of them started and not yet joined at once, so the most workers the call
 *   had at once are `most` + 1 (the calling thread works too);
 * - `left`: those never joined before the call returned;
 * - `from_workers`: those started from a worker rather than from the calling thread.
 *
 * Each call is made on a grid of 256 x 160 quads (81,920 triangles, where the library starts one
 * worker per 16,384), and its m_setTSpace arguments are kept, to compare bit for bit:
 * - alone, with 1, 2 and 4 threads: no thread with 1, and with n, at most n - 1 at once, exactly
 *   n - 1 in some step; the same set calls as with 1;
 * - a count changed from inside a call (its m_getNumFaces) applies to the calls that start after,
 *   not to that one, from 4 to 1 and from 1 to 4;
 * - two calls at once on two other threads (each held in m_getNumFaces until both have started,
 *   and in its first m_setTSpace until both have computed): one started with 4 that sets 2
 *   before the other starts, which then uses 2 (the count is the process's, not the thread's),
 *   the first keeping 4; then both with 4, each starting what it starts alone.
 * Every callback runs on its call's calling thread.
 *
 * Prints "N passed, M failed" last and exits 0 when nothing failed.
 */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../counted.h"
#include "tbasis_mikktspace.h"

enum { COLS = 256, ROWS = 160, FACES = COLS * ROWS, SLOTS = 4 * FACES, VALUES = 9, MAX_LIVE = 256 };

/* The threads of one call. */
typedef struct call_threads {
    pthread_mutex_t lock;
    long started, most, from_workers;
    long live_count;           /* started and not yet joined */
    pthread_t live[MAX_LIVE];  /* which */
    long overflow;             /* started while `live` was full: not followed */
} call_threads;

/* The call the running thread works for, NULL outside calls; whether it is one of its workers. */
static __thread call_threads *current;
static __thread int is_worker;

typedef int (*create_function)(pthread_t *, const pthread_attr_t *, void *(*)(void *), void *);
typedef int (*join_function)(pthread_t, void **);

/* A worker's start routine, its argument and its call. */
typedef struct start {
    void *(*routine)(void *);
    void *argument;
    call_threads *call;
} start;

static void *run_worker(void *argument)
{
    start s = *(start *)argument;
    free(argument);
    current = s.call;
    is_worker = 1;
    return s.routine(s.argument);
}

int pthread_create(pthread_t *thread, const pthread_attr_t *attr, void *(*routine)(void *), void *argument)
{
    create_function create = (create_function)dlsym(RTLD_NEXT, "pthread_create");
    call_threads *call = current;
    start *s;
    int result;
    if (create == NULL) {
        printf("pthread_create not found\n");
        exit(2);
    }
    if (call == NULL)
        return create(thread, attr, routine, argument);
    s = (start *)malloc(sizeof *s);
    if (s == NULL) {
        printf("out of memory\n");
        exit(2);
    }
    s->routine = routine;
    s->argument = argument;
    s->call = call;
    result = create(thread, attr, run_worker, s);
    if (result != 0) {
        free(s);
        return result;
    }
    pthread_mutex_lock(&call->lock);
    call->started++;
    call->from_workers += is_worker;
    if (call->live_count < MAX_LIVE)
        call->live[call->live_count++] = *thread;
    else
        call->overflow++;
    if (call->live_count > call->most)
        call->most = call->live_count;
    pthread_mutex_unlock(&call->lock);
    return 0;
}

int pthread_join(pthread_t thread, void **result)
{
    join_function join = (join_function)dlsym(RTLD_NEXT, "pthread_join");
    call_threads *call = current;
    long k;
    int status;
    if (join == NULL) {
        printf("pthread_join not found\n");
        exit(2);
    }
    status = join(thread, result);
    if (call != NULL && status == 0) {
        pthread_mutex_lock(&call->lock);
        for (k = 0; k < call->live_count; k++)
            if (pthread_equal(call->live[k], thread)) {
                call->live[k] = call->live[--call->live_count];
                break;
            }
        pthread_mutex_unlock(&call->lock);
    }
    return status;
}

/* One call: its setup, what its callbacks saw, what it returned. */
typedef struct run {
    int threads_at_start;        /* the count set before the call */
    int threads_in_callback;     /* set from m_getNumFaces when not 0 */
    pthread_barrier_t *started;  /* waited at in m_getNumFaces, when not NULL */
    pthread_barrier_t *changed;  /* waited at in m_getNumFaces after the count is set, when not NULL */
    pthread_barrier_t *computed; /* waited at in the first m_setTSpace, when not NULL */
    pthread_barrier_t *before;   /* waited at before the call starts, when not NULL */
    pthread_t thread;
    long wrong_thread;
    long set_calls;
    float *values; /* VALUES per face vertex, 4 * face + vert */
    call_threads threads;
    tbool result;
} run;

static run *run_of(const SMikkTSpaceContext *context)
{
    return (run *)context->m_pUserData;
}

static void on_thread(const SMikkTSpaceContext *context)
{
    if (!pthread_equal(pthread_self(), run_of(context)->thread))
        run_of(context)->wrong_thread++;
}

static int get_num_faces(const SMikkTSpaceContext *context)
{
    run *r = run_of(context);
    on_thread(context);
    if (r->threads_in_callback != 0)
        tbasis_mikktspace_set_threads(r->threads_in_callback);
    if (r->changed != NULL)
        pthread_barrier_wait(r->changed);
    if (r->started != NULL)
        pthread_barrier_wait(r->started);
    return FACES;
}

static int get_num_vertices_of_face(const SMikkTSpaceContext *context, const int iFace)
{
    (void)iFace;
    on_thread(context);
    return 4;
}

static void grid_vertex(int face, int vert, int *i, int *j)
{
    static const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
    *i = face % COLS + di[vert & 3];
    *j = face / COLS + dj[vert & 3];
}

static void get_position(const SMikkTSpaceContext *context, float fvPosOut[], const int iFace, const int iVert)
{
    int i, j;
    on_thread(context);
    grid_vertex(iFace, iVert, &i, &j);
    fvPosOut[0] = (float)i;
    fvPosOut[1] = (float)j;
    fvPosOut[2] = 0.05f * (float)((i * 7 + j * 3) % 5);
}

static void get_normal(const SMikkTSpaceContext *context, float fvNormOut[], const int iFace, const int iVert)
{
    (void)iFace;
    (void)iVert;
    on_thread(context);
    fvNormOut[0] = 0.0f;
    fvNormOut[1] = 0.0f;
    fvNormOut[2] = 1.0f;
}

static void get_tex_coord(const SMikkTSpaceContext *context, float fvTexcOut[], const int iFace, const int iVert)
{
    int i, j;
    on_thread(context);
    grid_vertex(iFace, iVert, &i, &j);
    /* A mirror seam down the middle column. */
    fvTexcOut[0] = 0.1f * (float)abs(i - COLS / 2) + 0.01f * (float)((i * 5 + j) % 3);
    fvTexcOut[1] = 0.1f * (float)j;
}

static void set_tspace(const SMikkTSpaceContext *context, const float fvTangent[], const float fvBiTangent[],
                       const float fMagS, const float fMagT, const tbool bIsOrientationPreserving, const int iFace,
                       const int iVert)
{
    run *r = run_of(context);
    float *values;
    on_thread(context);
    if (r->set_calls++ == 0 && r->computed != NULL)
        pthread_barrier_wait(r->computed);
    if (iFace < 0 || iFace >= FACES || iVert < 0 || iVert > 3)
        return;
    values = r->values + (size_t)VALUES * (size_t)(4 * iFace + iVert);
    memcpy(values, fvTangent, 3 * sizeof(float));
    memcpy(values + 3, fvBiTangent, 3 * sizeof(float));
    values[6] = fMagS;
    values[7] = fMagT;
    values[8] = (float)bIsOrientationPreserving;
}

static void init_run(run *r, int threads_at_start)
{
    memset(r, 0, sizeof *r);
    r->threads_at_start = threads_at_start;
    pthread_mutex_init(&r->threads.lock, NULL);
    r->values = (float *)calloc((size_t)SLOTS * VALUES, sizeof(float));
    if (r->values == NULL) {
        printf("out of memory\n");
        exit(2);
    }
}

/* Makes the call of `r` on the running thread, the count set first unless 0. */
static void *call(void *argument)
{
    run *r = (run *)argument;
    SMikkTSpaceInterface interface = {get_num_faces, get_num_vertices_of_face, get_position, get_normal,
                                      get_tex_coord, NULL,                     set_tspace};
    SMikkTSpaceContext context;
    context.m_pInterface = &interface;
    context.m_pUserData = r;
    r->thread = pthread_self();
    if (r->before != NULL)
        pthread_barrier_wait(r->before);
    if (r->threads_at_start != 0)
        tbasis_mikktspace_set_threads(r->threads_at_start);
    current = &r->threads;
    r->result = genTangSpaceDefault(&context);
    current = NULL;
    return NULL;
}

/* What every call must show: 1 after a set call per face vertex, all on its calling thread; every
   thread it started joined before it returned, none started from a worker; at most `workers`
   workers at once, the calling thread included; the same set calls as `reference`, if given. */
static void check_call(const char *what, const run *r, long workers, const run *reference)
{
    check(r->result == 1 && r->set_calls == SLOTS, "%s: returned %d after %ld set calls", what, r->result,
          r->set_calls);
    check(r->wrong_thread == 0, "%s: %ld callbacks on another thread", what, r->wrong_thread);
    check(r->threads.live_count == 0 && r->threads.overflow == 0, "%s: %ld threads not joined before it returned",
          what, r->threads.live_count + r->threads.overflow);
    check(r->threads.from_workers == 0, "%s: %ld threads started from a worker", what, r->threads.from_workers);
    check(r->threads.most + 1 <= workers, "%s: %ld workers at once, more than %ld", what, r->threads.most + 1,
          workers);
    if (reference != NULL)
        check(memcmp(r->values, reference->values, (size_t)SLOTS * VALUES * sizeof(float)) == 0,
              "%s: other set calls than with 1 thread", what);
}

/* Whether two calls started the same threads, as many at once. */
static int same_threads(const run *a, const run *b)
{
    return a->threads.started == b->threads.started && a->threads.most == b->threads.most;
}

int main(void)
{
    run one, two, four, late, after, early, then, first, second;
    pthread_barrier_t changed, started, computed;
    pthread_t threads[2];
    int k;

    /* Alone: 1, 2 and 4 threads. */
    init_run(&one, 1);
    call(&one);
    init_run(&two, 2);
    call(&two);
    init_run(&four, 4);
    call(&four);
    check_call("1 thread", &one, 1, NULL);
    check(one.threads.started == 0, "1 thread: %ld threads started", one.threads.started);
    check_call("2 threads", &two, 2, &one);
    check(two.threads.most == 1, "2 threads: %ld workers at once, not 2", two.threads.most + 1);
    check_call("4 threads", &four, 4, &one);
    check(four.threads.most == 3, "4 threads: %ld workers at once, not 4", four.threads.most + 1);
    check(four.threads.started > two.threads.started && two.threads.started > 0,
          "threads started: %ld with 4, %ld with 2", four.threads.started, two.threads.started);

    /* The count changed from inside a call: from 4 to 1, then from 1 to 4. */
    init_run(&late, 4);
    late.threads_in_callback = 1;
    call(&late);
    init_run(&after, 0);
    call(&after);
    check_call("4, set to 1 during the call", &late, 4, &one);
    check(same_threads(&late, &four), "4, set to 1 during the call: %ld threads started, %ld at once; alone %ld, %ld",
          late.threads.started, late.threads.most, four.threads.started, four.threads.most);
    check_call("the call after the one set to 1", &after, 1, &one);
    check(after.threads.started == 0, "the call after the one set to 1: %ld threads started", after.threads.started);
    init_run(&early, 1);
    early.threads_in_callback = 4;
    call(&early);
    init_run(&then, 0);
    call(&then);
    check_call("1, set to 4 during the call", &early, 1, &one);
    check(early.threads.started == 0, "1, set to 4 during the call: %ld threads started", early.threads.started);
    check_call("the call after the one set to 4", &then, 4, &one);
    check(same_threads(&then, &four),
          "the call after the one set to 4: %ld threads started, %ld at once; with 4 alone %ld, %ld",
          then.threads.started, then.threads.most, four.threads.started, four.threads.most);

    /* Two calls at once. The first starts with 4 and sets 2; the second, on another thread that
       sets nothing, starts only then. Both are held until both have started, and again until both
       have computed. */
    pthread_barrier_init(&changed, NULL, 2);
    pthread_barrier_init(&started, NULL, 2);
    pthread_barrier_init(&computed, NULL, 2);
    init_run(&first, 4);
    first.threads_in_callback = 2;
    first.changed = &changed;
    init_run(&second, 0);
    second.before = &changed;
    for (k = 0; k < 2; k++) {
        run *r = k == 0 ? &first : &second;
        r->started = &started;
        r->computed = &computed;
        check(pthread_create(&threads[k], NULL, call, r) == 0, "start calling thread %d", k);
    }
    for (k = 0; k < 2; k++)
        pthread_join(threads[k], NULL);
    check_call("at once, started with 4", &first, 4, &one);
    check(same_threads(&first, &four), "at once, started with 4: %ld threads started, %ld at once; alone %ld, %ld",
          first.threads.started, first.threads.most, four.threads.started, four.threads.most);
    check_call("at once, started after the count became 2", &second, 2, &one);
    check(same_threads(&second, &two),
          "at once, started after the count became 2: %ld threads started, %ld at once; with 2 alone %ld, %ld",
          second.threads.started, second.threads.most, two.threads.started, two.threads.most);

    /* Both with 4. */
    for (k = 0; k < 2; k++) {
        run *r = k == 0 ? &first : &second;
        free(r->values);
        init_run(r, 4);
        r->started = &started;
        r->computed = &computed;
        check(pthread_create(&threads[k], NULL, call, r) == 0, "start calling thread %d", k);
    }
    for (k = 0; k < 2; k++) {
        const run *r = k == 0 ? &first : &second;
        pthread_join(threads[k], NULL);
        check_call(k == 0 ? "at once with 4, the first" : "at once with 4, the second", r, 4, &one);
        check(same_threads(r, &four), "at once with 4, call %d: %ld threads started, %ld at once; alone %ld, %ld", k,
              r->threads.started, r->threads.most, four.threads.started, four.threads.most);
    }

    free(one.values);
    free(two.values);
    free(four.values);
    free(late.values);
    free(after.values);
    free(early.values);
    free(then.values);
    free(first.values);
    free(second.values);
    printf("%ld passed, %ld failed\n", checks_passed, checks_failed);
    return checks_failed == 0 ? 0 : 1;
}
