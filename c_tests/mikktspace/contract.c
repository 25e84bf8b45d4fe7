/*
 * What include/tbasis_mikktspace.h promises beyond mikktspace.c's results, checked against
 * libtbasis_mikktspace (tests/mikktspace_dropin.rs builds and runs it):
 *
 * - a NULL context, a NULL interface or a NULL get callback: 0, and no callback called;
 * - a face count of 0 or less: 0 after m_getNumFaces alone; faces but none of 3 or 4 vertices: 0
 *   after the counts alone;
 * - the callbacks, in the header's order: m_getNumFaces once, m_getNumVerticesOfFace once per
 *   face, the three get callbacks once per vertex of each face of 3 or 4 vertices, then
 *   m_setTSpace and m_setTSpaceBasic per face vertex; faces of other counts never read;
 * - both set callbacks NULL: 1, and no set call;
 * - with 4 worker threads, and from two threads at once, every callback on the calling thread
 *   and the same set calls as with one thread.
 *
 * Prints "N passed, M failed" last and exits 0 when nothing failed.
 *
 * With -DCONTRACT_FAULTS, for a library built with the test-only feature fault-injection: both
 * entry points on a quad, printing "internal 2" when each returned 0 without calling any
 * callback (TBASIS_INJECT_PANIC set), "ok 2" when each returned 1 after its callbacks.
 */
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../counted.h"
#include "tbasis_mikktspace.h"

/* A callback call: which, face, vertex, and for set calls the arguments. */
enum { NUM_FACES = 1, NUM_VERTICES, POSITION, NORMAL, TEXCOORD, SET_BASIC, SET_FULL };

typedef struct call {
    int kind;
    int face;
    int vert;
    float values[9];
} call;

/* A grid of cols x rows quads with shared vertices; face k of `sizes` reports sizes[k] vertices
   (a size past the grid's faces, or of other counts, reads nothing). */
typedef struct mesh {
    int cols, rows;
    int face_count;
    const int *sizes; /* NULL: every face is a quad */
    int reported_faces;
    pthread_t thread;   /* the thread every callback must run on */
    long wrong_thread;  /* callbacks on another thread */
    long out_of_range;  /* callbacks for a face or vertex that does not exist */
    call *calls;        /* NULL: not recorded */
    long call_count, call_capacity;
    long callbacks;     /* every callback */
} mesh;

static mesh *mesh_of(const SMikkTSpaceContext *context)
{
    return (mesh *)context->m_pUserData;
}

static void note(const SMikkTSpaceContext *context, int kind, int face, int vert, const float *values, int n)
{
    mesh *m = mesh_of(context);
    m->callbacks++;
    if (!pthread_equal(pthread_self(), m->thread))
        m->wrong_thread++;
    if (m->calls == NULL)
        return;
    if (m->call_count == m->call_capacity) {
        m->call_capacity = m->call_capacity * 2 + 64;
        m->calls = (call *)realloc(m->calls, (size_t)m->call_capacity * sizeof(call));
        if (m->calls == NULL) {
            printf("out of memory\n");
            exit(2);
        }
    }
    memset(&m->calls[m->call_count], 0, sizeof(call));
    m->calls[m->call_count].kind = kind;
    m->calls[m->call_count].face = face;
    m->calls[m->call_count].vert = vert;
    if (n > 0)
        memcpy(m->calls[m->call_count].values, values, (size_t)n * sizeof(float));
    m->call_count++;
}

static int face_size(const mesh *m, int face)
{
    return m->sizes != NULL ? m->sizes[face] : 4;
}

/* The grid vertex (column, row) of vertex `vert` of `face`; faces past the grid reuse cell 0. */
static void grid_vertex(const SMikkTSpaceContext *context, int face, int vert, int *i, int *j)
{
    mesh *m = mesh_of(context);
    int cell = face % (m->cols * m->rows);
    static const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
    if (face < 0 || face >= m->face_count || vert < 0 || vert >= face_size(m, face) || vert > 3) {
        m->out_of_range++;
        vert = 0;
        cell = 0;
    }
    *i = cell % m->cols + di[vert];
    *j = cell / m->cols + dj[vert];
}

static int get_num_faces(const SMikkTSpaceContext *context)
{
    note(context, NUM_FACES, -1, -1, NULL, 0);
    return mesh_of(context)->reported_faces;
}

static int get_num_vertices_of_face(const SMikkTSpaceContext *context, const int iFace)
{
    mesh *m = mesh_of(context);
    note(context, NUM_VERTICES, iFace, -1, NULL, 0);
    if (iFace < 0 || iFace >= m->face_count) {
        m->out_of_range++;
        return 0;
    }
    return face_size(m, iFace);
}

