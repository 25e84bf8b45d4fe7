/*
 * libtbasis_mikktspace when memory runs out, against what include/tbasis_mikktspace.h promises
 * with one thread (the default): a call returns 0 and calls no set callback, and the process goes
 * on (tests/mikktspace_dropin.rs builds it against the shared library and runs it).
 *
 * This program defines malloc, calloc, realloc, free, posix_memalign, aligned_alloc and memalign,
 * which the shared library's calls reach before the C library's (an executable's definitions come
 * first), and hands them on to the C library's own (glibc's __libc_malloc and the others). While
 * a call runs, allocation number `fail_at` (counting from 0) fails, every other one succeeds. For
 * both entry points and two meshes (a grid of quads with a mirror seam, the same with degenerate
 * faces), `fail_at` takes every value from 0 on, until the call makes fewer allocations:
 * - when the allocation failed: the call returned 0 and called no set callback;
 * - when none failed: it returned 1, with the set calls of a call made without failures;
 * - either way, every block it allocated is freed by the time it returns.
 *
 * Prints "N passed, M failed" last and exits 0 when nothing failed.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "../counted.h"
#include "tbasis_mikktspace.h"

void *__libc_malloc(size_t size);
void *__libc_calloc(size_t count, size_t size);
void *__libc_realloc(void *block, size_t size);
void __libc_free(void *block);
void *__libc_memalign(size_t alignment, size_t size);

/* While `armed`: allocations made (`made`), the one to fail, whether it did, and blocks live. */
static int armed;
static long made, fail_at, failed, live;

/* Whether the allocation being made fails (then errno is ENOMEM); counts it. */
static int fails(void)
{
    if (!armed)
        return 0;
    if (made++ == fail_at) {
        failed = 1;
        errno = ENOMEM;
        return 1;
    }
    return 0;
}

static void *counted_block(void *block)
{
    if (armed && block != NULL)
        live++;
    return block;
}

void *malloc(size_t size)
{
    return fails() ? NULL : counted_block(__libc_malloc(size));
}

void *calloc(size_t count, size_t size)
{
    return fails() ? NULL : counted_block(__libc_calloc(count, size));
}

void *realloc(void *block, size_t size)
{
    void *moved;
    if (block == NULL)
        return malloc(size);
    /* A size of 0 frees (glibc): it is no allocation to fail. */
    if (size != 0 && fails())
        return NULL;
    moved = __libc_realloc(block, size);
    if (armed && moved == NULL && size == 0)
        live--;
    return moved;
}

void free(void *block)
{
    if (armed && block != NULL)
        live--;
    __libc_free(block);
}

void *memalign(size_t alignment, size_t size)
{
    return fails() ? NULL : counted_block(__libc_memalign(alignment, size));
}

void *aligned_alloc(size_t alignment, size_t size)
{
    return memalign(alignment, size);
}

int posix_memalign(void **out, size_t alignment, size_t size)
{
    void *block;
    if (alignment % sizeof(void *) != 0 || (alignment & (alignment - 1)) != 0)
        return EINVAL;
    block = memalign(alignment, size);
    if (block == NULL)
        return ENOMEM;
    *out = block;
    return 0;
}

/* A grid of COLS x ROWS quads whose texture coordinates mirror at the middle column; with
 * `degenerate`, every seventh face has two equal positions. */
enum { COLS = 6, ROWS = 4, FACES = COLS * ROWS, SLOTS = 4 * FACES, VALUES = 5 };

typedef struct mesh {
    int degenerate;
    long set_calls;
    float values[SLOTS][VALUES]; /* per face vertex: tangent, sign, orientation */
} mesh;

static mesh *mesh_of(const SMikkTSpaceContext *context)
{
    return (mesh *)context->m_pUserData;
}

static int get_num_faces(const SMikkTSpaceContext *context)
{
    (void)context;
    return FACES;
}

static int get_num_vertices_of_face(const SMikkTSpaceContext *context, const int iFace)
{
    (void)context;
    (void)iFace;
    return 4;
}

static void grid_vertex(const SMikkTSpaceContext *context, int face, int vert, int *i, int *j)
{
    static const int di[4] = {0, 1, 1, 0}, dj[4] = {0, 0, 1, 1};
    int collapsed = mesh_of(context)->degenerate && face % 7 == 3 && vert == 2;
    *i = face % COLS + di[collapsed ? 1 : vert];
    *j = face / COLS + dj[collapsed ? 1 : vert];
}

