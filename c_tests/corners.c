#include "corners.h"

#include "check.h"
#include "fixture.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define COUNT(array) (sizeof(array) / sizeof((array)[0]))

static const uint32_t PER_VERTEX_METHODS[] = {TBASIS_METHOD_LENGYEL, TBASIS_METHOD_ANGLE, TBASIS_METHOD_AREA,
                                              TBASIS_METHOD_UNIFORM};
static const uint32_t CORNER_POLICIES[] = {TBASIS_DEGENERATE_LEGACY, TBASIS_DEGENERATE_SKIP,
                                           TBASIS_DEGENERATE_INHERIT};

static tbasis_options method_options(uint32_t method, uint32_t policy)
{
    tbasis_options o;
    memset(&o, 0, sizeof o);
    o.method = method;
    o.degenerate_policy = policy;
    return o;
}

/* The sign (+1, -1 or 0) of the UV determinant of the triangle corner c belongs to. */
static int corner_orientation(const test_mesh *m, const tbasis_mesh *d, size_t c)
{
    const size_t first = c - c % 3;
    const float *a = m->texcoords + 2 * corner_vertex(d, first);
    const float *b = m->texcoords + 2 * corner_vertex(d, first + 1);
    const float *e = m->texcoords + 2 * corner_vertex(d, first + 2);
    double det = ((double)b[0] - a[0]) * ((double)e[1] - a[1]) - ((double)e[0] - a[0]) * ((double)b[1] - a[1]);
    return (det > 0.0) - (det < 0.0);
}

/* ---------------------------------------------------------------------------------------------
 * Per corner against per vertex
 */

/* One mesh form: the orientation of each corner's triangle, and which vertices have both. */
typedef struct corner_form {
    const test_mesh *m;
    uint32_t index_type;
    tbasis_mesh desc;
    size_t corners;
    signed char *orientation; /* per corner */
    unsigned char *two_sided; /* per vertex: used with both UV orientations */
    float *vertex_tangents;   /* tbasis_generate's, 4 per vertex */
    guarded out;              /* the per-corner output, 16 bytes per corner */
} corner_form;

static int form_make(corner_form *f, const test_mesh *m, uint32_t index_type)
{
    size_t n = (size_t)m->vertex_count, c;
    unsigned char *sides;
    memset(f, 0, sizeof *f);
    f->m = m;
    f->index_type = index_type;
    f->desc = mesh_description(m, index_type);
    f->corners = corner_count(&f->desc);
    f->orientation = malloc(f->corners + 1);
    f->two_sided = calloc(n + 1, 1);
    f->vertex_tangents = calloc(4 * n + 1, sizeof(float));
    if (f->orientation == NULL || f->two_sided == NULL || f->vertex_tangents == NULL ||
        guarded_alloc(&f->out, 16 * f->corners) != 0)
        return -1;
    /* Bit 1: used with a positive determinant, bit 2: with a negative one. */
    sides = f->two_sided;
    for (c = 0; c < f->corners; c++) {
        f->orientation[c] = (signed char)corner_orientation(m, &f->desc, c);
        sides[corner_vertex(&f->desc, c)] |= f->orientation[c] > 0 ? 1 : f->orientation[c] < 0 ? 2 : 0;
    }
    for (c = 0; c < n; c++)
        sides[c] = sides[c] == 3;
    return 0;
}

static void form_free(corner_form *f)
{
    free(f->orientation);
    free(f->two_sided);
    free(f->vertex_tangents);
    guarded_free(&f->out);
}

/* What is wrong with corner c's frame t, or NULL: its vertex's bits, or at a fold a valid frame of
   the opposite handedness; with `clean_fold`, a fold corner's w is its triangle's orientation. */
static const char *corner_problem(const corner_form *f, const tbasis_options *options, int clean_fold, size_t c,
                                  const float t[4], int *side_frame)
{
    const size_t v = corner_vertex(&f->desc, c);
    const float *vertex = f->vertex_tangents + 4 * v;
    const int sides = options->degenerate_policy != TBASIS_DEGENERATE_LEGACY;
    *side_frame = memcmp(t, vertex, 16) != 0;
    if (*side_frame) {
        if (!sides)
            return "differs from its vertex's frame (LEGACY has no sides)";
        if (!f->two_sided[v])
            return "differs from its vertex's frame away from a mirror fold";
        if (t[3] != -vertex[3])
            return "at a fold, differs from its vertex's frame but has its w";
        return tangent_problem(f->m->normals + 3 * v, t);
    }
    if (clean_fold && sides && f->two_sided[v] && t[3] != (float)f->orientation[c])
        return "at a fold, w is not its own triangle's UV orientation";
    return NULL;
}