static void get_position(const SMikkTSpaceContext *context, float fvPosOut[], const int iFace, const int iVert)
{
    int i, j;
    note(context, POSITION, iFace, iVert, NULL, 0);
    grid_vertex(context, iFace, iVert, &i, &j);
    fvPosOut[0] = (float)i;
    fvPosOut[1] = (float)j;
    fvPosOut[2] = 0.05f * (float)((i * 7 + j * 3) % 5);
}

static void get_normal(const SMikkTSpaceContext *context, float fvNormOut[], const int iFace, const int iVert)
{
    note(context, NORMAL, iFace, iVert, NULL, 0);
    fvNormOut[0] = 0.0f;
    fvNormOut[1] = 0.0f;
    fvNormOut[2] = 1.0f;
}

static void get_tex_coord(const SMikkTSpaceContext *context, float fvTexcOut[], const int iFace, const int iVert)
{
    int i, j;
    note(context, TEXCOORD, iFace, iVert, NULL, 0);
    grid_vertex(context, iFace, iVert, &i, &j);
    fvTexcOut[0] = 0.1f * (float)i + 0.01f * (float)((i * 5 + j) % 3);
    fvTexcOut[1] = 0.1f * (float)j;
}

static void set_tspace_basic(const SMikkTSpaceContext *context, const float fvTangent[], const float fSign,
                             const int iFace, const int iVert)
{
    float values[4];
    memcpy(values, fvTangent, 3 * sizeof(float));
    values[3] = fSign;
    note(context, SET_BASIC, iFace, iVert, values, 4);
}

static void set_tspace(const SMikkTSpaceContext *context, const float fvTangent[], const float fvBiTangent[],
                       const float fMagS, const float fMagT, const tbool bIsOrientationPreserving, const int iFace,
                       const int iVert)
{
    float values[9];
    memcpy(values, fvTangent, 3 * sizeof(float));
    memcpy(values + 3, fvBiTangent, 3 * sizeof(float));
    values[6] = fMagS;
    values[7] = fMagT;
    values[8] = (float)bIsOrientationPreserving;
    note(context, SET_FULL, iFace, iVert, values, 9);
}

/* Every callback, in the header's member order (a positional initializer checks that order). */
static SMikkTSpaceInterface full_interface(void)
{
    SMikkTSpaceInterface interface = {get_num_faces, get_num_vertices_of_face, get_position, get_normal,
                                      get_tex_coord, set_tspace_basic,        set_tspace};
    return interface;
}

static void init_mesh(mesh *m, int cols, int rows, const int *sizes, int face_count, int record)
{
    memset(m, 0, sizeof *m);
    m->cols = cols;
    m->rows = rows;
    m->sizes = sizes;
    m->face_count = face_count;
    m->reported_faces = face_count;
    m->thread = pthread_self();
    if (record) {
        m->call_capacity = 64;
        m->calls = (call *)malloc((size_t)m->call_capacity * sizeof(call));
        if (m->calls == NULL)
            exit(2);
    }
}

#ifdef CONTRACT_FAULTS

int main(void)
{
    SMikkTSpaceInterface interface = full_interface();
    SMikkTSpaceContext context;
    mesh m;
    tbool results[2];
    long callbacks[2];
    int k, internal = 0, ok = 0;
    init_mesh(&m, 1, 1, NULL, 1, 0);
    context.m_pInterface = &interface;
    context.m_pUserData = &m;
    for (k = 0; k < 2; k++) {
        m.callbacks = 0;
        results[k] = k == 0 ? genTangSpaceDefault(&context) : genTangSpace(&context, 90.0f);
        callbacks[k] = m.callbacks;
        internal += results[k] == 0 && callbacks[k] == 0;
        ok += results[k] == 1 && callbacks[k] > 0;
    }
    if (internal == 2 || ok == 2) {
        printf("%s 2\n", internal == 2 ? "internal" : "ok");
        return 0;
    }
    printf("genTangSpaceDefault: %d after %ld callbacks; genTangSpace: %d after %ld\n", results[0], callbacks[0],
           results[1], callbacks[1]);
    return 1;
}

#else

static tbool generate(SMikkTSpaceInterface *interface, mesh *m)
{
    SMikkTSpaceContext context;
    context.m_pInterface = interface;
    context.m_pUserData = m;
    return genTangSpaceDefault(&context);
}

