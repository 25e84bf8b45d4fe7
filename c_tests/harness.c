/*
 * C test program for the tbasis C ABI.
 *
 *   harness [case-file [max-vertices]]
 *
 * Checks the ABI against this soname's table (abi.c), LEGACY results bit for bit against the
 * port of the original listing (listing.c) on generated meshes in every index form and layout,
 * the per-corner output against the per-vertex one (corners.c), provokes every status code and
 * checks that a failing call writes nothing, and, given the case file the Rust tests write, runs
 * the stability suite through the C ABI, skipping cases above max-vertices when given (for slow
 * memory checkers).
 * Prints one line per failed check, then "N passed, M failed".
 */
#include "abi.h"
#include "cases.h"
#include "check.h"
#include "corners.h"
#include "split.h"
#include "fixture.h"
#include "listing.h"
#include "meshes.h"
#include "tbasis.h"

#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------------------------------------
 * Interleaved layouts
 */

/* An engine's vertex record. Packed back to back without the struct's tail padding it is 55
   bytes, an odd stride, so almost every float in the array is misaligned. */
struct Vertex {
    float pos[3];
    float pad0;
    float normal[3];
    float uv[2];
    float tangent[4];
    char pad1[3];
};

#define NO_FIELD ((size_t)-1)

/* Byte offsets of each attribute in a record of `stride` bytes. */
typedef struct layout {
    size_t stride, position, normal, texcoord, tangent, bitangent;
} layout;

static const layout VERTEX_LAYOUT = {
    offsetof(struct Vertex, pad1) + sizeof(((struct Vertex *)0)->pad1),
    offsetof(struct Vertex, pos),
    offsetof(struct Vertex, normal),
    offsetof(struct Vertex, uv),
    offsetof(struct Vertex, tangent),
    NO_FIELD,
};

/* 61-byte records: uv, one spare byte, tangent, position, bitangent, normal. */
static const layout STABILITY_LAYOUT = {61, 25, 49, 0, 9, 37};

typedef struct interleaved {
    const layout *layout;
    size_t count;
    size_t size;                /* bytes in allocation */
    unsigned char *allocation;  /* count records after one spare byte */
    unsigned char *base;        /* allocation + 1, so the records start misaligned */
} interleaved;

static void scatter(const interleaved *v, unsigned char *bytes, size_t offset, size_t floats, const float *values)
{
    size_t i;
    for (i = 0; i < v->count; i++)
        memcpy(bytes + 1 + i * v->layout->stride + offset, values + i * floats, floats * sizeof(float));
}

static void gather(const interleaved *v, size_t offset, size_t floats, float *values)
{
    size_t i;
    for (i = 0; i < v->count; i++)
        memcpy(values + i * floats, v->base + i * v->layout->stride + offset, floats * sizeof(float));
}

/* Packs the attributes into records; every other byte holds the sentinel pattern. */
static int interleave(interleaved *v, const layout *l, size_t count, const float *positions, const float *normals,
                      const float *texcoords)
{
    v->layout = l;
    v->count = count;
    v->size = count * l->stride + 2;
    v->allocation = malloc(v->size);
    if (v->allocation == NULL)
        return -1;
    v->base = v->allocation + 1;
    sentinel_fill(v->allocation, v->size);
    scatter(v, v->allocation, l->position, 3, positions);
    scatter(v, v->allocation, l->normal, 3, normals);
    if (texcoords != NULL)
        scatter(v, v->allocation, l->texcoord, 2, texcoords);
    return 0;
}

static tbasis_mesh interleaved_mesh(const interleaved *v, int has_texcoords, const void *indices,
                                    size_t index_count, uint32_t index_type)
{
    tbasis_mesh m;
    memset(&m, 0, sizeof m);
    m.vertex_count = v->count;
    m.positions = v->base + v->layout->position;
    m.positions_stride = v->layout->stride;
    m.normals = v->base + v->layout->normal;
    m.normals_stride = v->layout->stride;
    m.texcoords = has_texcoords ? v->base + v->layout->texcoord : NULL;
    m.texcoords_stride = v->layout->stride;
    m.indices = indices;
    m.index_count = index_count;
    m.index_type = index_type;
    return m;
}

static tbasis_output interleaved_output(const interleaved *v)
{
    tbasis_output o;
    memset(&o, 0, sizeof o);
    o.tangents = v->base + v->layout->tangent;
    o.tangents_stride = v->layout->stride;
    if (v->layout->bitangent != NO_FIELD) {
        o.bitangents = v->base + v->layout->bitangent;
        o.bitangents_stride = v->layout->stride;
    }
    return o;
}

/* Checks that a call which wrote `tangents` (and `bitangents` when the layout has that field) left
   every other byte of the buffer as it was in `before`. */
static void check_only_outputs_written(const char *what, const interleaved *v, const unsigned char *before,
                                       const float *tangents, const float *bitangents)
{
    unsigned char *expected = malloc(v->size);
    if (!check(expected != NULL, "%s: out of memory", what))
        return;
    memcpy(expected, before, v->size);
    scatter(v, expected, v->layout->tangent, 4, tangents);
    if (v->layout->bitangent != NO_FIELD)
        scatter(v, expected, v->layout->bitangent, 3, bitangents);
    check(memcmp(expected, v->allocation, v->size) == 0, "%s: bytes outside the output fields changed", what);
    free(expected);
}

/* ---------------------------------------------------------------------------------------------
 * Shared call helpers
 */

static tbasis_options policy_options(uint32_t policy)
{
    tbasis_options o;
    memset(&o, 0, sizeof o);
    o.method = TBASIS_METHOD_LENGYEL;
    o.degenerate_policy = policy;
    return o;
}

static long run_listing(const test_mesh *m, uint32_t index_type, float *tangents)
{
    switch (index_type) {
    case TBASIS_INDEX_U16:
        return listing_tangents_u16(m->vertex_count, m->positions, m->normals, m->texcoords, m->triangle_count,
                                    m->indices16, tangents);
    case TBASIS_INDEX_U32:
        return listing_tangents_u32(m->vertex_count, m->positions, m->normals, m->texcoords, m->triangle_count,
                                    m->indices32, tangents);
    default:
        return listing_tangents_unindexed(m->vertex_count, m->positions, m->normals, m->texcoords, tangents);
    }
}

/* One check over all vertices: frame_problem, or with `raw_normal` the LEGACY bitangent rule
   b = w * cross(n, t) with the normal as given. */
static void check_frames(const char *what, size_t count, const float *normals, const float *tangents,
                         const float *bitangents, int raw_normal)
{
    size_t i, bad = 0, first = 0;
    const char *first_problem = NULL;
    for (i = 0; i < count; i++) {
        const char *problem;
        if (raw_normal) {
            double n[3];
            n[0] = normals[3 * i];
            n[1] = normals[3 * i + 1];
            n[2] = normals[3 * i + 2];
            problem = bitangent_problem(n, tangents + 4 * i, bitangents + 3 * i, 1e-6);
        } else {
            problem = frame_problem(normals + 3 * i, tangents + 4 * i, bitangents + 3 * i);
        }
        if (problem != NULL && bad++ == 0) {
            first = i;
            first_problem = problem;
        }
    }
    if (bad == 0) {
        check(1, "%s", what);
        return;
    }
    check(0, "%s: %zu of %zu vertices wrong; vertex %zu: %s (t = %g %g %g %g, b = %g %g %g, n = %g %g %g)", what, bad,
          count, first, first_problem, tangents[4 * first], tangents[4 * first + 1], tangents[4 * first + 2],
          tangents[4 * first + 3], bitangents[3 * first], bitangents[3 * first + 1], bitangents[3 * first + 2],
          normals[3 * first], normals[3 * first + 1], normals[3 * first + 2]);
}

/* ---------------------------------------------------------------------------------------------
 * Version and status strings
 */

