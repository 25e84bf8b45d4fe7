/*
 * The ABI this soname freezes (README, "ABI policy"), written down here rather than read from the
 * header: every constant's value, the layout of the four structs callers allocate, and every
 * function's type. A difference is a change the soname must follow; new constants and functions
 * are added to the tables when they are added to the header.
 */
#include "abi.h"

#include "check.h"
#include "tbasis.h"

#include <stddef.h>
#include <stdint.h>
#include <string.h>

/* The structs as this soname froze them: same field names, types and order. */
typedef struct frozen_mesh {
    size_t vertex_count;
    const void *positions;
    size_t positions_stride;
    const void *normals;
    size_t normals_stride;
    const void *texcoords;
    size_t texcoords_stride;
    const void *indices;
    size_t index_count;
    uint32_t index_type;
} frozen_mesh;

typedef struct frozen_options {
    uint32_t method;
    uint32_t degenerate_policy;
    uint32_t flags;
    uint32_t threads;
    float degenerate_threshold;
    void *scratch;
    size_t scratch_size;
} frozen_options;

typedef struct frozen_output {
    void *tangents;
    size_t tangents_stride;
    void *bitangents;
    size_t bitangents_stride;
} frozen_output;

typedef struct frozen_report {
    size_t degenerate_triangles;
    size_t first_degenerate_triangle;
    size_t fallback_vertices;
    size_t mirrored_vertices;
    size_t unreferenced_vertices;
    size_t inherited_vertices;
    size_t abnormal_normals;
    size_t repaired_corners;
    size_t split_vertices;
    size_t failed_triangle;
} frozen_report;

/* Every function, through a pointer of its frozen type: a changed signature does not compile
   (the harness builds with -Werror). */
static const struct {
    tbasis_status (*generate)(const struct tbasis_mesh *, const struct tbasis_options *,
                              const struct tbasis_output *, struct tbasis_report *);
    tbasis_status (*generate_corners)(const struct tbasis_mesh *, const struct tbasis_options *,
                                      void *, size_t, struct tbasis_report *);
    tbasis_status (*split_corners)(const struct tbasis_mesh *, const void *, size_t, uint32_t *,
                                   uint32_t *, size_t *);
    tbasis_status (*copy_split_vertices)(void *, size_t, size_t, size_t, const uint32_t *, size_t);
    tbasis_status (*calculate_tangent_array)(long, const float *, const float *, const float *,
                                             long, const uint16_t *, float *);
    size_t (*scratch_size)(const struct tbasis_mesh *, const struct tbasis_options *);
    const char *(*status_string)(tbasis_status);
    uint32_t (*version)(void);
    tbasis_status (*to_tangent_space)(const float *, const float *, const float *, float *);
    tbasis_status (*from_tangent_space)(const float *, const float *, const float *, float *);
} FUNCTIONS = {
    tbasis_generate,
    tbasis_generate_corners,
    tbasis_split_corners,
    tbasis_copy_split_vertices,
    tbasis_calculate_tangent_array,
    tbasis_scratch_size,
    tbasis_status_string,
    tbasis_version,
    tbasis_to_tangent_space,
    tbasis_from_tangent_space,
};

typedef struct constant {
    const char *name;
    unsigned long long value, frozen;
} constant;

#define FROZEN(name, value) {#name, (unsigned long long)(name), (value)}

static const constant CONSTANTS[] = {
    FROZEN(TBASIS_INDEX_U16, 1),
    FROZEN(TBASIS_INDEX_U32, 2),
    FROZEN(TBASIS_METHOD_LENGYEL, 1),
    FROZEN(TBASIS_METHOD_ANGLE, 2),
    FROZEN(TBASIS_METHOD_AREA, 3),
    FROZEN(TBASIS_METHOD_UNIFORM, 4),
    FROZEN(TBASIS_METHOD_MIKKTSPACE, 5),
    FROZEN(TBASIS_DEGENERATE_LEGACY, 1),
    FROZEN(TBASIS_DEGENERATE_SKIP, 2),
    FROZEN(TBASIS_DEGENERATE_INHERIT, 3),
    FROZEN(TBASIS_DEGENERATE_REJECT, 4),
    FROZEN(TBASIS_FLAG_FLIP_V, 1),
    FROZEN(TBASIS_NO_TRIANGLE, SIZE_MAX),
    FROZEN(TBASIS_OK, 0),
    FROZEN(TBASIS_ERROR_NULL_POINTER, 1),
    FROZEN(TBASIS_ERROR_INVALID_STRIDE, 2),
    FROZEN(TBASIS_ERROR_INVALID_INDEX_COUNT, 3),
    FROZEN(TBASIS_ERROR_INDEX_OUT_OF_RANGE, 4),
    FROZEN(TBASIS_ERROR_INVALID_INDEX_TYPE, 5),
    FROZEN(TBASIS_ERROR_UNKNOWN_METHOD, 6),
    FROZEN(TBASIS_ERROR_UNKNOWN_POLICY, 7),
    FROZEN(TBASIS_ERROR_UNKNOWN_FLAGS, 8),
    FROZEN(TBASIS_ERROR_SIZE_OVERFLOW, 9),
    FROZEN(TBASIS_ERROR_OVERLAP, 10),
    FROZEN(TBASIS_ERROR_DEGENERATE_UV, 11),
    FROZEN(TBASIS_ERROR_OUT_OF_MEMORY, 12),
    FROZEN(TBASIS_ERROR_SCRATCH_TOO_SMALL, 13),
    FROZEN(TBASIS_ERROR_INVALID_THRESHOLD, 14),
    FROZEN(TBASIS_ERROR_INVALID_COUNT, 15),
    FROZEN(TBASIS_ERROR_INTERNAL, 16),
    FROZEN(TBASIS_ERROR_INVALID_FRAME, 17),
    FROZEN(TBASIS_ERROR_TOO_MANY_VERTICES, 18),
    FROZEN(TBASIS_ERROR_NO_LEGACY_FORM, 19),
};