static void get_position(const SMikkTSpaceContext *context, float out[], const int iFace, const int iVert)
{
    int i, j;
    grid_vertex(context, iFace, iVert, &i, &j);
    out[0] = (float)i;
    out[1] = (float)j;
    out[2] = 0.1f * (float)((i * 5 + j * 3) % 4);
}

static void get_normal(const SMikkTSpaceContext *context, float out[], const int iFace, const int iVert)
{
    (void)context;
    (void)iFace;
    (void)iVert;
    out[0] = 0.0f;
    out[1] = 0.0f;
    out[2] = 1.0f;
}

static void get_tex_coord(const SMikkTSpaceContext *context, float out[], const int iFace, const int iVert)
{
    int i, j;
    grid_vertex(context, iFace, iVert, &i, &j);
    out[0] = (float)abs(2 * i - COLS) / (float)COLS;
    out[1] = (float)j / (float)ROWS;
}

static void set_space(const SMikkTSpaceContext *context, const float tangent[], const float bitangent[],
                      const float magnitude_s, const float magnitude_t, const tbool preserving, const int iFace,
                      const int iVert)
{
    mesh *m = mesh_of(context);
    float *values = m->values[4 * iFace + iVert];
    (void)bitangent;
    (void)magnitude_s;
    (void)magnitude_t;
    values[0] = tangent[0];
    values[1] = tangent[1];
    values[2] = tangent[2];
    values[4] = (float)preserving;
    m->set_calls++;
}

static void set_basic(const SMikkTSpaceContext *context, const float tangent[], const float sign, const int iFace,
                      const int iVert)
{
    (void)tangent;
    mesh_of(context)->values[4 * iFace + iVert][3] = sign;
    mesh_of(context)->set_calls++;
}

static SMikkTSpaceInterface interface = {get_num_faces, get_num_vertices_of_face, get_position, get_normal,
                                         get_tex_coord, set_basic, set_space};

/* One call with allocation `fail_at` failing (-1: none), on `m`, through the entry point
 * `threshold` names (a negative one: genTangSpaceDefault). */
static tbool call(mesh *m, long failing, float threshold)
{
    SMikkTSpaceContext context = {&interface, m};
    tbool result;
    m->set_calls = 0;
    memset(m->values, 0, sizeof m->values);
    made = 0;
    failed = 0;
    live = 0;
    fail_at = failing;
    armed = 1;
    result = threshold < 0.0f ? genTangSpaceDefault(&context) : genTangSpace(&context, threshold);
    armed = 0;
    return result;
}

int main(void)
{
    static mesh expected, found;
    static const float thresholds[2] = {-1.0f, 30.0f};
    int degenerate, t;
    for (degenerate = 0; degenerate < 2; degenerate++)
        for (t = 0; t < 2; t++) {
            const char *entry = thresholds[t] < 0.0f ? "genTangSpaceDefault" : "genTangSpace";
            long k, allocations;
            expected.degenerate = found.degenerate = degenerate;
            check(call(&expected, -1, thresholds[t]) == 1, "%s, mesh %d: succeeds", entry, degenerate);
            check(expected.set_calls == 2 * SLOTS, "%s, mesh %d: %ld set calls", entry, degenerate,
                  expected.set_calls);
            allocations = made;
            check(allocations > 0, "%s, mesh %d: allocates", entry, degenerate);
            for (k = 0; k <= allocations; k++) {
                tbool result = call(&found, k, thresholds[t]);
                int same = memcmp(found.values, expected.values, sizeof expected.values) == 0;
                if (failed)
                    check(result == 0 && found.set_calls == 0,
                          "%s, mesh %d, allocation %ld failing: returned %d after %ld set calls", entry, degenerate,
                          k, result, found.set_calls);
                else
                    check(result == 1 && same && found.set_calls == expected.set_calls,
                          "%s, mesh %d, allocation %ld past the last: returned %d, same %d, %ld set calls", entry,
                          degenerate, k, result, same, found.set_calls);
                check(live == 0, "%s, mesh %d, allocation %ld failing: %ld blocks left", entry, degenerate, k, live);
            }
            check(!failed, "%s, mesh %d: %ld allocations, then fewer", entry, degenerate, allocations);
        }
    printf("%ld passed, %ld failed\n", checks_passed, checks_failed);
    return checks_failed == 0 ? 0 : 1;
}