static void test_version_and_strings(void)
{
    const char *strings[LAST_STATUS + 1];
    const tbasis_status unknown[] = {LAST_STATUS + 1, 1000, UINT32_MAX};
    tbasis_status s;
    size_t k;

    check(tbasis_version() == TBASIS_VERSION, "tbasis_version() is %lu, header says %lu", (unsigned long)tbasis_version(),
          (unsigned long)TBASIS_VERSION);
    check(TBASIS_VERSION == TBASIS_VERSION_MAJOR * 1000000 + TBASIS_VERSION_MINOR * 1000 + TBASIS_VERSION_PATCH &&
              TBASIS_VERSION_MINOR < 1000 && TBASIS_VERSION_PATCH < 1000,
          "TBASIS_VERSION disagrees with the MAJOR/MINOR/PATCH macros");

    for (s = 0; s <= LAST_STATUS; s++) {
        strings[s] = tbasis_status_string(s);
        if (!check(strings[s] != NULL && strings[s][0] != '\0', "tbasis_status_string(%u) is NULL or empty",
                   (unsigned)s))
            continue;
        for (k = 0; k < s; k++)
            if (strings[k] != NULL)
                check(strcmp(strings[k], strings[s]) != 0, "status %u and %u share the string \"%s\"", (unsigned)k,
                      (unsigned)s, strings[s]);
    }
    for (k = 0; k < sizeof unknown / sizeof unknown[0]; k++) {
        const char *text = tbasis_status_string(unknown[k]);
        if (!check(text != NULL && text[0] != '\0', "tbasis_status_string(%lu) is NULL or empty",
                   (unsigned long)unknown[k]))
            continue;
        for (s = 0; s <= LAST_STATUS; s++)
            if (strings[s] != NULL)
                check(strcmp(strings[s], text) != 0, "unknown status %lu reads like status %u: \"%s\"",
                      (unsigned long)unknown[k], (unsigned)s, text);
    }
}

/* ---------------------------------------------------------------------------------------------
 * LEGACY: bit for bit against the listing
 */

static long exact_results;   /* vertex results of LEGACY calls found bit-identical to the listing */
static long exact_vertices;  /* distinct vertices among them, summed over mesh forms */
static long nonfinite_floats; /* inf/NaN floats the listing writes for those vertices */

static void test_legacy_interleaved(const char *name, const test_mesh *m, uint32_t index_type, const float *reference)
{
    char what[256];
    size_t n = (size_t)m->vertex_count;
    interleaved v;
    unsigned char *before;
    float *tangents = calloc(4 * n + 1, sizeof(float));
    tbasis_options options = policy_options(TBASIS_DEGENERATE_LEGACY);
    tbasis_mesh desc;
    tbasis_output output;

    snprintf(what, sizeof what, "%s: interleaved struct Vertex, stride %zu, misaligned", name, VERTEX_LAYOUT.stride);
    if (!check(tangents != NULL && interleave(&v, &VERTEX_LAYOUT, n, m->positions, m->normals, m->texcoords) == 0,
               "%s: out of memory", what)) {
        free(tangents);
        return;
    }
    before = malloc(v.size);
    if (check(before != NULL, "%s: out of memory", what)) {
        memcpy(before, v.allocation, v.size);
        desc = interleaved_mesh(&v, 1, mesh_indices(m, index_type), mesh_description(m, index_type).index_count, index_type);
        output = interleaved_output(&v);
        if (expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK)) {
            gather(&v, VERTEX_LAYOUT.tangent, 4, tangents);
            if (check_float_bits(what, reference, tangents, 4 * n))
                exact_results += (long)n;
            check_only_outputs_written(what, &v, before, tangents, NULL);
        }
    }
    free(before);
    free(v.allocation);
    free(tangents);
}

/* FLIP_V negates t1 and t2, which negates the determinant and tdir exactly and leaves sdir's bits
   alone: the tangent keeps the listing's bits and w flips, except where the handedness dot product
   is zero or NaN (both +1), which happens only at vertices whose tangent is NaN. */
static void test_legacy_flip_v(const char *name, const test_mesh *m, const float *reference)
{
    char what[256];
    size_t n = (size_t)m->vertex_count, i;
    float *tangents = calloc(4 * n + 1, sizeof(float));
    tbasis_mesh desc = mesh_description(m, TBASIS_INDEX_U32);
    tbasis_options options = policy_options(TBASIS_DEGENERATE_LEGACY);
    tbasis_output output;

    snprintf(what, sizeof what, "%s: LEGACY with TBASIS_FLAG_FLIP_V", name);
    if (!check(tangents != NULL, "%s: out of memory", what))
        return;
    memset(&output, 0, sizeof output);
    output.tangents = tangents;
    output.tangents_stride = 16;
    options.flags = TBASIS_FLAG_FLIP_V;
    if (expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK)) {
        for (i = 0; i < n; i++) {
            const float *t = tangents + 4 * i, *r = reference + 4 * i;
            int unflipped_ok = isnan(r[0]) && t[3] == 1.0f && r[3] == 1.0f;
            if (memcmp(t, r, 12) != 0 || !(t[3] == -r[3] || unflipped_ok))
                break;
        }
        if (i == n)
            check(1, "%s", what);
        else
            check(0, "%s: vertex %zu is %g %g %g %g, the listing gives %g %g %g %g", what, i, tangents[4 * i],
                  tangents[4 * i + 1], tangents[4 * i + 2], tangents[4 * i + 3], reference[4 * i],
                  reference[4 * i + 1], reference[4 * i + 2], reference[4 * i + 3]);
    }
    free(tangents);
}

/* Everything LEGACY must reproduce for one mesh in one index form (0: unindexed). */
/* The listing's own types (Lengyel 2001): legacy code that holds its mesh in them swaps one call,
   as the README shows, and gets the listing's bits. */
typedef struct { float x, y, z; } Point3D;
typedef struct { float x, y, z; } Vector3D;
typedef struct { float x, y; } Point2D;
typedef struct { float x, y, z, w; } Vector4D;
typedef struct { unsigned short index[3]; } Triangle;

static void test_legacy_swap(const test_mesh *m, const float *reference)
{
    long vertexCount = m->vertex_count, triangleCount = m->triangle_count;
    size_t n = (size_t)vertexCount;
    Point3D *vertex = malloc(n * sizeof *vertex + 1);
    Vector3D *normal = malloc(n * sizeof *normal + 1);
    Point2D *texcoord = malloc(n * sizeof *texcoord + 1);
    Triangle *triangle = malloc((size_t)triangleCount * sizeof *triangle + 1);
    Vector4D *tangent = calloc(n + 1, sizeof *tangent);
    tbasis_status status;

    if (check(vertex && normal && texcoord && triangle && tangent, "%s: out of memory", m->name)) {
        memcpy(vertex, m->positions, n * sizeof *vertex);
        memcpy(normal, m->normals, n * sizeof *normal);
        memcpy(texcoord, m->texcoords, n * sizeof *texcoord);
        memcpy(triangle, m->indices16, (size_t)triangleCount * sizeof *triangle);
        /* CalculateTangentArray(vertexCount, vertex, normal, texcoord, triangleCount, triangle, tangent); */
        status = tbasis_calculate_tangent_array(vertexCount, &vertex->x, &normal->x, &texcoord->x,
                                                triangleCount, triangle->index, &tangent->x);
        if (expect_status("the listing's types, one call swapped", status, TBASIS_OK) &&
            check_float_bits("the listing's types, one call swapped", reference, &tangent->x, 4 * n))
            exact_results += (long)n;
    }
    free(vertex);
    free(normal);
    free(texcoord);
    free(triangle);
    free(tangent);
}

