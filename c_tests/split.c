#include "split.h"

#include "check.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static tbasis_options mikktspace_options(void)
{
    tbasis_options o;
    memset(&o, 0, sizeof o);
    o.method = TBASIS_METHOD_MIKKTSPACE;
    return o;
}

/* The split of one mesh form, checked against the corners it came from. */
static void test_split_form(const test_mesh *m, uint32_t index_type)
{
    const tbasis_mesh d = mesh_description(m, index_type);
    const tbasis_options o = mikktspace_options();
    const size_t corners = corner_count(&d), vertices = d.vertex_count;
    float *tangents = malloc(16 * corners);
    uint32_t *new_indices = malloc(4 * corners), *sources = malloc(4 * corners);
    float *owner_tangent = NULL, *positions = NULL;
    unsigned char *seen = calloc(vertices, 1);
    int *owned = NULL;
    size_t appended = 0, total, c, j, k;
    tbasis_report report;
    char what[128];

    snprintf(what, sizeof what, "split %s %s", m->name, index_type_name(index_type));
    if (!check(tangents && new_indices && sources && seen, "%s: out of memory", what))
        goto done;
    if (!expect_status(what, tbasis_generate_corners(&d, &o, tangents, 16, &report), TBASIS_OK) ||
        !expect_status(what, tbasis_split_corners(&d, tangents, 16, new_indices, sources, &appended), TBASIS_OK))
        goto done;
    check(appended >= report.split_vertices && appended <= corners,
          "%s: %zu vertices appended, %zu split vertices reported", what, appended, report.split_vertices);
    check(index_type == 0 || report.split_vertices > 0, "%s: the mesh has a mirror fold, yet no vertex is split",
          what);

    total = vertices + appended;
    owner_tangent = malloc(16 * total);
    owned = calloc(total, sizeof *owned);
    if (!check(owner_tangent && owned, "%s: out of memory", what))
        goto done;
    for (c = 0; c < corners; c++) {
        const size_t v = corner_vertex(&d, c), n = new_indices[c];
        if (!check(n < total, "%s: corner %zu has index %zu of %zu vertices", what, c, n, total))
            goto done;
        check((n < vertices ? n : sources[n - vertices]) == v, "%s: corner %zu of vertex %zu drawn with %zu", what,
              c, v, n);
        if (!seen[v]) {
            seen[v] = 1;
            check(n == v, "%s: vertex %zu's first corner %zu moved to %zu", what, v, c, n);
        }
        if (owned[n])
            check(memcmp(owner_tangent + 4 * n, tangents + 4 * c, 16) == 0,
                  "%s: corner %zu does not carry the tangent of its vertex %zu", what, c, n);
        else
            memcpy(owner_tangent + 4 * n, tangents + 4 * c, 16);
        owned[n] = 1;
    }
    for (j = 0; j < appended; j++) {
        check(owned[vertices + j], "%s: appended vertex %zu is never drawn", what, j);
        for (k = 0; k < vertices + j; k++) {
            const size_t source = k < vertices ? k : sources[k - vertices];
            if (owned[k] && source == sources[j])
                check(memcmp(owner_tangent + 4 * k, owner_tangent + 4 * (vertices + j), 16) != 0,
                      "%s: appended vertex %zu repeats vertex %zu", what, vertices + j, k);
        }
    }

    /* Appended vertices copy their source's position, with room after the original vertices. */
    positions = malloc(12 * total);
    if (!check(positions != NULL, "%s: out of memory", what))
        goto done;
    memcpy(positions, m->positions, 12 * vertices);
    expect_status(what, tbasis_copy_split_vertices(positions, 12, 12, vertices, sources, appended), TBASIS_OK);
    for (j = 0; j < appended; j++)
        check(memcmp(positions + 3 * (vertices + j), m->positions + 3 * sources[j], 12) == 0,
              "%s: appended vertex %zu is not a copy of %u", what, vertices + j, (unsigned)sources[j]);

done:
    free(tangents);
    free(new_indices);
    free(sources);
    free(seen);
    free(owner_tangent);
    free(owned);
    free(positions);
}

void test_split(const test_mesh *m)
{
    test_mesh unindexed;
    test_split_form(m, TBASIS_INDEX_U16);
    test_split_form(m, TBASIS_INDEX_U32);
    if (check(mesh_unindexed(&unindexed, m) == 0, "split %s: out of memory", m->name)) {
        test_split_form(&unindexed, 0);
        mesh_free(&unindexed);
    }
}