static void compare_corners(corner_form *f, tbasis_options options, int clean_fold)
{
    char what[256];
    tbasis_output output;
    tbasis_report vertex_report, corner_report;
    size_t c, side_frames = 0, bad = 0, first = 0;
    const char *first_problem = NULL;

    snprintf(what, sizeof what, "%s (%s): corners, method %u policy %u", f->m->name, index_type_name(f->index_type),
             (unsigned)options.method, (unsigned)options.degenerate_policy);
    memset(&output, 0, sizeof output);
    output.tangents = f->vertex_tangents;
    output.tangents_stride = 16;
    memset(&vertex_report, 0x5A, sizeof vertex_report);
    memset(&corner_report, 0xA5, sizeof corner_report);
    if (!expect_status(what, tbasis_generate(&f->desc, &options, &output, &vertex_report), TBASIS_OK))
        return;
    guarded_reset(&f->out);
    if (!expect_status(what, tbasis_generate_corners(&f->desc, &options, f->out.inner, 16, &corner_report), TBASIS_OK))
        return;
    check(guards_intact(&f->out), "%s: wrote outside its output", what);
    check(memcmp(&vertex_report, &corner_report, sizeof vertex_report) == 0, "%s: the report differs from "
          "tbasis_generate's", what);
    for (c = 0; c < f->corners; c++) {
        float t[4];
        int side_frame;
        const char *problem;
        memcpy(t, (const unsigned char *)f->out.inner + 16 * c, sizeof t);
        problem = corner_problem(f, &options, clean_fold, c, t, &side_frame);
        side_frames += (size_t)side_frame;
        if (problem != NULL && bad++ == 0) {
            first = c;
            first_problem = problem;
        }
    }
    if (bad == 0)
        check(1, "%s", what);
    else
        check(0, "%s: %zu of %zu corners wrong; corner %zu (vertex %zu): %s", what, bad, f->corners, first,
              corner_vertex(&f->desc, first), first_problem);
    if (clean_fold && options.degenerate_policy != TBASIS_DEGENERATE_LEGACY)
        check(side_frames > 0, "%s: no corner at the mirror fold took its own side's frame", what);
}

/* Caller scratch of exactly tbasis_scratch_size bytes at every alignment gives the same bits; one
   byte less is refused without writing. */
static void check_corner_scratch(corner_form *f, tbasis_options options)
{
    char what[256];
    size_t needed = tbasis_scratch_size(&f->desc, &options), offset;
    unsigned char *scratch = malloc(needed + 4), *plain = malloc(16 * f->corners + 1);

    snprintf(what, sizeof what, "%s (%s): corners with caller scratch, policy %u", f->m->name,
             index_type_name(f->index_type), (unsigned)options.degenerate_policy);
    if (!check(scratch != NULL && plain != NULL && needed > 0, "%s: out of memory", what))
        goto done;
    if (!expect_status(what, tbasis_generate_corners(&f->desc, &options, plain, 16, NULL), TBASIS_OK))
        goto done;
    memset(scratch, 0xEE, needed + 4);
    for (offset = 0; offset < 4; offset++) {
        options.scratch = scratch + offset;
        options.scratch_size = needed;
        guarded_reset(&f->out);
        if (expect_status(what, tbasis_generate_corners(&f->desc, &options, f->out.inner, 16, NULL), TBASIS_OK))
            check_float_bits(what, (const float *)plain, f->out.inner, 4 * f->corners);
        guarded_reset(&f->out);
        options.scratch_size = needed - 1;
        expect_status(what, tbasis_generate_corners(&f->desc, &options, f->out.inner, 16, NULL),
                      TBASIS_ERROR_SCRATCH_TOO_SMALL);
        check(guarded_intact(&f->out), "%s: one byte short at offset %zu wrote output", what, offset);
    }
done:
    free(scratch);
    free(plain);
}