static void test_legacy_form(const test_mesh *m, uint32_t index_type, int expect_nonfinite)
{
    char name[128], what[256];
    size_t n = (size_t)m->vertex_count;
    float *reference = calloc(4 * n + 1, sizeof(float));
    float *tangents = calloc(4 * n + 1, sizeof(float));
    float *bitangents = calloc(3 * n + 1, sizeof(float));
    tbasis_mesh desc = mesh_description(m, index_type);
    tbasis_options options = policy_options(TBASIS_DEGENERATE_LEGACY);
    tbasis_output output;
    tbasis_report report;
    guarded out;
    long zero_determinants;

    snprintf(name, sizeof name, "%s (%s, %ld vertices)", m->name, index_type_name(index_type), m->vertex_count);
    memset(&out, 0, sizeof out);
    if (!check(reference && tangents && bitangents && guarded_alloc(&out, 16 * n) == 0, "%s: out of memory", name))
        goto done;
    zero_determinants = run_listing(m, index_type, reference);
    if (!check(zero_determinants >= 0, "%s: the listing port could not allocate", name))
        goto done;
    if (expect_nonfinite)
        check(count_nonfinite(reference, 4 * n) > 0, "%s: the listing should write inf/NaN on this mesh", name);
    if (index_type == TBASIS_INDEX_U16) {
        /* The port's own index paths must agree before it can judge the library. */
        listing_tangents_u32(m->vertex_count, m->positions, m->normals, m->texcoords, m->triangle_count, m->indices32,
                             tangents);
        snprintf(what, sizeof what, "%s: listing port u32 vs u16", name);
        check_float_bits(what, reference, tangents, 4 * n);
    }

    /* Packed, inside guard bytes. */
    memset(&output, 0, sizeof output);
    output.tangents = out.inner;
    output.tangents_stride = 16;
    memset(&report, 0x5A, sizeof report);
    snprintf(what, sizeof what, "%s: tbasis_generate LEGACY, packed", name);
    if (expect_status(what, tbasis_generate(&desc, &options, &output, &report), TBASIS_OK)) {
        memcpy(tangents, out.inner, 16 * n);
        if (check_float_bits(what, reference, tangents, 4 * n)) {
            exact_results += (long)n;
            exact_vertices += (long)n;
            nonfinite_floats += (long)count_nonfinite(reference, 4 * n);
        }
        check(guards_intact(&out), "%s: wrote outside the tangent array", what);
        check(report.degenerate_triangles == (size_t)zero_determinants && report.fallback_vertices == 0 &&
                  report.inherited_vertices == 0,
              "%s: report counts %zu degenerate, %zu fallback, %zu inherited; the listing has %ld zero determinants",
              what, report.degenerate_triangles, report.fallback_vertices, report.inherited_vertices,
              zero_determinants);
    }

    /* With bitangents: same tangents, and b = w * cross(n, t). */
    output.tangents = tangents;
    output.bitangents = bitangents;
    output.bitangents_stride = 12;
    memset(tangents, 0, 16 * n);
    snprintf(what, sizeof what, "%s: tbasis_generate LEGACY with bitangents", name);
    if (expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK)) {
        if (check_float_bits(what, reference, tangents, 4 * n))
            exact_results += (long)n;
        snprintf(what, sizeof what, "%s: LEGACY bitangent = w * cross(n, t)", name);
        check_frames(what, n, m->normals, tangents, bitangents, 1);
    }

    test_legacy_interleaved(name, m, index_type, reference);

    if (index_type == TBASIS_INDEX_U16) {
        guarded_reset(&out);
        snprintf(what, sizeof what, "%s: tbasis_calculate_tangent_array", name);
        if (expect_status(what,
                          tbasis_calculate_tangent_array(m->vertex_count, m->positions, m->normals, m->texcoords,
                                                         m->triangle_count, m->indices16, out.inner),
                          TBASIS_OK)) {
            memcpy(tangents, out.inner, 16 * n);
            if (check_float_bits(what, reference, tangents, 4 * n))
                exact_results += (long)n;
            check(guards_intact(&out), "%s: wrote outside the tangent array", what);
        }
        test_legacy_swap(m, reference);
    }
    if (index_type == TBASIS_INDEX_U32)
        test_legacy_flip_v(name, m, reference);

done:
    guarded_free(&out);
    free(reference);
    free(tangents);
    free(bitangents);
}

static void test_legacy(const test_mesh *m, int expect_nonfinite)
{
    test_mesh flat;
    if (m->indices16 != NULL)
        test_legacy_form(m, TBASIS_INDEX_U16, expect_nonfinite);
    test_legacy_form(m, TBASIS_INDEX_U32, expect_nonfinite);
    if (check(mesh_unindexed(&flat, m) == 0, "%s: out of memory", m->name)) {
        test_legacy_form(&flat, 0, expect_nonfinite);
        mesh_free(&flat);
    }
}

/* ---------------------------------------------------------------------------------------------
 * REJECT names the first degenerate triangle; SKIP and LEGACY see the same triangles
 */

static void test_degenerate_triangles(const test_mesh *grid)
{
    const long first = 17, second = 40;
    test_mesh m;
    size_t n;
    guarded tangents, bitangents;
    tbasis_mesh desc;
    tbasis_options options;
    tbasis_output output;
    tbasis_report report;
    float *reference;

    memset(&tangents, 0, sizeof tangents);
    memset(&bitangents, 0, sizeof bitangents);
    if (!check(mesh_unindexed(&m, grid) == 0, "degenerate triangles: out of memory"))
        return;
    /* A third corner on the first corner's UV: s2 = t2 = 0, a zero determinant. */
    memcpy(m.texcoords + 2 * (3 * first + 2), m.texcoords + 2 * (3 * first), 2 * sizeof(float));
    memcpy(m.texcoords + 2 * (3 * second + 2), m.texcoords + 2 * (3 * second), 2 * sizeof(float));
    n = (size_t)m.vertex_count;
    desc = mesh_description(&m, 0);
    reference = calloc(4 * n + 1, sizeof(float));
    if (!check(reference && guarded_alloc(&tangents, 16 * n) == 0 && guarded_alloc(&bitangents, 12 * n) == 0,
               "degenerate triangles: out of memory"))
        goto done;
    memset(&output, 0, sizeof output);
    output.tangents = tangents.inner;
    output.tangents_stride = 16;
    output.bitangents = bitangents.inner;
    output.bitangents_stride = 12;

    options = policy_options(TBASIS_DEGENERATE_REJECT);
    memset(&report, 0x5A, sizeof report);
    expect_status("REJECT on two collapsed UV triangles", tbasis_generate(&desc, &options, &output, &report),
                  TBASIS_ERROR_DEGENERATE_UV);
    check(report.degenerate_triangles == 2 && report.first_degenerate_triangle == (size_t)first &&
              report.failed_triangle == (size_t)first,
          "REJECT report: %zu degenerate, first %zu, failed %zu; expected 2, first %ld", report.degenerate_triangles,
          report.first_degenerate_triangle, report.failed_triangle, first);
    check(guarded_intact(&tangents) && guarded_intact(&bitangents), "REJECT wrote into its outputs");

    options = policy_options(TBASIS_DEGENERATE_SKIP);
    memset(&report, 0x5A, sizeof report);
    if (expect_status("SKIP on two collapsed UV triangles", tbasis_generate(&desc, &options, &output, &report),
                      TBASIS_OK)) {
        check(report.degenerate_triangles == 2 && report.first_degenerate_triangle == (size_t)first &&
                  report.failed_triangle == TBASIS_NO_TRIANGLE,
              "SKIP report: %zu degenerate, first %zu, failed %zu; expected 2, first %ld, none failed",
              report.degenerate_triangles, report.first_degenerate_triangle, report.failed_triangle, first);
        check_frames("SKIP on two collapsed UV triangles: frames", n, m.normals, tangents.inner, bitangents.inner, 0);
    }

    options = policy_options(TBASIS_DEGENERATE_LEGACY);
    output.bitangents = NULL;
    memset(&report, 0x5A, sizeof report);
    check(listing_tangents_unindexed(m.vertex_count, m.positions, m.normals, m.texcoords, reference) == 2,
          "the listing port should count two zero determinants");
    if (expect_status("LEGACY on two collapsed UV triangles", tbasis_generate(&desc, &options, &output, &report),
                      TBASIS_OK)) {
        check_float_bits("LEGACY on two collapsed UV triangles", reference, tangents.inner, 4 * n);
        check(report.degenerate_triangles == 2 && report.first_degenerate_triangle == (size_t)first,
              "LEGACY report: %zu degenerate, first %zu; expected 2, first %ld", report.degenerate_triangles,
              report.first_degenerate_triangle, first);
    }
done:
    guarded_free(&tangents);
    guarded_free(&bitangents);
    free(reference);
    mesh_free(&m);
}

/* ---------------------------------------------------------------------------------------------
 * Caller scratch
 */