/* A NULL context, interface or get callback: 0 without any call. */
static void null_callbacks(void)
{
    SMikkTSpaceInterface interface;
    SMikkTSpaceContext context;
    mesh m;
    int k;
    init_mesh(&m, 2, 2, NULL, 4, 0);
    check(genTangSpaceDefault(NULL) == 0 && genTangSpace(NULL, 30.0f) == 0, "a NULL context returns 0");
    context.m_pInterface = NULL;
    context.m_pUserData = &m;
    check(genTangSpaceDefault(&context) == 0, "a NULL interface returns 0");
    for (k = 0; k < 5; k++) {
        interface = full_interface();
        switch (k) {
        case 0: interface.m_getNumFaces = NULL; break;
        case 1: interface.m_getNumVerticesOfFace = NULL; break;
        case 2: interface.m_getPosition = NULL; break;
        case 3: interface.m_getNormal = NULL; break;
        default: interface.m_getTexCoord = NULL; break;
        }
        m.callbacks = 0;
        check(generate(&interface, &m) == 0 && m.callbacks == 0, "get callback %d NULL: 0 without a call (%ld calls)",
              k, m.callbacks);
    }
}

/* Face counts of 0 or less: 0 after m_getNumFaces alone. */
static void no_faces(void)
{
    SMikkTSpaceInterface interface = full_interface();
    static const int counts[3] = {0, -1, -2147483647 - 1};
    mesh m;
    int k;
    for (k = 0; k < 3; k++) {
        init_mesh(&m, 2, 2, NULL, 4, 1);
        m.reported_faces = counts[k];
        check(generate(&interface, &m) == 0, "a face count of %d returns 0", counts[k]);
        check(m.call_count == 1 && m.calls[0].kind == NUM_FACES, "a face count of %d: m_getNumFaces alone (%ld calls)",
              counts[k], m.call_count);
        free(m.calls);
    }
}

/* Faces, but none of 3 or 4 vertices: 0 with no get callback past the counts and no set call. */
static void no_usable_face(void)
{
    SMikkTSpaceInterface interface = full_interface();
    static const int sizes[4] = {5, 2, 0, -1};
    mesh m;
    long k, reads = 0;
    init_mesh(&m, 2, 2, sizes, 4, 1);
    check(generate(&interface, &m) == 0, "no face of 3 or 4 vertices returns 0");
    for (k = 0; k < m.call_count; k++)
        reads += m.calls[k].kind != NUM_FACES && m.calls[k].kind != NUM_VERTICES;
    check(reads == 0, "no face of 3 or 4 vertices: %ld calls past the counts", reads);
    free(m.calls);
}

/* Appends the expected call to `expected`. */
static void expect(call *expected, long *n, int kind, int face, int vert)
{
    memset(&expected[*n], 0, sizeof(call));
    expected[*n].kind = kind;
    expected[*n].face = face;
    expected[*n].vert = vert;
    (*n)++;
}

/* The callbacks in the header's order on quads, triangles and faces of other counts `sizes`. */
static void call_order(const int sizes[8])
{
    SMikkTSpaceInterface interface = full_interface();
    call expected[256];
    long n = 0, k, first_set = 0;
    int f, v, kind, same = 1;
    tbool result;
    mesh m;
    init_mesh(&m, 4, 2, sizes, 8, 1);
    result = generate(&interface, &m);

    expect(expected, &n, NUM_FACES, -1, -1);
    for (f = 0; f < 8; f++)
        expect(expected, &n, NUM_VERTICES, f, -1);
    if (sizes[0] != 3 && sizes[0] != 4)
        expect(expected, &n, POSITION, 0, 0);
    for (f = 0; f < 8; f++)
        for (v = 0; (sizes[f] == 3 || sizes[f] == 4) && v < sizes[f]; v++)
            for (kind = POSITION; kind <= TEXCOORD; kind++)
                expect(expected, &n, kind, f, v);
    first_set = n;
    for (f = 0; f < 8; f++)
        for (v = 0; (sizes[f] == 3 || sizes[f] == 4) && v < sizes[f]; v++) {
            expect(expected, &n, SET_FULL, f, v);
            expect(expected, &n, SET_BASIC, f, v);
        }
    for (k = 0; k < first_set && k < m.call_count; k++)
        same = same && m.calls[k].kind == expected[k].kind && m.calls[k].face == expected[k].face &&
               m.calls[k].vert == expected[k].vert;
    check(same && m.call_count >= first_set, "the get callbacks in the header's order (%ld calls, %ld expected)",
          m.call_count, first_set);
    check(result == 1, "quads and triangles among other faces return 1 (%d)", result);
    same = m.call_count == n;
    for (k = first_set; same && k < n; k++)
        same = m.calls[k].kind == expected[k].kind && m.calls[k].face == expected[k].face &&
               m.calls[k].vert == expected[k].vert;
    check(same, "the set callbacks in the header's order (%ld calls, %ld expected)", m.call_count, n);
    for (k = first_set; same && k < n; k += 2)
        check(memcmp(m.calls[k].values, m.calls[k + 1].values, 3 * sizeof(float)) == 0 &&
                  m.calls[k + 1].values[3] == (m.calls[k].values[8] == 1.0f ? 1.0f : -1.0f) &&
                  (m.calls[k].values[8] == 0.0f || m.calls[k].values[8] == 1.0f),
              "face %d vert %d: both set callbacks get the same tangent, sign and orientation", m.calls[k].face,
              m.calls[k].vert);
    check(m.out_of_range == 0, "no callback for a face or vertex out of range (%ld)", m.out_of_range);
    free(m.calls);

    /* Neither set callback: 1, the get callbacks alone. */
    interface.m_setTSpace = NULL;
    interface.m_setTSpaceBasic = NULL;
    init_mesh(&m, 4, 2, sizes, 8, 1);
    result = generate(&interface, &m);
    check(result == 1 && m.call_count == first_set, "no set callback: 1 after the get callbacks (%d, %ld calls)",
          result, m.call_count);
    free(m.calls);
}

