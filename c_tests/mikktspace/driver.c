/*
 * A program that uses mikktspace.c's interface as any program would: compiled against
 * mikktspace.h (or, with -DDRIVER_TBASIS_HEADER, against include/tbasis_mikktspace.h), linked to
 * mikktspace.c or to libtbasis_mikktspace. tests/mikktspace_dropin.rs builds it each way, runs it
 * on the same meshes and requires the same output.
 *
 *   driver MESHES [--max-vertices N] [--config CONFIG]... [--strict] [--threads N]
 *          [--dump MESH CONFIG] [--perturb MESH]
 *
 * MESHES is the file crates/test-support/src/face_meshes.rs writes. For every mesh (up to N
 * vertices) and every configuration (genTangSpaceDefault, genTangSpace at 180, 90 and 30 degrees;
 * m_setTSpace, m_setTSpaceBasic, both, and neither) it prints one line:
 *
 *   MESH <tab> CONFIG <tab> RETURN <tab> SET_CALLS <tab> DIGEST
 *
 * DIGEST is a 64-bit FNV-1a hash of every argument of every set call, in call order (the callback,
 * face, vertex, and each float's bits; any NaN hashed as 0x7fc00000, since which NaN an operation
 * on NaN gives is not fixed). --config runs the named configurations only (valgrind's run takes
 * three). --dump prints the calls of one run instead, one per line, as bits.
 * --perturb flips the lowest bit of the first tangent of every run of one mesh: the test that the
 * comparison notices. --threads calls tbasis_mikktspace_set_threads (with its header only).
 *
 * A set callback for a face or vertex that does not exist is reported, and the exit status is 1;
 * with --strict (the drop-in's runs), a get callback as well, but one: mikktspace.c, and the
 * drop-in with it, reads the position of face 0's vertex 0 for its bounding box whatever face 0's
 * vertex count (its GenerateSharedVerticesIndexList starts from index 0, not from the first
 * triangle's). Where face 0 has no vertex the driver answers that read with zeros.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#ifdef DRIVER_TBASIS_HEADER
#include "tbasis_mikktspace.h"
#else
#include "mikktspace.h"
#endif

typedef struct mesh {
    char *name;
    uint32_t vertex_count;
    int32_t reported_faces;
    uint32_t face_count;
    uint32_t slot_count;
    float *positions;
    float *normals;
    float *texcoords;
    int32_t *face_sizes;
    uint32_t *face_vertices;
    uint32_t *face_starts;
} mesh;

/* One call of genTangSpace(Default) on one mesh: what the callbacks saw. */
typedef struct run {
    const mesh *mesh;
    uint64_t digest;
    unsigned long set_calls;
    unsigned long bad_gets, bad_sets;     /* calls for a face or vertex out of range */
    const char *first_bad;                /* the first such callback, its face and vertex */
    int first_bad_face, first_bad_vert;
    int perturb;
    FILE *dump;
} run;

static const run *run_of(const SMikkTSpaceContext *context)
{
    return (const run *)context->m_pUserData;
}

/* Counts a callback for a face or vertex that does not exist. */
static void out_of_range(const SMikkTSpaceContext *context, const char *callback, int iFace, int iVert, int set)
{
    run *r = (run *)context->m_pUserData;
    if (r->bad_gets + r->bad_sets == 0) {
        r->first_bad = callback;
        r->first_bad_face = iFace;
        r->first_bad_vert = iVert;
    }
    if (set)
        r->bad_sets++;
    else
        r->bad_gets++;
}

/* The attribute index of vertex iVert of face iFace, or -1 (counted) when out of range. */
static long vertex_of(const SMikkTSpaceContext *context, const char *callback, int iFace, int iVert, int set)
{
    const mesh *m = run_of(context)->mesh;
    if (iFace < 0 || (uint32_t)iFace >= m->face_count || iVert < 0 || iVert >= m->face_sizes[iFace]) {
        out_of_range(context, callback, iFace, iVert, set);
        return -1;
    }
    return (long)m->face_vertices[m->face_starts[iFace] + (uint32_t)iVert];
}

static int get_num_faces(const SMikkTSpaceContext *context)
{
    return run_of(context)->mesh->reported_faces;
}

static int get_num_vertices_of_face(const SMikkTSpaceContext *context, const int iFace)
{
    const mesh *m = run_of(context)->mesh;
    if (iFace < 0 || (uint32_t)iFace >= m->face_count) {
        out_of_range(context, "m_getNumVerticesOfFace", iFace, -1, 0);
        return 0;
    }
    return m->face_sizes[iFace];
}