static void test_scratch(const test_mesh *m)
{
    size_t n = (size_t)m->vertex_count, needed, exact, offset;
    const uint32_t policies[] = {TBASIS_DEGENERATE_LEGACY, TBASIS_DEGENERATE_INHERIT};
    tbasis_mesh desc = mesh_description(m, TBASIS_INDEX_U32), huge = desc, empty = desc;
    const size_t corners = desc.index_count, inherit = n * 37 + corners * 4 + 3;
    tbasis_options options;
    tbasis_output output;
    unsigned char *scratch;
    float *plain = calloc(4 * n + 1, sizeof(float));
    guarded out;
    size_t p;

    memset(&out, 0, sizeof out);
    /* The default policy, INHERIT, adds its adjacency: 8 bytes per vertex and 4 per corner. */
    needed = tbasis_scratch_size(&desc, NULL);
    check(needed == inherit, "tbasis_scratch_size is %zu for %zu vertices and %zu corners, expected %zu", needed, n,
          corners, inherit);
    options = policy_options(TBASIS_DEGENERATE_SKIP);
    check(tbasis_scratch_size(&desc, &options) == n * 29 + 3, "tbasis_scratch_size with SKIP is %zu, expected %zu",
          tbasis_scratch_size(&desc, &options), n * 29 + 3);
    empty.vertex_count = 0;
    check(tbasis_scratch_size(&empty, NULL) == 0, "tbasis_scratch_size of an empty mesh is not 0");
    check(tbasis_scratch_size(NULL, NULL) == SIZE_MAX, "tbasis_scratch_size(NULL) is not SIZE_MAX");
    huge.vertex_count = SIZE_MAX / 29 + 1;
    check(tbasis_scratch_size(&huge, NULL) == SIZE_MAX, "tbasis_scratch_size does not report overflow as SIZE_MAX");

    scratch = malloc(needed + 4);
    if (!check(plain && scratch && guarded_alloc(&out, 16 * n) == 0, "scratch: out of memory"))
        goto done;
    memset(&output, 0, sizeof output);
    output.tangents = out.inner;
    output.tangents_stride = 16;
    for (p = 0; p < sizeof policies / sizeof policies[0]; p++) {
        options = policy_options(policies[p]);
        if (!expect_status("scratch: call without scratch", tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK))
            continue;
        memcpy(plain, out.inner, 16 * n);
        guarded_reset(&out);
        options.threads = 4;
        if (expect_status("scratch: call with threads = 4", tbasis_generate(&desc, &options, &output, NULL),
                          TBASIS_OK))
            check_float_bits("threads = 4 vs the calling thread only", plain, out.inner, 4 * n);
        options.threads = 0;
        exact = tbasis_scratch_size(&desc, &options);
        /* Every alignment of the caller's bytes must do with exactly the documented size. */
        for (offset = 0; offset < 4; offset++) {
            char what[128];
            guarded_reset(&out);
            options.scratch = scratch + offset;
            options.scratch_size = exact;
            snprintf(what, sizeof what, "policy %u, scratch of exactly %zu bytes at offset %zu", (unsigned)policies[p],
                     exact, offset);
            if (expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK))
                check_float_bits(what, plain, out.inner, 4 * n);

            guarded_reset(&out);
            options.scratch_size = exact - 1;
            snprintf(what, sizeof what, "policy %u, scratch one byte short at offset %zu", (unsigned)policies[p],
                     offset);
            expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_ERROR_SCRATCH_TOO_SMALL);
            check(guarded_intact(&out), "%s: the output was written", what);
        }
    }
done:
    guarded_free(&out);
    free(scratch);
    free(plain);
}

/* ---------------------------------------------------------------------------------------------
 * Out of memory, without touching memory
 */

static void test_out_of_memory(void)
{
#if SIZE_MAX > 0xFFFFFFFFu
    /* One real 48-byte record (position, normal, uv, tangent) described as the first of 2^57:
       every span stays below PTRDIFF_MAX, so the description passes validation, but the scratch
       the call must then allocate (28 bytes a vertex, about 4e18 bytes) cannot exist. Validation
       is arithmetic and the allocation comes before any read, so no byte of the claimed arrays
       beyond the record is ever touched. With zero indices there are no triangles to read. */
    unsigned char record[48];
    uint16_t no_indices[1] = {0};
    tbasis_mesh desc;
    tbasis_output output;

    sentinel_fill(record, sizeof record);
    memset(&desc, 0, sizeof desc);
    desc.vertex_count = (size_t)1 << 57;
    desc.positions = record;
    desc.positions_stride = 48;
    desc.normals = record + 12;
    desc.normals_stride = 48;
    desc.texcoords = record + 24;
    desc.texcoords_stride = 48;
    desc.indices = no_indices;
    desc.index_count = 0;
    desc.index_type = TBASIS_INDEX_U16;
    memset(&output, 0, sizeof output);
    output.tangents = record + 32;
    output.tangents_stride = 48;
    expect_status("2^57 vertices described in place", tbasis_generate(&desc, NULL, &output, NULL),
                  TBASIS_ERROR_OUT_OF_MEMORY);
    check(sentinel_intact(record, sizeof record), "out of memory: the record was written");
#else
    printf("note: TBASIS_ERROR_OUT_OF_MEMORY is provoked only where size_t has 64 bits\n");
    provoked[TBASIS_ERROR_OUT_OF_MEMORY] = 1;
#endif
}

/* ---------------------------------------------------------------------------------------------
 * Several workers (one per 16384 triangles at most) give the calling thread's bits, per vertex
 * and per corner, for every method, and for LEGACY
 */

static void test_threads(const test_mesh *m)
{
    const tbasis_mesh desc = mesh_description(m, TBASIS_INDEX_U32);
    const size_t vertices = desc.vertex_count, corners = desc.index_count;
    float *results[2];
    uint32_t method;
    int k, t;
    results[0] = calloc(4 * corners + 4 * vertices, sizeof(float));
    results[1] = calloc(4 * corners + 4 * vertices, sizeof(float));
    if (!check(results[0] && results[1], "threads: out of memory") ||
        !check(corners / 3 >= 2 * 16384, "threads: %zu triangles make one worker", corners / 3))
        goto done;
    /* Methods LENGYEL to MIKKTSPACE with policy INHERIT, then LENGYEL with LEGACY (the loop's
       value past MIKKTSPACE). */
    for (method = TBASIS_METHOD_LENGYEL; method <= TBASIS_METHOD_MIKKTSPACE + 1; method++) {
        int legacy = method > TBASIS_METHOD_MIKKTSPACE;
        tbasis_options options = policy_options(legacy ? TBASIS_DEGENERATE_LEGACY : TBASIS_DEGENERATE_INHERIT);
        char what[96];
        if (!legacy)
            options.method = method;
        for (k = 0; k < 2; k++) {
            tbasis_output output;
            memset(&output, 0, sizeof output);
            output.tangents = results[k];
            output.tangents_stride = 16;
            options.threads = (uint32_t)(k + 1);
            snprintf(what, sizeof what, "threads: method %u%s, %d thread(s)", (unsigned)options.method,
                     legacy ? " LEGACY" : "", k + 1);
            t = expect_status(what, tbasis_generate(&desc, &options, &output, NULL), TBASIS_OK);
            t = t && expect_status(what, tbasis_generate_corners(&desc, &options, results[k] + 4 * vertices, 16, NULL),
                                   TBASIS_OK);
            if (!t)
                goto done;
        }
        snprintf(what, sizeof what, "threads: method %u%s, 2 threads against 1", (unsigned)options.method,
                 legacy ? " LEGACY" : "");
        check_float_bits(what, results[0], results[1], 4 * vertices + 4 * corners);
    }
done:
    free(results[0]);
    free(results[1]);
}

/* ---------------------------------------------------------------------------------------------
 * Every error status, and nothing written when one is returned
 */

/* Runs the fixture's call; on an error every byte of the arena must be as before, and the report
   too but on the two refusals that fill it. */