static void test_corners_form(const test_mesh *m, uint32_t index_type, int clean_fold, int every_method)
{
    corner_form f;
    size_t k, p;
    if (check(form_make(&f, m, index_type) == 0, "%s (%s): corners: out of memory", m->name,
              index_type_name(index_type))) {
        for (k = 0; k < COUNT(PER_VERTEX_METHODS) && every_method; k++)
            for (p = 0; p < COUNT(CORNER_POLICIES); p++)
                /* Only LENGYEL has a legacy form among the per-vertex methods. */
                if (CORNER_POLICIES[p] != TBASIS_DEGENERATE_LEGACY || PER_VERTEX_METHODS[k] == TBASIS_METHOD_LENGYEL)
                    compare_corners(&f, method_options(PER_VERTEX_METHODS[k], CORNER_POLICIES[p]), clean_fold);
        compare_corners(&f, method_options(0, 0), clean_fold);
        if (!every_method)
            compare_corners(&f, method_options(TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_LEGACY), clean_fold);
        if (index_type == TBASIS_INDEX_U32) {
            check_corner_scratch(&f, method_options(TBASIS_METHOD_LENGYEL, TBASIS_DEGENERATE_LEGACY));
            check_corner_scratch(&f, method_options(TBASIS_METHOD_ANGLE, TBASIS_DEGENERATE_INHERIT));
        }
    }
    form_free(&f);
}

void test_corners(const test_mesh *m, int clean_fold, int every_method)
{
    test_mesh flat;
    if (m->indices16 != NULL)
        test_corners_form(m, TBASIS_INDEX_U16, clean_fold, every_method);
    test_corners_form(m, TBASIS_INDEX_U32, clean_fold, every_method);
    /* Unindexed, no vertex is shared, so there is no fold. */
    if (check(mesh_unindexed(&flat, m) == 0, "%s: out of memory", m->name)) {
        test_corners_form(&flat, 0, 0, every_method);
        mesh_free(&flat);
    }
}

/* ---------------------------------------------------------------------------------------------
 * Statuses: every error writes no byte
 */

/* The fixture's call made a per-corner one with `method` and its default policy. */
static void call_reset(fixture *f, uint32_t method)
{
    fixture_reset(f);
    f->options = method_options(method, 0);
}

static tbasis_status call_run(fixture *f, tbasis_report *report)
{
    memcpy(&f->before, &f->memory, sizeof f->memory);
    memset(report, 0x5A, sizeof *report);
    return tbasis_generate_corners(f->mesh_arg, &f->options, f->output.tangents, f->output.tangents_stride, report);
}

/* The call must fail with `want` and leave every byte of the arena, and the report, as it was. */
static void expect_refused(fixture *f, const char *label, tbasis_status want)
{
    char what[256];
    tbasis_report report, untouched;
    snprintf(what, sizeof what, "corners, method %u: %s", (unsigned)f->options.method, label);
    expect_status(what, call_run(f, &report), want);
    check(memcmp(&f->before, &f->memory, sizeof f->memory) == 0, "%s: a byte was written", what);
    /* The header's contract: only these two refusals fill the report. */
    memset(&untouched, 0x5A, sizeof untouched);
    if (want != TBASIS_ERROR_INDEX_OUT_OF_RANGE && want != TBASIS_ERROR_DEGENERATE_UV)
        check(memcmp(&report, &untouched, sizeof report) == 0, "%s: the report was written", what);
}

/* The call must succeed, write every corner's 16 bytes and nothing else. */
static void expect_written(fixture *f, const char *label)
{
    char what[256];
    const size_t corners = corner_count(&f->mesh);
    unsigned char *tangents = f->memory.tangents, *before = f->before.tangents;
    size_t c, unwritten = 0;
    tbasis_report report;
    snprintf(what, sizeof what, "corners, method %u policy %u: %s", (unsigned)f->options.method,
             (unsigned)f->options.degenerate_policy, label);
    if (!expect_status(what, call_run(f, &report), TBASIS_OK))
        return;
    for (c = 0; c < corners; c++)
        unwritten += memcmp(tangents + GUARD_BYTES + 16 * c, before + GUARD_BYTES + 16 * c, 16) == 0;
    check(unwritten == 0, "%s: %zu of %zu corners not written", what, unwritten, corners);
    check(memcmp(tangents, before, GUARD_BYTES) == 0 &&
              memcmp(tangents + GUARD_BYTES + 16 * corners, before + GUARD_BYTES + 16 * corners,
                     FIX_BUFFER - GUARD_BYTES - 16 * corners) == 0,
          "%s: bytes around the corners were written", what);
    /* The corners were checked above; the scratch is working memory. */
    memset(tangents + GUARD_BYTES, 0, 16 * corners);
    memset(before + GUARD_BYTES, 0, 16 * corners);
    memset(f->memory.scratch, 0, sizeof f->memory.scratch);
    memset(f->before.scratch, 0, sizeof f->before.scratch);
    check(memcmp(&f->before, &f->memory, sizeof f->memory) == 0, "%s: an input byte was written", what);
}