static void copy_attribute(float out[], const float *values, long vertex, int n)
{
    int k;
    for (k = 0; k < n; k++)
        out[k] = vertex < 0 ? 0.0f : values[vertex * n + k];
}

static void get_position(const SMikkTSpaceContext *context, float fvPosOut[], const int iFace, const int iVert)
{
    const mesh *m = run_of(context)->mesh;
    if (iFace == 0 && iVert == 0 && m->face_count > 0 && m->face_sizes[0] < 1) {
        /* The one read outside the faces that mikktspace.c (and so the drop-in) makes: index 0's
           position, to start its bounding box. Answered with zeros. */
        copy_attribute(fvPosOut, m->positions, -1, 3);
        return;
    }
    copy_attribute(fvPosOut, m->positions, vertex_of(context, "m_getPosition", iFace, iVert, 0), 3);
}

static void get_normal(const SMikkTSpaceContext *context, float fvNormOut[], const int iFace, const int iVert)
{
    copy_attribute(fvNormOut, run_of(context)->mesh->normals, vertex_of(context, "m_getNormal", iFace, iVert, 0), 3);
}

static void get_tex_coord(const SMikkTSpaceContext *context, float fvTexcOut[], const int iFace, const int iVert)
{
    copy_attribute(fvTexcOut, run_of(context)->mesh->texcoords, vertex_of(context, "m_getTexCoord", iFace, iVert, 0), 2);
}

static uint32_t bits_of(float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    if ((bits & 0x7fffffffu) > 0x7f800000u)
        bits = 0x7fc00000u;
    return bits;
}

static void hash_word(run *r, uint32_t word)
{
    int k;
    for (k = 0; k < 4; k++) {
        r->digest ^= (word >> (8 * k)) & 0xffu;
        r->digest *= 0x100000001b3ull;
    }
}

/* Hashes (or dumps) one set call: the callback (1 m_setTSpace, 2 m_setTSpaceBasic), face,
   vertex, then the floats' bits and the flag. */
static void record(run *r, uint32_t callback, int iFace, int iVert, const uint32_t *words, int n)
{
    int k;
    if (r->dump != NULL) {
        fprintf(r->dump, "%s face %d vert %d", callback == 1 ? "setTSpace" : "setTSpaceBasic", iFace, iVert);
        for (k = 0; k < n; k++)
            fprintf(r->dump, " %08lx", (unsigned long)words[k]);
        fprintf(r->dump, "\n");
    }
    hash_word(r, callback);
    hash_word(r, (uint32_t)iFace);
    hash_word(r, (uint32_t)iVert);
    for (k = 0; k < n; k++)
        hash_word(r, words[k]);
    r->set_calls++;
}

/* The first words of a set call: the bits of `floats` (its tangent first), the tangent's x with
   its lowest bit flipped on the first call of a perturbed run. */
static void words_of(run *r, const float *floats, int n, uint32_t *words)
{
    int k;
    for (k = 0; k < n; k++)
        words[k] = bits_of(floats[k]);
    if (r->perturb && r->set_calls == 0)
        words[0] ^= 1u;
}

static void set_tspace(const SMikkTSpaceContext *context, const float fvTangent[], const float fvBiTangent[],
                       const float fMagS, const float fMagT, const tbool bIsOrientationPreserving, const int iFace,
                       const int iVert)
{
    run *r = (run *)context->m_pUserData;
    float floats[8];
    uint32_t words[9];
    (void)vertex_of(context, "m_setTSpace", iFace, iVert, 1);
    memcpy(floats, fvTangent, 3 * sizeof(float));
    memcpy(floats + 3, fvBiTangent, 3 * sizeof(float));
    floats[6] = fMagS;
    floats[7] = fMagT;
    words_of(r, floats, 8, words);
    words[8] = (uint32_t)bIsOrientationPreserving;
    record(r, 1, iFace, iVert, words, 9);
}

static void set_tspace_basic(const SMikkTSpaceContext *context, const float fvTangent[], const float fSign,
                             const int iFace, const int iVert)
{
    run *r = (run *)context->m_pUserData;
    float floats[4];
    uint32_t words[4];
    (void)vertex_of(context, "m_setTSpaceBasic", iFace, iVert, 1);
    memcpy(floats, fvTangent, 3 * sizeof(float));
    floats[3] = fSign;
    words_of(r, floats, 4, words);
    record(r, 2, iFace, iVert, words, 4);
}

