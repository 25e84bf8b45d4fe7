/* Reader for the stability case file the Rust tests write (format: crates/test-support/src/cases.rs). */
#ifndef CASES_H
#define CASES_H

#include <stdint.h>

enum { REPORT_FIELDS = 6, CASE_POLICIES = 3 };

typedef struct stability_case {
    char *name;
    uint64_t vertex_count;
    float *positions; /* 3 per vertex */
    float *normals;   /* 3 per vertex */
    float *texcoords; /* 2 per vertex; NULL when the case has none */
    uint32_t *indices; /* NULL when unindexed */
    uint64_t index_count;
    /* Expected report for SKIP, INHERIT, REJECT: degenerate_triangles, first_degenerate_triangle,
       fallback_vertices, mirrored_vertices, unreferenced_vertices, inherited_vertices. */
    uint64_t expected[CASE_POLICIES][REPORT_FIELDS];
} stability_case;

/* Reads every case; returns 0, or -1 after printing why. */
int cases_read(const char *path, stability_case **cases, uint32_t *count);
void cases_free(stability_case *cases, uint32_t count);

#endif