/* The statuses every method shares: validation before any method runs. */
static void refuse_invalid_calls(fixture *f, uint32_t method)
{
    const size_t n = (size_t)f->source->vertex_count, t = (size_t)f->source->triangle_count;
    arena *a = &f->memory;
    size_t needed;
    uint16_t index16;

    call_reset(f, method);
    f->mesh_arg = NULL;
    expect_refused(f, "NULL mesh", TBASIS_ERROR_NULL_POINTER);
    call_reset(f, method);
    f->output.tangents = NULL;
    expect_refused(f, "NULL tangents", TBASIS_ERROR_NULL_POINTER);
    call_reset(f, method);
    f->mesh.positions = NULL;
    expect_refused(f, "NULL positions", TBASIS_ERROR_NULL_POINTER);
    call_reset(f, method);
    f->output.tangents_stride = 15;
    expect_refused(f, "tangents stride 15", TBASIS_ERROR_INVALID_STRIDE);
    call_reset(f, method);
    f->output.tangents_stride = 0;
    expect_refused(f, "tangents stride 0", TBASIS_ERROR_INVALID_STRIDE);
    call_reset(f, method);
    f->output.tangents_stride = SIZE_MAX / 16;
    expect_refused(f, "tangents stride SIZE_MAX/16", TBASIS_ERROR_SIZE_OVERFLOW);
    call_reset(f, method);
    f->mesh.index_count -= 1;
    expect_refused(f, "index_count not a multiple of 3", TBASIS_ERROR_INVALID_INDEX_COUNT);
    call_reset(f, method);
    f->mesh.index_type = 3;
    expect_refused(f, "index_type 3", TBASIS_ERROR_INVALID_INDEX_TYPE);
    call_reset(f, method);
    index16 = (uint16_t)n;
    memcpy(a->indices + 2 * (3 * t - 1), &index16, sizeof index16);
    expect_refused(f, "index == vertex_count in the last triangle", TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    call_reset(f, method);
    f->options.degenerate_policy = TBASIS_DEGENERATE_REJECT + 1;
    expect_refused(f, "policy one past the last", TBASIS_ERROR_UNKNOWN_POLICY);
    call_reset(f, method);
    f->options.flags = 2;
    expect_refused(f, "flag bit 1", TBASIS_ERROR_UNKNOWN_FLAGS);
    call_reset(f, method);
    f->options.degenerate_threshold = -1.0f;
    expect_refused(f, "threshold -1", TBASIS_ERROR_INVALID_THRESHOLD);

    call_reset(f, method);
    f->output.tangents = a->positions;
    expect_refused(f, "tangents on top of the positions", TBASIS_ERROR_OVERLAP);
    call_reset(f, method);
    f->output.tangents = a->normals + 12 * (n - 1);
    expect_refused(f, "corner 0 on the last normal", TBASIS_ERROR_OVERLAP);
    call_reset(f, method);
    f->output.tangents = a->indices + 2 * (3 * t - 1);
    expect_refused(f, "corner 0 on the last index", TBASIS_ERROR_OVERLAP);

    /* Scratch: any size from tbasis_scratch_size up is accepted; less is refused. */
    call_reset(f, method);
    needed = tbasis_scratch_size(&f->mesh, &f->options);
    if (!check(needed + GUARD_BYTES <= FIX_BUFFER, "corners, method %u: tbasis_scratch_size %zu exceeds the arena",
               (unsigned)method, needed))
        return;
    f->options.scratch = a->scratch;
    f->options.scratch_size = needed + GUARD_BYTES;
    f->output.tangents = a->scratch + GUARD_BYTES / 2;
    expect_refused(f, "tangents inside the scratch", TBASIS_ERROR_OVERLAP);
    call_reset(f, method);
    f->options.scratch = a->texcoords;
    f->options.scratch_size = needed + GUARD_BYTES;
    expect_refused(f, "scratch on top of the texcoords", TBASIS_ERROR_OVERLAP);
    if (needed > 0) {
        call_reset(f, method);
        f->options.scratch = a->scratch;
        f->options.scratch_size = needed - 1;
        expect_refused(f, "scratch one byte short", TBASIS_ERROR_SCRATCH_TOO_SMALL);
        call_reset(f, method);
        f->options.scratch = a->scratch + 1;
        f->options.scratch_size = 0;
        expect_refused(f, "scratch of size 0", TBASIS_ERROR_SCRATCH_TOO_SMALL);
    }
    call_reset(f, method);
    f->options.scratch = a->scratch + 1;
    f->options.scratch_size = needed;
    expect_written(f, "caller scratch of exactly tbasis_scratch_size bytes");
}

void test_corner_statuses(const test_mesh *m)
{
    static const uint32_t mikktspace_policies[] = {0, TBASIS_DEGENERATE_SKIP, TBASIS_DEGENERATE_INHERIT};
    fixture *f = calloc(1, sizeof *f);
    tbasis_report report;
    size_t p;
    if (!check(f != NULL && m->indices16 != NULL, "corner statuses: out of memory"))
        goto done;
    f->source = m;

    call_reset(f, TBASIS_METHOD_ANGLE);
    expect_written(f, "baseline");
    call_reset(f, TBASIS_METHOD_ANGLE);
    f->mesh.index_count = 0;
    f->output.tangents = NULL;
    expect_written(f, "no corners, NULL tangents");
    refuse_invalid_calls(f, TBASIS_METHOD_ANGLE);
    call_reset(f, TBASIS_METHOD_ANGLE);
    f->options.method = TBASIS_METHOD_MIKKTSPACE + 1;
    expect_refused(f, "method one past the last", TBASIS_ERROR_UNKNOWN_METHOD);
    call_reset(f, TBASIS_METHOD_LENGYEL);
    f->options.degenerate_policy = TBASIS_DEGENERATE_LEGACY;
    f->mesh.texcoords = NULL;
    expect_refused(f, "NULL texcoords under LEGACY", TBASIS_ERROR_NULL_POINTER);
    call_reset(f, TBASIS_METHOD_ANGLE);
    f->options.degenerate_policy = TBASIS_DEGENERATE_LEGACY;
    expect_refused(f, "LEGACY with a method that has no legacy form", TBASIS_ERROR_NO_LEGACY_FORM);
    call_reset(f, TBASIS_METHOD_ANGLE);
    f->options.degenerate_policy = TBASIS_DEGENERATE_REJECT;
    memcpy(f->memory.texcoords + 8 * f->source->indices16[2], f->memory.texcoords + 8 * f->source->indices16[0], 8);
    expect_status("corners: REJECT on a collapsed UV triangle", call_run(f, &report), TBASIS_ERROR_DEGENERATE_UV);
    check(report.degenerate_triangles >= 1 && report.first_degenerate_triangle == 0,
          "corners: REJECT report counts %zu degenerate, first %zu; expected some, first 0",
          report.degenerate_triangles, report.first_degenerate_triangle);
    check(memcmp(&f->before, &f->memory, sizeof f->memory) == 0, "corners: REJECT wrote a byte");

    /* MIKKTSPACE: validated like the others; it needs texcoords under every policy. */
    for (p = 0; p < COUNT(mikktspace_policies); p++) {
        call_reset(f, TBASIS_METHOD_MIKKTSPACE);
        f->options.degenerate_policy = mikktspace_policies[p];
        expect_written(f, "baseline");
        call_reset(f, TBASIS_METHOD_MIKKTSPACE);
        f->options.degenerate_policy = mikktspace_policies[p];
        f->mesh.texcoords = NULL;
        expect_refused(f, "NULL texcoords", TBASIS_ERROR_NULL_POINTER);
    }
    call_reset(f, TBASIS_METHOD_MIKKTSPACE);
    f->mesh.index_count = 0;
    f->output.tangents = NULL;
    expect_written(f, "no corners, NULL tangents");
    refuse_invalid_calls(f, TBASIS_METHOD_MIKKTSPACE);
done:
    free(f);
}

/* ---------------------------------------------------------------------------------------------
 * Scratch sizes
 */

void test_scratch_sizes(const test_mesh *m)
{
    static const uint32_t index_types[] = {TBASIS_INDEX_U16, TBASIS_INDEX_U32, 0};
    const size_t n = (size_t)m->vertex_count, per_vertex = n * 29 + 3;
    tbasis_options options;
    tbasis_mesh desc, empty;
    uint32_t method, policy;
    size_t k, corners, expected;

    for (k = 0; k < COUNT(index_types); k++) {
        if (index_types[k] == TBASIS_INDEX_U16 && m->indices16 == NULL)
            continue;
        desc = mesh_description(m, index_types[k]);
        corners = desc.indices != NULL ? desc.index_count : desc.vertex_count;
        /* Per-vertex methods: the same for both calls; policy INHERIT (also policy 0) adds its
           adjacency, 8 bytes per vertex and 4 per corner. */
        for (method = 0; method <= TBASIS_METHOD_UNIFORM; method++)
            for (policy = 0; policy <= TBASIS_DEGENERATE_REJECT; policy++) {
                options = method_options(method, policy);
                expected = policy == 0 || policy == TBASIS_DEGENERATE_INHERIT ? per_vertex + n * 8 + corners * 4
                                                                               : per_vertex;
                /* LEGACY has no form but the listing's (method LENGYEL, or 0): the options are invalid. */
                if (policy == TBASIS_DEGENERATE_LEGACY && method > TBASIS_METHOD_LENGYEL)
                    expected = SIZE_MAX;
                check(tbasis_scratch_size(&desc, &options) == expected,
                      "tbasis_scratch_size (%s, method %u, policy %u) is %zu, expected %zu",
                      index_type_name(index_types[k]), (unsigned)method, (unsigned)policy,
                      tbasis_scratch_size(&desc, &options), expected);
            }
        /* MIKKTSPACE: the header's formula, with T = C / 3 triangles; REJECT at least 29 V + 3. */
        options = method_options(TBASIS_METHOD_MIKKTSPACE, 0);
        expected = 97 * corners + 65 * (corners / 3) + 12 * n + 4 * (2 * n + 2 > corners ? 2 * n + 2 : corners) +
                   16454;
        check(tbasis_scratch_size(&desc, &options) == expected,
              "tbasis_scratch_size (%s, MIKKTSPACE) is %zu, expected %zu", index_type_name(index_types[k]),
              tbasis_scratch_size(&desc, &options), expected);
        options = method_options(TBASIS_METHOD_MIKKTSPACE, TBASIS_DEGENERATE_REJECT);
        check(tbasis_scratch_size(&desc, &options) >= per_vertex, "tbasis_scratch_size (%s, MIKKTSPACE, REJECT)",
              index_type_name(index_types[k]));
    }

    /* MIKKTSPACE indexes vertices and corners in 32 bits: at most 2^30 - 1 of each. */
    desc = mesh_description(m, 0);
    options = method_options(TBASIS_METHOD_MIKKTSPACE, 0);
    desc.vertex_count = ((size_t)1 << 30) - 1;
    check(tbasis_scratch_size(&desc, &options) != SIZE_MAX, "tbasis_scratch_size, MIKKTSPACE, 2^30 - 1 vertices");
    desc.vertex_count = (size_t)1 << 30;
    check(tbasis_scratch_size(&desc, &options) == SIZE_MAX, "tbasis_scratch_size, MIKKTSPACE, 2^30 vertices");

    desc = mesh_description(m, TBASIS_INDEX_U32);
    empty = desc;
    empty.vertex_count = 0;
    empty.index_count = 0;
    for (method = 0; method <= TBASIS_METHOD_MIKKTSPACE; method++) {
        options = method_options(method, 0);
        check(tbasis_scratch_size(&empty, &options) == 0, "tbasis_scratch_size of an empty mesh, method %u, is not 0",
              (unsigned)method);
    }
    options = method_options(TBASIS_METHOD_MIKKTSPACE + 1, 0);
    check(tbasis_scratch_size(&desc, &options) == SIZE_MAX, "tbasis_scratch_size with an unknown method");
    options = method_options(TBASIS_METHOD_MIKKTSPACE, TBASIS_DEGENERATE_REJECT + 1);
    check(tbasis_scratch_size(&desc, &options) == SIZE_MAX, "tbasis_scratch_size with an unknown policy");
    options = method_options(0, 0);
    options.flags = 2;
    check(tbasis_scratch_size(&desc, &options) == SIZE_MAX, "tbasis_scratch_size with unknown flags");
    options = method_options(0, 0);
    options.degenerate_threshold = -1.0f;
    check(tbasis_scratch_size(&desc, &options) == SIZE_MAX, "tbasis_scratch_size with a negative threshold");
}