typedef struct config {
    const char *name;
    float threshold; /* < 0: genTangSpaceDefault */
    int full;
    int basic;
} config;

static const config configs[] = {
    {"default both", -1.0f, 1, 1}, {"default full", -1.0f, 1, 0}, {"default basic", -1.0f, 0, 1},
    {"default none", -1.0f, 0, 0}, {"180 both", 180.0f, 1, 1},    {"180 full", 180.0f, 1, 0},
    {"180 basic", 180.0f, 0, 1},   {"90 both", 90.0f, 1, 1},      {"90 full", 90.0f, 1, 0},
    {"90 basic", 90.0f, 0, 1},     {"30 both", 30.0f, 1, 1},      {"30 full", 30.0f, 1, 0},
    {"30 basic", 30.0f, 0, 1},
};

/* What the runs found beyond their lines: errors, and runs whose get callbacks (allowed without
   --strict) asked for a face or vertex that does not exist. */
typedef struct totals {
    int strict;
    unsigned long errors;
    unsigned long lenient_runs;
} totals;

static void run_config(const mesh *m, const config *c, int perturb, FILE *dump, totals *t)
{
    SMikkTSpaceInterface interface;
    SMikkTSpaceContext context;
    run r;
    tbool result;
    memset(&interface, 0, sizeof interface);
    interface.m_getNumFaces = get_num_faces;
    interface.m_getNumVerticesOfFace = get_num_vertices_of_face;
    interface.m_getPosition = get_position;
    interface.m_getNormal = get_normal;
    interface.m_getTexCoord = get_tex_coord;
    interface.m_setTSpace = c->full ? set_tspace : NULL;
    interface.m_setTSpaceBasic = c->basic ? set_tspace_basic : NULL;
    memset(&r, 0, sizeof r);
    r.mesh = m;
    r.digest = 0xcbf29ce484222325ull;
    r.perturb = perturb;
    r.dump = dump;
    context.m_pInterface = &interface;
    context.m_pUserData = &r;
    result = c->threshold < 0.0f ? genTangSpaceDefault(&context) : genTangSpace(&context, c->threshold);
    if (dump == NULL)
        printf("%s\t%s\t%d\t%lu\t%016llx\n", m->name, c->name, (int)result, r.set_calls,
               (unsigned long long)r.digest);
    else
        fprintf(dump, "return %d\n", (int)result);
    if (r.bad_sets > 0 || (t->strict && r.bad_gets > 0)) {
        fprintf(stderr, "%s, %s: %lu set and %lu get callbacks out of range, the first %s(face %d, vertex %d)\n",
                m->name, c->name, r.bad_sets, r.bad_gets, r.first_bad, r.first_bad_face, r.first_bad_vert);
        t->errors++;
    } else if (r.bad_gets > 0) {
        t->lenient_runs++;
    }
}

static int read_exact(FILE *file, void *buffer, size_t size)
{
    return size == 0 || fread(buffer, 1, size, file) == size;
}

static void *read_array(FILE *file, size_t count, size_t size, int *ok)
{
    void *array = malloc(count * size + 1);
    if (array == NULL || !read_exact(file, array, count * size))
        *ok = 0;
    return array;
}

/* Reads one mesh; 0 on a short or malformed file. */
static int read_mesh(FILE *file, mesh *m)
{
    uint32_t name_length, f, start = 0;
    int ok = 1;
    memset(m, 0, sizeof *m);
    if (!read_exact(file, &name_length, 4) || name_length > 4096)
        return 0;
    m->name = (char *)read_array(file, name_length, 1, &ok);
    if (!ok)
        return 0;
    m->name[name_length] = '\0';
    if (!read_exact(file, &m->vertex_count, 4) || !read_exact(file, &m->reported_faces, 4) ||
        !read_exact(file, &m->face_count, 4) || !read_exact(file, &m->slot_count, 4))
        return 0;
    m->positions = (float *)read_array(file, (size_t)m->vertex_count * 3, sizeof(float), &ok);
    m->normals = (float *)read_array(file, (size_t)m->vertex_count * 3, sizeof(float), &ok);
    m->texcoords = (float *)read_array(file, (size_t)m->vertex_count * 2, sizeof(float), &ok);
    m->face_sizes = (int32_t *)read_array(file, m->face_count, sizeof(int32_t), &ok);
    m->face_vertices = (uint32_t *)read_array(file, m->slot_count, sizeof(uint32_t), &ok);
    m->face_starts = (uint32_t *)malloc((size_t)m->face_count * sizeof(uint32_t) + 1);
    if (!ok || m->face_starts == NULL || m->reported_faces > (int32_t)m->face_count)
        return 0;
    for (f = 0; f < m->face_count; f++) {
        m->face_starts[f] = start;
        start += m->face_sizes[f] > 0 ? (uint32_t)m->face_sizes[f] : 0;
    }
    for (f = 0; f < m->slot_count; f++)
        if (m->face_vertices[f] >= m->vertex_count)
            return 0;
    return start == m->slot_count;
}