/* One run on a grid big enough for several workers, recorded, on this thread. */
typedef struct threaded_run {
    mesh m;
    int threads;
    tbool result;
} threaded_run;

enum { GRID_COLS = 160, GRID_ROWS = 120 };

static void *threaded(void *argument)
{
    threaded_run *r = (threaded_run *)argument;
    SMikkTSpaceInterface interface = full_interface();
    init_mesh(&r->m, GRID_COLS, GRID_ROWS, NULL, GRID_COLS * GRID_ROWS, 1);
    r->result = generate(&interface, &r->m);
    return NULL;
}

static int same_set_calls(const mesh *a, const mesh *b)
{
    long k;
    if (a->call_count != b->call_count)
        return 0;
    for (k = 0; k < a->call_count; k++)
        if (a->calls[k].kind != b->calls[k].kind || a->calls[k].face != b->calls[k].face ||
            a->calls[k].vert != b->calls[k].vert || memcmp(a->calls[k].values, b->calls[k].values, 9 * sizeof(float)))
            return 0;
    return 1;
}

/* 1 and 4 workers, then two calls at once with 2: the same calls, all on the calling thread. */
static void threads(void)
{
    threaded_run one, four, concurrent[2];
    pthread_t workers[2];
    int k;
    tbasis_mikktspace_set_threads(1);
    threaded(&one);
    tbasis_mikktspace_set_threads(4);
    threaded(&four);
    check(one.result == 1 && four.result == 1, "the grid returns 1 with 1 and 4 threads (%d, %d)", one.result,
          four.result);
    check(four.m.wrong_thread == 0 && one.m.wrong_thread == 0, "4 threads: every callback on the calling thread");
    check(same_set_calls(&one.m, &four.m), "4 threads: the same calls as 1");
    tbasis_mikktspace_set_threads(2);
    for (k = 0; k < 2; k++)
        check(pthread_create(&workers[k], NULL, threaded, &concurrent[k]) == 0, "start thread %d", k);
    for (k = 0; k < 2; k++) {
        pthread_join(workers[k], NULL);
        check(concurrent[k].m.wrong_thread == 0, "concurrent call %d: every callback on its calling thread", k);
        check(same_set_calls(&one.m, &concurrent[k].m), "concurrent call %d: the same calls as alone", k);
        free(concurrent[k].m.calls);
    }
    /* Counts of 1 or less mean the calling thread alone. */
    tbasis_mikktspace_set_threads(0);
    tbasis_mikktspace_set_threads(-3);
    free(one.m.calls);
    threaded(&one);
    check(same_set_calls(&one.m, &four.m), "threads -3: the same calls");
    free(one.m.calls);
    free(four.m.calls);
}

int main(void)
{
    null_callbacks();
    no_faces();
    no_usable_face();
    {
        static const int quad_first[8] = {4, 3, 5, -2, 0, 4, 2, 3};
        static const int other_first[8] = {5, 3, -2, 0, 4, 2, 3, 4};
        call_order(quad_first);
        call_order(other_first);
    }
    threads();
    printf("%ld passed, %ld failed\n", checks_passed, checks_failed);
    return checks_failed == 0 ? 0 : 1;
}

#endif