/* One field of a header struct against its frozen twin: offset and size. */
#define SAME_FIELD(type, frozen, field)                                                           \
    check(offsetof(type, field) == offsetof(frozen, field) &&                                     \
              sizeof(((type *)0)->field) == sizeof(((frozen *)0)->field),                         \
          "abi: " #type "." #field " at offset %zu, %zu bytes; frozen at %zu, %zu bytes",         \
          offsetof(type, field), sizeof(((type *)0)->field), offsetof(frozen, field),             \
          sizeof(((frozen *)0)->field))

#define SAME_SIZE(type, frozen)                                                                   \
    check(sizeof(type) == sizeof(frozen), "abi: sizeof(" #type ") is %zu, frozen at %zu",         \
          sizeof(type), sizeof(frozen))

void test_abi(void)
{
    size_t k;
    for (k = 0; k < sizeof CONSTANTS / sizeof CONSTANTS[0]; k++)
        check(CONSTANTS[k].value == CONSTANTS[k].frozen, "abi: %s is %llu, frozen at %llu",
              CONSTANTS[k].name, CONSTANTS[k].value, CONSTANTS[k].frozen);
    check(sizeof(tbasis_status) == 4, "abi: tbasis_status is %zu bytes, frozen at 4",
          sizeof(tbasis_status));
    /* The table holds every status the library knows: the one after its last is unknown. */
    check(strcmp(tbasis_status_string(TBASIS_ERROR_NO_LEGACY_FORM + 1), "unknown status") == 0,
          "abi: the library knows a status past the table");

    SAME_SIZE(tbasis_mesh, frozen_mesh);
    SAME_FIELD(tbasis_mesh, frozen_mesh, vertex_count);
    SAME_FIELD(tbasis_mesh, frozen_mesh, positions);
    SAME_FIELD(tbasis_mesh, frozen_mesh, positions_stride);
    SAME_FIELD(tbasis_mesh, frozen_mesh, normals);
    SAME_FIELD(tbasis_mesh, frozen_mesh, normals_stride);
    SAME_FIELD(tbasis_mesh, frozen_mesh, texcoords);
    SAME_FIELD(tbasis_mesh, frozen_mesh, texcoords_stride);
    SAME_FIELD(tbasis_mesh, frozen_mesh, indices);
    SAME_FIELD(tbasis_mesh, frozen_mesh, index_count);
    SAME_FIELD(tbasis_mesh, frozen_mesh, index_type);

    SAME_SIZE(tbasis_options, frozen_options);
    SAME_FIELD(tbasis_options, frozen_options, method);
    SAME_FIELD(tbasis_options, frozen_options, degenerate_policy);
    SAME_FIELD(tbasis_options, frozen_options, flags);
    SAME_FIELD(tbasis_options, frozen_options, threads);
    SAME_FIELD(tbasis_options, frozen_options, degenerate_threshold);
    SAME_FIELD(tbasis_options, frozen_options, scratch);
    SAME_FIELD(tbasis_options, frozen_options, scratch_size);

    SAME_SIZE(tbasis_output, frozen_output);
    SAME_FIELD(tbasis_output, frozen_output, tangents);
    SAME_FIELD(tbasis_output, frozen_output, tangents_stride);
    SAME_FIELD(tbasis_output, frozen_output, bitangents);
    SAME_FIELD(tbasis_output, frozen_output, bitangents_stride);

    SAME_SIZE(tbasis_report, frozen_report);
    SAME_FIELD(tbasis_report, frozen_report, degenerate_triangles);
    SAME_FIELD(tbasis_report, frozen_report, first_degenerate_triangle);
    SAME_FIELD(tbasis_report, frozen_report, fallback_vertices);
    SAME_FIELD(tbasis_report, frozen_report, mirrored_vertices);
    SAME_FIELD(tbasis_report, frozen_report, unreferenced_vertices);
    SAME_FIELD(tbasis_report, frozen_report, inherited_vertices);
    SAME_FIELD(tbasis_report, frozen_report, abnormal_normals);
    SAME_FIELD(tbasis_report, frozen_report, repaired_corners);
    SAME_FIELD(tbasis_report, frozen_report, split_vertices);
    SAME_FIELD(tbasis_report, frozen_report, failed_triangle);

    /* FUNCTIONS is checked as it compiles; nothing is left to check when it runs. */
    (void)FUNCTIONS;
}