static void free_mesh(mesh *m)
{
    free(m->name);
    free(m->positions);
    free(m->normals);
    free(m->texcoords);
    free(m->face_sizes);
    free(m->face_vertices);
    free(m->face_starts);
}

int main(int argc, char **argv)
{
    FILE *file;
    char magic[4];
    uint32_t mesh_count, k;
    unsigned long max_vertices = (unsigned long)-1;
    totals t;
    const char *dump_mesh = NULL, *dump_config = NULL, *perturb_mesh = NULL;
    const char *chosen[16];
    int a, chosen_count = 0;
    size_t c;

    memset(&t, 0, sizeof t);
    if (argc < 2) {
        fprintf(stderr, "usage: %s MESHES [--max-vertices N] [--config CONFIG]... [--strict] [--threads N] "
                "[--dump MESH CONFIG] [--perturb MESH]\n",
                argv[0]);
        return 2;
    }
    for (a = 2; a < argc; a++) {
        if (strcmp(argv[a], "--max-vertices") == 0 && a + 1 < argc) {
            max_vertices = strtoul(argv[++a], NULL, 10);
        } else if (strcmp(argv[a], "--dump") == 0 && a + 2 < argc) {
            dump_mesh = argv[++a];
            dump_config = argv[++a];
        } else if (strcmp(argv[a], "--config") == 0 && a + 1 < argc && chosen_count < 16) {
            chosen[chosen_count++] = argv[++a];
        } else if (strcmp(argv[a], "--strict") == 0) {
            t.strict = 1;
        } else if (strcmp(argv[a], "--perturb") == 0 && a + 1 < argc) {
            perturb_mesh = argv[++a];
#ifdef TBASIS_MIKKTSPACE_H
        } else if (strcmp(argv[a], "--threads") == 0 && a + 1 < argc) {
            tbasis_mikktspace_set_threads(atoi(argv[++a]));
#endif
        } else {
            fprintf(stderr, "%s: unknown or incomplete argument %s\n", argv[0], argv[a]);
            return 2;
        }
    }
    file = fopen(argv[1], "rb");
    if (file == NULL || !read_exact(file, magic, 4) || memcmp(magic, "TBMK", 4) != 0 ||
        !read_exact(file, &mesh_count, 4)) {
        fprintf(stderr, "%s: cannot read a mesh file\n", argv[1]);
        return 2;
    }
    for (k = 0; k < mesh_count; k++) {
        mesh m;
        if (!read_mesh(file, &m)) {
            fprintf(stderr, "%s: mesh %lu is malformed\n", argv[1], (unsigned long)k);
            return 2;
        }
        if (m.vertex_count <= max_vertices) {
            for (c = 0; c < sizeof configs / sizeof configs[0]; c++) {
                int perturb = perturb_mesh != NULL && strcmp(perturb_mesh, m.name) == 0, k, take = chosen_count == 0;
                for (k = 0; k < chosen_count; k++)
                    take = take || strcmp(chosen[k], configs[c].name) == 0;
                if (!take)
                    continue;
                if (dump_mesh == NULL)
                    run_config(&m, &configs[c], perturb, NULL, &t);
                else if (strcmp(dump_mesh, m.name) == 0 && strcmp(dump_config, configs[c].name) == 0)
                    run_config(&m, &configs[c], perturb, stdout, &t);
            }
        }
        free_mesh(&m);
    }
    fclose(file);
    if (t.lenient_runs > 0)
        fprintf(stderr, "%lu runs called a get callback for a face or vertex that does not exist\n", t.lenient_runs);
    return t.errors > 0 ? 1 : 0;
}