/* The outputs of the status checks, refilled with a sentinel before each call. */
typedef struct split_outputs {
    uint32_t new_indices[128];
    uint32_t sources[128];
    size_t appended;
} split_outputs;

static void expect_split(const char *what, const tbasis_mesh *d, const void *tangents, size_t stride,
                         split_outputs *out, uint32_t *new_indices, uint32_t *sources, size_t *appended,
                         tbasis_status want)
{
    sentinel_fill(out, sizeof *out);
    if (expect_status(what, tbasis_split_corners(d, tangents, stride, new_indices, sources, appended), want))
        check(sentinel_intact(out, sizeof *out), "%s: an output changed on error", what);
}

void test_split_statuses(const test_mesh *m)
{
    const tbasis_options o = mikktspace_options();
    tbasis_mesh d = mesh_description(m, TBASIS_INDEX_U16);
    const size_t corners = corner_count(&d);
    float tangents[128 * 4];
    uint16_t indices[128];
    float attribute[8 * 3];
    uint32_t copy_sources[2] = {0, 1};
    split_outputs out;

    if (!check(corners <= 128 && d.vertex_count >= 2, "split statuses: the mesh is too large"))
        return;
    if (!expect_status("split statuses: corners", tbasis_generate_corners(&d, &o, tangents, 16, NULL), TBASIS_OK))
        return;
    memcpy(indices, d.indices, 2 * corners);
    d.indices = indices;

    expect_split("split: NULL mesh", NULL, tangents, 16, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_NULL_POINTER);
    expect_split("split: NULL appended_count", &d, tangents, 16, &out, out.new_indices, out.sources, NULL,
                 TBASIS_ERROR_NULL_POINTER);
    expect_split("split: NULL new_indices", &d, tangents, 16, &out, NULL, out.sources, &out.appended,
                 TBASIS_ERROR_NULL_POINTER);
    expect_split("split: NULL tangents", &d, NULL, 16, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_NULL_POINTER);
    expect_split("split: tangent stride 8", &d, tangents, 8, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_INVALID_STRIDE);
    expect_split("split: tangent stride SIZE_MAX", &d, tangents, SIZE_MAX, &out, out.new_indices, out.sources,
                 &out.appended, TBASIS_ERROR_SIZE_OVERFLOW);
    expect_split("split: sources are new_indices", &d, tangents, 16, &out, out.new_indices, out.new_indices,
                 &out.appended, TBASIS_ERROR_OVERLAP);
    expect_split("split: new_indices are the tangents", &d, tangents, 16, &out, (uint32_t *)tangents, out.sources,
                 &out.appended, TBASIS_ERROR_OVERLAP);
    expect_split("split: NULL sources", &d, tangents, 16, &out, out.new_indices, NULL, &out.appended,
                 TBASIS_ERROR_NULL_POINTER);
    expect_split("split: new_indices over the mesh's indices", &d, tangents, 16, &out, (uint32_t *)indices,
                 out.sources, &out.appended, TBASIS_ERROR_OVERLAP);
    expect_split("split: appended_count inside sources", &d, tangents, 16, &out, out.new_indices, out.sources,
                 (size_t *)(out.sources + 2), TBASIS_ERROR_OVERLAP);
    /* On success, only the first *appended_count sources are written. */
    sentinel_fill(&out, sizeof out);
    if (expect_status("split: sources past the appended count",
                      tbasis_split_corners(&d, tangents, 16, out.new_indices, out.sources, &out.appended), TBASIS_OK)) {
        split_outputs fresh;
        sentinel_fill(&fresh, sizeof fresh);
        check(out.appended < corners &&
                  memcmp(out.sources + out.appended, fresh.sources + out.appended,
                         sizeof out.sources - 4 * out.appended) == 0,
              "split: a source past the %zu appended was written", out.appended);
    }
    indices[corners - 1] = (uint16_t)d.vertex_count;
    expect_split("split: index out of range", &d, tangents, 16, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    memcpy(indices, mesh_indices(m, TBASIS_INDEX_U16), 2 * corners);
    d.index_count = corners - 1;
    expect_split("split: index count", &d, tangents, 16, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_INVALID_INDEX_COUNT);
    d.index_count = corners;
    d.index_type = 7;
    expect_split("split: index type", &d, tangents, 16, &out, out.new_indices, out.sources, &out.appended,
                 TBASIS_ERROR_INVALID_INDEX_TYPE);

    /* 2^32 vertices (only vertex 0 is used, and the split reads no vertex attribute): a second
       tangent at vertex 0 would be vertex 2^32, past 32-bit indices; with one vertex fewer it is
       vertex 2^32 - 1, the last that fits. */
    if (sizeof(size_t) > 4) {
        static const uint32_t zeros[6] = {0, 0, 0, 0, 0, 0};
        static const float two_sides[6 * 4] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1,
                                               1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};
        tbasis_mesh huge = d;
        huge.vertex_count = (size_t)UINT32_MAX + 1;
        huge.indices = zeros;
        huge.index_count = 6;
        huge.index_type = TBASIS_INDEX_U32;
        huge.texcoords = NULL;
        expect_split("split: 2^32 + 1 vertices", &huge, two_sides, 16, &out, out.new_indices, out.sources,
                     &out.appended, TBASIS_ERROR_TOO_MANY_VERTICES);
        huge.vertex_count = UINT32_MAX;
        if (expect_status("split: 2^32 vertices",
                          tbasis_split_corners(&huge, two_sides, 16, out.new_indices, out.sources, &out.appended),
                          TBASIS_OK))
            check(out.appended == 1 && out.new_indices[3] == UINT32_MAX && out.new_indices[0] == 0 &&
                      out.sources[0] == 0,
                  "split: 2^32 vertices: %zu appended, corner 3 at %u", out.appended, (unsigned)out.new_indices[3]);
    }

    /* tbasis_copy_split_vertices: 6 vertices and 2 appended, 12 bytes each. */
    sentinel_fill(attribute, sizeof attribute);
    expect_status("copy: element larger than stride", tbasis_copy_split_vertices(attribute, 8, 12, 6, copy_sources, 2),
                  TBASIS_ERROR_INVALID_STRIDE);
    expect_status("copy: NULL attribute", tbasis_copy_split_vertices(NULL, 12, 12, 6, copy_sources, 2),
                  TBASIS_ERROR_NULL_POINTER);
    expect_status("copy: NULL sources", tbasis_copy_split_vertices(attribute, 12, 12, 6, NULL, 2),
                  TBASIS_ERROR_NULL_POINTER);
    expect_status("copy: stride SIZE_MAX", tbasis_copy_split_vertices(attribute, SIZE_MAX, 12, 6, copy_sources, 2),
                  TBASIS_ERROR_SIZE_OVERFLOW);
    expect_status("copy: sources inside the attribute",
                  tbasis_copy_split_vertices(attribute, 12, 12, 6, (const uint32_t *)(attribute + 3), 2),
                  TBASIS_ERROR_OVERLAP);
    copy_sources[1] = 6;
    expect_status("copy: source out of range", tbasis_copy_split_vertices(attribute, 12, 12, 6, copy_sources, 2),
                  TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    check(sentinel_intact(attribute, sizeof attribute), "copy: the attribute changed on error");
    /* With nothing to copy, the pointers may be NULL; the sources are still checked. */
    expect_status("copy: element size 0, NULL attribute, source out of range",
                  tbasis_copy_split_vertices(NULL, 12, 0, 6, copy_sources, 2), TBASIS_ERROR_INDEX_OUT_OF_RANGE);
    copy_sources[1] = 5;
    expect_status("copy: element size 0, NULL attribute", tbasis_copy_split_vertices(NULL, 12, 0, 6, copy_sources, 2),
                  TBASIS_OK);
    expect_status("copy: nothing appended, NULL buffers", tbasis_copy_split_vertices(NULL, 12, 12, 6, NULL, 0),
                  TBASIS_OK);
    if (expect_status("copy", tbasis_copy_split_vertices(attribute, 12, 12, 6, copy_sources, 2), TBASIS_OK))
        check(memcmp(attribute + 18, attribute, 12) == 0 && memcmp(attribute + 21, attribute + 15, 12) == 0,
              "copy: appended vertices are not copies of their sources");

    /* A stride larger than the element: the bytes between elements are left as they were. */
    {
        float padded[8 * 4], before[8 * 4];
        size_t v;
        int gaps_intact = 1;
        sentinel_fill(padded, sizeof padded);
        for (v = 0; v < 6; v++)
            padded[4 * v] = (float)v;
        memcpy(before, padded, sizeof padded);
        if (expect_status("copy: stride 16, element 12", tbasis_copy_split_vertices(padded, 16, 12, 6, copy_sources, 2),
                          TBASIS_OK)) {
            for (v = 0; v < 8; v++)
                gaps_intact &= memcmp(&padded[4 * v + 3], &before[4 * v + 3], sizeof(float)) == 0;
            check(padded[24] == 0.0f && padded[28] == 5.0f && gaps_intact,
                  "copy: stride 16: the copies or the gaps between elements are wrong");
        }
    }
}