static void expect(fixture *f, const char *what, tbasis_status want)
{
    tbasis_status got;
    tbasis_report report, untouched;
    memcpy(&f->before, &f->memory, sizeof f->memory);
    memset(&report, 0x5A, sizeof report);
    memset(&untouched, 0x5A, sizeof untouched);
    got = tbasis_generate(f->mesh_arg, &f->options, f->output_arg, &report);
    expect_status(what, got, want);
    if (want != TBASIS_OK)
        check(memcmp(&f->before, &f->memory, sizeof f->memory) == 0, "%s: a byte was written", what);
    if (want != TBASIS_OK && want != TBASIS_ERROR_INDEX_OUT_OF_RANGE && want != TBASIS_ERROR_DEGENERATE_UV)
        check(memcmp(&report, &untouched, sizeof report) == 0, "%s: the report was written", what);
}

/* The same for the listing's signature over the fixture's packed buffers. */
static void expect_legacy(fixture *f, const char *what, tbasis_status want, long vertex_count, const void *vertex,
                          long triangle_count, const void *triangle, void *tangent)
{
    const void *normal = f->memory.normals, *texcoord = f->memory.texcoords;
    tbasis_status got;
    memcpy(&f->before, &f->memory, sizeof f->memory);
    got = tbasis_calculate_tangent_array(vertex_count, vertex, normal, texcoord, triangle_count, triangle, tangent);
    expect_status(what, got, want);
    if (want != TBASIS_OK)
        check(memcmp(&f->before, &f->memory, sizeof f->memory) == 0, "%s: a byte was written", what);
}

static void test_statuses(fixture *f)
{
    const long v = f->source->vertex_count, t = f->source->triangle_count;
    /* The fixture's policy is INHERIT: 37 bytes per vertex and 4 per corner. */
    const size_t n = (size_t)v, needed = n * 37 + 12 * (size_t)t + 3;
    arena *a = &f->memory;
    uint16_t index16;
    uint32_t index32;

    /* The baseline must succeed, or the errors below would prove nothing. */
    fixture_reset(f);
    expect(f, "fixture baseline", TBASIS_OK);
    check(memcmp(f->before.tangents + GUARD_BYTES, a->tangents + GUARD_BYTES, 16 * n) != 0 &&
              memcmp(f->before.bitangents + GUARD_BYTES, a->bitangents + GUARD_BYTES, 12 * n) != 0,
          "fixture baseline: the outputs were not written");
    check(memcmp(f->before.tangents, a->tangents, GUARD_BYTES) == 0 &&
              memcmp(f->before.tangents + GUARD_BYTES + 16 * n, a->tangents + GUARD_BYTES + 16 * n,
                     FIX_BUFFER - GUARD_BYTES - 16 * n) == 0,
          "fixture baseline: bytes around the tangents were written");
    fixture_reset(f);
    f->mesh.texcoords = NULL;
    expect(f, "no texcoords under INHERIT (fallback frames)", TBASIS_OK);

    fixture_reset(f);
    f->mesh_arg = NULL;
    expect(f, "NULL mesh", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->output_arg = NULL;
    expect(f, "NULL output", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->output.tangents = NULL;
    expect(f, "NULL tangents", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->mesh.positions = NULL;
    expect(f, "NULL positions", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->mesh.normals = NULL;
    expect(f, "NULL normals", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->mesh.indices = NULL;
    expect(f, "NULL indices with a nonzero index_count", TBASIS_ERROR_NULL_POINTER);
    fixture_reset(f);
    f->mesh.texcoords = NULL;
    f->options.degenerate_policy = TBASIS_DEGENERATE_LEGACY;
    expect(f, "NULL texcoords under LEGACY", TBASIS_ERROR_NULL_POINTER);

    fixture_reset(f);
    f->mesh.positions_stride = 11;
    expect(f, "positions stride 11", TBASIS_ERROR_INVALID_STRIDE);
    fixture_reset(f);
    f->mesh.normals_stride = 0;
    expect(f, "normals stride 0", TBASIS_ERROR_INVALID_STRIDE);
    fixture_reset(f);
    f->mesh.texcoords_stride = 7;
    expect(f, "texcoords stride 7", TBASIS_ERROR_INVALID_STRIDE);
    fixture_reset(f);
    f->output.tangents_stride = 12;
    expect(f, "tangents stride 12", TBASIS_ERROR_INVALID_STRIDE);
    fixture_reset(f);
    f->output.bitangents_stride = 11;
    expect(f, "bitangents stride 11", TBASIS_ERROR_INVALID_STRIDE);

    fixture_reset(f);
    f->mesh.index_count -= 1;
    expect(f, "index_count not a multiple of 3", TBASIS_ERROR_INVALID_INDEX_COUNT);
    fixture_reset(f);
    f->mesh.indices = NULL;
    f->mesh.index_count = 0;
    f->mesh.vertex_count = n - 2;
    expect(f, "unindexed vertex_count not a multiple of 3", TBASIS_ERROR_INVALID_INDEX_COUNT);

    /* Out-of-range indices in the last triangle: every earlier triangle has been summed by then. */
    fixture_reset(f);
    index16 = (uint16_t)n;
    memcpy(a->indices + 2 * (3 * t - 1), &index16, sizeof index16);
    expect(f, "u16 index == vertex_count in the last triangle", TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    {
        /* The report names the triangle at fault, the only thing filled. */
        tbasis_report report;
        memset(&report, 0x5A, sizeof report);
        tbasis_generate(f->mesh_arg, &f->options, f->output_arg, &report);
        check(report.failed_triangle == (size_t)(t - 1) && report.degenerate_triangles == 0 &&
                  report.first_degenerate_triangle == TBASIS_NO_TRIANGLE,
              "index out of range: report names triangle %zu, expected %ld", report.failed_triangle, t - 1);
    }
    fixture_reset(f);
    fixture_use_u32(f);
    expect(f, "fixture baseline with u32 indices", TBASIS_OK);
    fixture_reset(f);
    fixture_use_u32(f);
    index32 = UINT32_MAX;
    memcpy(a->indices + 4 * (3 * t - 2), &index32, sizeof index32);
    expect(f, "u32 index 0xFFFFFFFF", TBASIS_ERROR_INDEX_OUT_OF_RANGE);

    fixture_reset(f);
    f->mesh.indices = NULL;
    f->mesh.index_count = 0;
    f->mesh.index_type = 77;
    expect(f, "unindexed, index_type ignored", TBASIS_OK);
    fixture_reset(f);
    f->mesh.index_type = 0;
    expect(f, "index_type 0", TBASIS_ERROR_INVALID_INDEX_TYPE);
    fixture_reset(f);
    f->mesh.index_type = 3;
    expect(f, "index_type 3", TBASIS_ERROR_INVALID_INDEX_TYPE);

    fixture_reset(f);
    f->options.method = TBASIS_METHOD_MIKKTSPACE + 1;
    expect(f, "method one past the last", TBASIS_ERROR_UNKNOWN_METHOD);
    fixture_reset(f);
    f->options.method = UINT32_MAX;
    expect(f, "method 0xFFFFFFFF", TBASIS_ERROR_UNKNOWN_METHOD);
    fixture_reset(f);
    f->options.method = TBASIS_METHOD_ANGLE;
    f->options.degenerate_policy = TBASIS_DEGENERATE_LEGACY;
    expect(f, "policy LEGACY with method ANGLE", TBASIS_ERROR_NO_LEGACY_FORM);
    fixture_reset(f);
    f->mesh.vertex_count = 0;
    f->mesh.index_count = 0;
    f->mesh.positions = NULL;
    f->mesh.normals = NULL;
    f->mesh.texcoords = NULL;
    f->mesh.indices = NULL;
    f->output.tangents = NULL;
    f->output.bitangents = NULL;
    expect(f, "an empty mesh with every buffer NULL", TBASIS_OK);
    fixture_reset(f);
    f->options.degenerate_policy = 5;
    expect(f, "policy 5", TBASIS_ERROR_UNKNOWN_POLICY);
    fixture_reset(f);
    f->options.degenerate_policy = UINT32_MAX;
    expect(f, "policy 0xFFFFFFFF", TBASIS_ERROR_UNKNOWN_POLICY);
    fixture_reset(f);
    f->options.flags = 2;
    expect(f, "flag bit 1", TBASIS_ERROR_UNKNOWN_FLAGS);
    fixture_reset(f);
    f->options.flags = TBASIS_FLAG_FLIP_V | 0x80000000u;
    expect(f, "flag bit 31", TBASIS_ERROR_UNKNOWN_FLAGS);

    fixture_reset(f);
    f->mesh.vertex_count = SIZE_MAX / 8;
    f->mesh.positions_stride = 64;
    expect(f, "vertex_count SIZE_MAX/8 with stride 64", TBASIS_ERROR_SIZE_OVERFLOW);
    fixture_reset(f);
    f->output.tangents_stride = SIZE_MAX / 16;
    expect(f, "tangents stride SIZE_MAX/16", TBASIS_ERROR_SIZE_OVERFLOW);
    fixture_reset(f);
    /* Never dereferenced: the range check must fail first. */
    f->mesh.normals = (const void *)(UINTPTR_MAX - 64);
    expect(f, "normals ending past the top of the address space", TBASIS_ERROR_SIZE_OVERFLOW);

    fixture_reset(f);
    f->output.tangents = a->positions;
    expect(f, "tangents on top of positions", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->output.tangents = a->positions + 8;
    expect(f, "tangents sharing 4 bytes of each position", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->output.tangents = a->normals + 12 * (n - 1);
    expect(f, "tangent 0 on the last normal", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->output.tangents = a->texcoords + 4;
    expect(f, "tangents on top of texcoords", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->output.bitangents = a->indices + 2 * (3 * (size_t)t - 1);
    expect(f, "bitangent 0 on the last index", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->output.bitangents = a->tangents + GUARD_BYTES + 4;
    expect(f, "bitangents inside the tangents", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->options.scratch = a->scratch;
    f->options.scratch_size = needed;
    f->output.tangents = a->scratch + needed - 1;
    expect(f, "tangent 0 on the last scratch byte", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->options.scratch = a->bitangents + GUARD_BYTES + 12 * n - 1;
    f->options.scratch_size = needed;
    f->output.bitangents = a->bitangents + GUARD_BYTES;
    expect(f, "scratch starting on the last bitangent byte", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->options.scratch = a->positions;
    f->options.scratch_size = needed;
    expect(f, "scratch on top of positions", TBASIS_ERROR_OVERLAP);
    fixture_reset(f);
    f->options.scratch = a->scratch;
    f->options.scratch_size = needed;
    expect(f, "fixture with caller scratch", TBASIS_OK);

    fixture_reset(f);
    f->options.scratch = a->scratch;
    f->options.scratch_size = needed - 1;
    expect(f, "scratch one byte short", TBASIS_ERROR_SCRATCH_TOO_SMALL);
    fixture_reset(f);
    f->options.scratch = a->scratch;
    f->options.scratch_size = 0;
    expect(f, "scratch of size 0", TBASIS_ERROR_SCRATCH_TOO_SMALL);

    fixture_reset(f);
    f->options.degenerate_threshold = -1.0f;
    expect(f, "threshold -1", TBASIS_ERROR_INVALID_THRESHOLD);
    fixture_reset(f);
    f->options.degenerate_threshold = NAN;
    expect(f, "threshold NaN", TBASIS_ERROR_INVALID_THRESHOLD);
    fixture_reset(f);
    f->options.degenerate_threshold = INFINITY;
    expect(f, "threshold +inf", TBASIS_ERROR_INVALID_THRESHOLD);
    fixture_reset(f);
    f->options.degenerate_threshold = 0.5f;
    expect(f, "threshold 0.5", TBASIS_OK);

    /* The listing's signature. */
    fixture_reset(f);
    expect_legacy(f, "legacy signature baseline", TBASIS_OK, v, a->positions, t, a->indices, a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, vertex_count -1", TBASIS_ERROR_INVALID_COUNT, -1, a->positions, t, a->indices,
                  a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, triangle_count -1", TBASIS_ERROR_INVALID_COUNT, v, a->positions, -1,
                  a->indices, a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, NULL vertex", TBASIS_ERROR_NULL_POINTER, v, NULL, t, a->indices,
                  a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, NULL tangent", TBASIS_ERROR_NULL_POINTER, v, a->positions, t, a->indices,
                  NULL);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, NULL triangle", TBASIS_ERROR_NULL_POINTER, v, a->positions, t, NULL,
                  a->tangents + GUARD_BYTES);
    fixture_reset(f);
    index16 = (uint16_t)n;
    memcpy(a->indices + 2 * (3 * t - 1), &index16, sizeof index16);
    expect_legacy(f, "legacy signature, index == vertex_count", TBASIS_ERROR_INDEX_OUT_OF_RANGE, v, a->positions, t,
                  a->indices, a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, vertex_count LONG_MAX", TBASIS_ERROR_SIZE_OVERFLOW, LONG_MAX, a->positions, t,
                  a->indices, a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, triangle_count LONG_MAX", TBASIS_ERROR_SIZE_OVERFLOW, v, a->positions,
                  LONG_MAX, a->indices, a->tangents + GUARD_BYTES);
    fixture_reset(f);
    expect_legacy(f, "legacy signature, tangent on top of vertex", TBASIS_ERROR_OVERLAP, v, a->positions, t,
                  a->indices, a->positions);
}

/* ---------------------------------------------------------------------------------------------
 * Stability suite through the C ABI
 */

static const uint32_t CASE_POLICY[CASE_POLICIES] = {TBASIS_DEGENERATE_SKIP, TBASIS_DEGENERATE_INHERIT,
                                                    TBASIS_DEGENERATE_REJECT};

/* The file's reports are for the default method; with another method only the fields that depend
   on the triangles alone (not on how tangents are weighted) must match. */
static void check_report(const char *what, const tbasis_report *r, const uint64_t expected[REPORT_FIELDS],
                         int every_field)
{
    static const int weight_dependent[REPORT_FIELDS] = {0, 0, 1, 0, 0, 1};
    const uint64_t got[REPORT_FIELDS] = {r->degenerate_triangles,  r->first_degenerate_triangle,
                                         r->fallback_vertices,     r->mirrored_vertices,
                                         r->unreferenced_vertices, r->inherited_vertices};
    static const char *const names[REPORT_FIELDS] = {"degenerate_triangles",  "first_degenerate_triangle",
                                                     "fallback_vertices",     "mirrored_vertices",
                                                     "unreferenced_vertices", "inherited_vertices"};
    int f;
    for (f = 0; f < REPORT_FIELDS; f++)
        if (every_field || !weight_dependent[f])
            check(got[f] == expected[f], "%s: report %s is %llu, expected %llu", what, names[f],
              (unsigned long long)got[f], (unsigned long long)expected[f]);
}

/* abnormal_normals counts normals that are zero, not finite, or off unit length by more than 1e-3;
   lengths within 1e-6 of that boundary may go either way. */
static void check_abnormal_normals(const char *what, const stability_case *c, size_t reported)
{
    size_t definite = 0, borderline = 0, i;
    for (i = 0; i < (size_t)c->vertex_count; i++) {
        const float *n = c->normals + 3 * i;
        double length = sqrt((double)n[0] * n[0] + (double)n[1] * n[1] + (double)n[2] * n[2]);
        double off = fabs(length - 1.0);
        if (!isfinite(length) || length == 0.0 || off > 1e-3 + 1e-6)
            definite++;
        else if (off >= 1e-3 - 1e-6)
            borderline++;
    }
    check(reported >= definite && reported <= definite + borderline,
          "%s: report abnormal_normals is %zu, expected %zu (plus up to %zu on the 1e-3 boundary)", what, reported,
          definite, borderline);
}

/* One case under one policy and method, with packed arrays and then interleaved records. */
static void test_stability_case(const stability_case *c, int p, uint32_t method)
{
    char what[256];
    const size_t n = (size_t)c->vertex_count;
    const int rejects = CASE_POLICY[p] == TBASIS_DEGENERATE_REJECT && c->expected[p][0] > 0;
    const tbasis_status want = rejects ? TBASIS_ERROR_DEGENERATE_UV : TBASIS_OK;
    const int every_field = method == TBASIS_METHOD_LENGYEL;
    tbasis_options options = policy_options(CASE_POLICY[p]);
    tbasis_mesh desc;
    tbasis_output output;
    tbasis_report report;
    guarded tangents, bitangents;
    interleaved v;
    unsigned char *before = NULL;
    float *gathered_t = calloc(4 * n + 1, sizeof(float)), *gathered_b = calloc(3 * n + 1, sizeof(float));

    options.method = method;
    memset(&v, 0, sizeof v);
    memset(&tangents, 0, sizeof tangents);
    memset(&bitangents, 0, sizeof bitangents);
    snprintf(what, sizeof what, "case %s, policy %u, method %u, packed", c->name, (unsigned)CASE_POLICY[p],
             (unsigned)method);
    if (!check(gathered_t && gathered_b && guarded_alloc(&tangents, 16 * n) == 0 &&
                   guarded_alloc(&bitangents, 12 * n) == 0,
               "%s: out of memory", what))
        goto done;

    memset(&desc, 0, sizeof desc);
    desc.vertex_count = n;
    desc.positions = c->positions;
    desc.positions_stride = 12;
    desc.normals = c->normals;
    desc.normals_stride = 12;
    desc.texcoords = c->texcoords;
    desc.texcoords_stride = 8;
    desc.indices = c->indices;
    desc.index_count = c->indices ? (size_t)c->index_count : 0;
    desc.index_type = TBASIS_INDEX_U32;
    memset(&output, 0, sizeof output);
    output.tangents = tangents.inner;
    output.tangents_stride = 16;
    output.bitangents = bitangents.inner;
    output.bitangents_stride = 12;
    memset(&report, 0x5A, sizeof report);
    if (!expect_status(what, tbasis_generate(&desc, &options, &output, &report), want))
        goto done;
    check_report(what, &report, c->expected[p], every_field);
    if (rejects) {
        check(guarded_intact(&tangents) && guarded_intact(&bitangents), "%s: a refused call wrote output", what);
    } else {
        check(guards_intact(&tangents) && guards_intact(&bitangents), "%s: wrote outside its outputs", what);
        check_frames(what, n, c->normals, tangents.inner, bitangents.inner, 0);
        check_abnormal_normals(what, c, report.abnormal_normals);
    }

    snprintf(what, sizeof what, "case %s, policy %u, method %u, interleaved stride %zu", c->name,
             (unsigned)CASE_POLICY[p], (unsigned)method, STABILITY_LAYOUT.stride);
    if (!check(interleave(&v, &STABILITY_LAYOUT, n, c->positions, c->normals, c->texcoords) == 0 &&
                   (before = malloc(v.size)) != NULL,
               "%s: out of memory", what))
        goto done;
    memcpy(before, v.allocation, v.size);
    desc = interleaved_mesh(&v, c->texcoords != NULL, desc.indices, desc.index_count, desc.index_type);
    output = interleaved_output(&v);
    memset(&report, 0x5A, sizeof report);
    if (!expect_status(what, tbasis_generate(&desc, &options, &output, &report), want))
        goto done;
    check_report(what, &report, c->expected[p], every_field);
    if (rejects) {
        check(memcmp(before, v.allocation, v.size) == 0, "%s: a refused call wrote a byte", what);
    } else {
        /* Same library, same numbers: the layout must not change a bit. */
        gather(&v, STABILITY_LAYOUT.tangent, 4, gathered_t);
        gather(&v, STABILITY_LAYOUT.bitangent, 3, gathered_b);
        check_float_bits(what, tangents.inner, gathered_t, 4 * n);
        check_float_bits(what, bitangents.inner, gathered_b, 3 * n);
        check_abnormal_normals(what, c, report.abnormal_normals);
        check_only_outputs_written(what, &v, before, gathered_t, gathered_b);
    }
done:
    free(before);
    free(v.allocation);
    guarded_free(&tangents);
    guarded_free(&bitangents);
    free(gathered_t);
    free(gathered_b);
}

static void test_stability(const char *path, uint64_t max_vertices)
{
    stability_case *cases;
    uint32_t count, i, skipped = 0;
    long vertices = 0;
    uint32_t method;
    int p;
    if (!check(cases_read(path, &cases, &count) == 0, "cannot read the case file %s", path))
        return;
    check(count > 0, "the case file %s holds no case", path);
    for (i = 0; i < count; i++) {
        if (cases[i].vertex_count > max_vertices) {
            skipped++;
            continue;
        }
        for (p = 0; p < CASE_POLICIES; p++)
            for (method = TBASIS_METHOD_LENGYEL; method <= TBASIS_METHOD_UNIFORM; method++)
                test_stability_case(&cases[i], p, method);
        vertices += (long)cases[i].vertex_count;
    }
    printf("stability suite: %lu cases, %ld vertices, 3 policies x 4 methods, packed and interleaved\n",
           (unsigned long)(count - skipped), vertices);
    if (skipped > 0)
        printf("stability suite: skipped %lu case(s) above %llu vertices\n", (unsigned long)skipped,
               (unsigned long long)max_vertices);
    cases_free(cases, count);
}

/* ---------------------------------------------------------------------------------------------
 * Tangent-space transforms
 */

static double det3(const double c0[3], const double c1[3], const double c2[3])
{
    return c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1]) +
           c2[0] * (c0[1] * c1[2] - c0[2] * c1[1]);
}

/* A frame that is not orthonormal (normal of length 2, tangent at 45 degrees to it, w = -1): the
   two exports must match M^-1 d and M d, M = [T B N] with B = w * cross(N, T), computed here in
   double (Cramer's rule), and refuse bad input without writing. */
static void test_transforms(void)
{
    const float normal[3] = {0.0f, 0.0f, 2.0f}, tangent[4] = {1.0f, 0.0f, 1.0f, -1.0f};
    const float direction[3] = {0.3f, -0.7f, 1.1f}, parallel[4] = {0.0f, 0.0f, 3.0f, 1.0f};
    const float nan_direction[3] = {0.3f, NAN, 1.1f};
    double t[3], b[3], n[3], d[3], column[3], det, want_to[3], want_from[3];
    float to[3], back[3], from[3], inplace[3];
    int k, j;

    for (k = 0; k < 3; k++) {
        t[k] = tangent[k];
        n[k] = normal[k];
        d[k] = direction[k];
    }
    b[0] = tangent[3] * (n[1] * t[2] - n[2] * t[1]);
    b[1] = tangent[3] * (n[2] * t[0] - n[0] * t[2]);
    b[2] = tangent[3] * (n[0] * t[1] - n[1] * t[0]);
    det = det3(t, b, n);
    for (k = 0; k < 3; k++) {
        /* Cramer: coordinate k is det(M with column k replaced by d) / det(M). */
        const double *columns[3];
        columns[0] = t;
        columns[1] = b;
        columns[2] = n;
        for (j = 0; j < 3; j++)
            column[j] = d[j];
        columns[k] = column;
        want_to[k] = det3(columns[0], columns[1], columns[2]) / det;
        want_from[k] = d[0] * t[k] + d[1] * b[k] + d[2] * n[k];
    }

    expect_status("to_tangent_space", tbasis_to_tangent_space(normal, tangent, direction, to), TBASIS_OK);
    expect_status("from_tangent_space", tbasis_from_tangent_space(normal, tangent, direction, from), TBASIS_OK);
    expect_status("from_tangent_space(to_tangent_space)", tbasis_from_tangent_space(normal, tangent, to, back),
                  TBASIS_OK);
    for (k = 0; k < 3; k++) {
        check(fabs(to[k] - want_to[k]) <= 1e-6 * fabs(want_to[k]) + 1e-7, "to_tangent_space[%d] = %.9g, want %.9g",
              k, to[k], want_to[k]);
        check(fabs(from[k] - want_from[k]) <= 1e-6 * fabs(want_from[k]) + 1e-7,
              "from_tangent_space[%d] = %.9g, want %.9g", k, from[k], want_from[k]);
        check(fabs(back[k] - direction[k]) <= 1e-6, "round trip [%d] = %.9g, want %.9g", k, back[k], direction[k]);
    }

    memcpy(inplace, direction, sizeof inplace);
    expect_status("to_tangent_space in place", tbasis_to_tangent_space(normal, tangent, inplace, inplace), TBASIS_OK);
    check(memcmp(inplace, to, sizeof to) == 0, "to_tangent_space in place differs from the separate result");

    sentinel_fill(to, sizeof to);
    expect_status("to_tangent_space, tangent parallel to the normal",
                  tbasis_to_tangent_space(normal, parallel, direction, to), TBASIS_ERROR_INVALID_FRAME);
    expect_status("from_tangent_space, NaN direction", tbasis_from_tangent_space(normal, tangent, nan_direction, to),
                  TBASIS_ERROR_INVALID_FRAME);
    expect_status("to_tangent_space, NULL tangent", tbasis_to_tangent_space(normal, NULL, direction, to),
                  TBASIS_ERROR_NULL_POINTER);
    expect_status("from_tangent_space, NULL result", tbasis_from_tangent_space(normal, tangent, direction, NULL),
                  TBASIS_ERROR_NULL_POINTER);
    expect_status("to_tangent_space, NULL normal", tbasis_to_tangent_space(NULL, tangent, direction, to),
                  TBASIS_ERROR_NULL_POINTER);
    expect_status("from_tangent_space, NULL direction", tbasis_from_tangent_space(normal, tangent, NULL, to),
                  TBASIS_ERROR_NULL_POINTER);
    /* Every frame the header calls invalid, both ways. */
    {
        static const float zero3[3] = {0.0f, 0.0f, 0.0f}, zero4[4] = {0.0f, 0.0f, 0.0f, 1.0f};
        static const float no_w[4] = {1.0f, 0.0f, 1.0f, 0.0f}, nan_normal[3] = {0.0f, NAN, 2.0f};
        static const float inf_tangent[4] = {INFINITY, 0.0f, 1.0f, 1.0f}, huge_direction[3] = {3e38f, 3e38f, 3e38f};
        static const float huge_normal[3] = {0.0f, 0.0f, 3e38f};
        const struct {
            const char *what;
            const float *normal, *tangent, *direction;
        } invalid[] = {
            {"zero normal", zero3, tangent, direction},
            {"zero tangent", normal, zero4, direction},
            {"w zero", normal, no_w, direction},
            {"NaN normal", nan_normal, tangent, direction},
            {"infinite tangent", normal, inf_tangent, direction},
            {"overflowing result", huge_normal, tangent, huge_direction},
        };
        size_t c;
        for (c = 0; c < sizeof invalid / sizeof invalid[0]; c++) {
            char what[96];
            snprintf(what, sizeof what, "from_tangent_space, %s", invalid[c].what);
            expect_status(what,
                          tbasis_from_tangent_space(invalid[c].normal, invalid[c].tangent, invalid[c].direction, to),
                          TBASIS_ERROR_INVALID_FRAME);
            if (c == 5)
                continue; /* to_tangent_space divides by the huge normal: its result is small */
            snprintf(what, sizeof what, "to_tangent_space, %s", invalid[c].what);
            expect_status(what,
                          tbasis_to_tangent_space(invalid[c].normal, invalid[c].tangent, invalid[c].direction, to),
                          TBASIS_ERROR_INVALID_FRAME);
        }
    }
    check(sentinel_intact(to, sizeof to), "a refused transform wrote its result");
    /* The result may overlap any input: every input is read before it is written. */
    {
        float frame[7], want[3];
        memcpy(frame, normal, sizeof normal);
        memcpy(frame + 3, tangent, sizeof tangent);
        if (expect_status("from_tangent_space", tbasis_from_tangent_space(normal, tangent, direction, want),
                          TBASIS_OK) &&
            expect_status("from_tangent_space into its normal",
                          tbasis_from_tangent_space(frame, frame + 3, direction, frame), TBASIS_OK))
            check(memcmp(frame, want, sizeof want) == 0, "from_tangent_space into its normal differs");
        memcpy(frame, normal, sizeof normal);
        memcpy(frame + 3, tangent, sizeof tangent);
        if (expect_status("to_tangent_space", tbasis_to_tangent_space(normal, tangent, direction, want),
                          TBASIS_OK) &&
            expect_status("to_tangent_space into its tangent",
                          tbasis_to_tangent_space(frame, frame + 3, direction, frame + 3), TBASIS_OK))
            check(memcmp(frame + 3, want, sizeof want) == 0, "to_tangent_space into its tangent differs");
    }
    check(strcmp(tbasis_status_string(TBASIS_ERROR_INVALID_FRAME), tbasis_status_string(1000)) != 0,
          "TBASIS_ERROR_INVALID_FRAME has no description of its own");
}

/* ---------------------------------------------------------------------------------------------
 * Main
 */

int main(int argc, char **argv)
{
    enum { MESHES = 5 };
    test_mesh meshes[MESHES], small;
    /* The listing writes NaN for the degenerate grid's collinear band and unused vertex, and for
       the spheres' pole vertices that only zero-area triangles touch. */
    const int nonfinite[MESHES] = {0, 1, 0, 1, 1};
    test_mesh corner_grids[2];
    fixture *f = calloc(1, sizeof *f);
    test_mesh threads_grid;
    int made[MESHES], k, small_made, corner_grids_made, threads_made;
    tbasis_status s;

    memset(meshes, 0, sizeof meshes);
    made[0] = mesh_grid(&meshes[0], 64, 50, 0) == 0;
    made[1] = mesh_grid(&meshes[1], 48, 36, 1) == 0;
    made[2] = mesh_torus(&meshes[2], 96, 36) == 0;
    made[3] = mesh_uv_sphere(&meshes[3], 72, 40, 0) == 0;
    made[4] = mesh_uv_sphere(&meshes[4], 72, 40, 1) == 0;
    small_made = mesh_grid(&small, 5, 4, 0) == 0;
    corner_grids_made = mesh_grid(&corner_grids[0], 16, 12, 0) == 0;
    corner_grids_made = mesh_grid(&corner_grids[1], 12, 9, 1) == 0 && corner_grids_made;
    threads_made = mesh_grid(&threads_grid, 130, 130, 0) == 0;

    test_abi();
    test_version_and_strings();
    for (k = 0; k < MESHES; k++)
        if (check(made[k], "mesh %d: out of memory", k))
            test_legacy(&meshes[k], nonfinite[k]);
    /* Per corner: every method on small grids with a mirror fold (the degenerate one has collapsed
       triangles at the fold), and the defaults and LEGACY's inf/NaN on the pinched sphere. */
    if (check(corner_grids_made, "corner grids: out of memory")) {
        test_corners(&corner_grids[0], 1, 1);
        test_corners(&corner_grids[1], 0, 1);
        test_split(&corner_grids[0]);
    }
    if (made[4])
        test_corners(&meshes[4], 0, 0);
    if (made[0]) {
        test_degenerate_triangles(&meshes[0]);
        test_scratch(&meshes[0]);
        test_scratch_sizes(&meshes[0]);
    }
    if (check(threads_made, "threads grid: out of memory"))
        test_threads(&threads_grid);
    test_out_of_memory();
    if (check(f != NULL && small_made, "status fixture: out of memory")) {
        f->source = &small;
        test_statuses(f);
        test_corner_statuses(&small);
        test_split_statuses(&small);
    }
    test_transforms();
    /* Every error but INTERNAL, which only a bug in the library returns. */
    for (s = TBASIS_ERROR_NULL_POINTER; s <= LAST_STATUS; s++)
        if (s != TBASIS_ERROR_INTERNAL)
            check(provoked[s], "no check provoked status %u (%s)", (unsigned)s, tbasis_status_string(s));

    if (argc > 1)
        test_stability(argv[1], argc > 2 ? strtoull(argv[2], NULL, 10) : UINT64_MAX);
    else
        printf("no case file given: stability suite skipped\n");

    printf("LEGACY bit-identical to the listing: %ld vertex results over %ld vertices of %d mesh forms "
           "(%ld inf/NaN floats among them)\n",
           exact_results, exact_vertices, 3 * MESHES, nonfinite_floats);
    printf("%ld passed, %ld failed\n", checks_passed, checks_failed);

    for (k = 0; k < MESHES; k++)
        if (made[k])
            mesh_free(&meshes[k]);
    if (small_made)
        mesh_free(&small);
    mesh_free(&corner_grids[0]);
    mesh_free(&corner_grids[1]);
    if (threads_made)
        mesh_free(&threads_grid);
    free(f);
    return checks_failed > 0 ? 1 : 0;
}
