/* Test meshes as packed arrays, in indexed (uint16_t and uint32_t) and unindexed forms. */
#ifndef MESHES_H
#define MESHES_H

#include <stddef.h>
#include <stdint.h>

#include "tbasis.h"

typedef struct test_mesh {
    char name[64];
    long vertex_count;
    float *positions; /* x, y, z per vertex */
    float *normals;   /* x, y, z per vertex, unit length */
    float *texcoords; /* u, v per vertex */
    long triangle_count;
    uint32_t *indices32; /* 3 per triangle; NULL: unindexed, triangle a is vertices 3a..3a+2 */
    uint16_t *indices16; /* the same indices; NULL when unindexed or beyond 65536 vertices */
} test_mesh;

/* A wavy height field of columns x rows quads with U mirrored at the middle (a mirror fold).
   degenerate != 0 maps a band of rows onto the UV line v = u, so those triangles have a zero UV
   determinant and the listing writes inf/NaN, and appends one vertex no triangle uses. */
int mesh_grid(test_mesh *m, int columns, int rows, int degenerate);

/* A torus with the U/V seams duplicated; U tiles three times around the ring. */
int mesh_torus(test_mesh *m, int rings, int sides);

/* A UV sphere whose pole rows hold one vertex per slice, all at the pole: each triangle with two
   pole corners has no area (at the south pole, from sinf(pi) != 0, almost none), and pole vertices
   that only such triangles touch get NaN from the listing. pinched != 0 also gives all of a pole's
   vertices the same UV, so those triangles have a zero UV determinant too. */
int mesh_uv_sphere(test_mesh *m, int slices, int stacks, int pinched);

/* Every triangle corner of `in` as its own vertex, in triangle order. */
int mesh_unindexed(test_mesh *out, const test_mesh *in);

void mesh_free(test_mesh *m);

/* The packed description of a test mesh; index_type TBASIS_INDEX_U16, TBASIS_INDEX_U32 or 0
   (unindexed). */
tbasis_mesh mesh_description(const test_mesh *m, uint32_t index_type);

/* The mesh's index array of that type; NULL for 0 (unindexed). */
const void *mesh_indices(const test_mesh *m, uint32_t index_type);

/* The corners of a described mesh (index_count, or vertex_count when unindexed), and the vertex of
   corner c. */
size_t corner_count(const tbasis_mesh *d);
size_t corner_vertex(const tbasis_mesh *d, size_t c);

/* "u16", "u32" or "unindexed". */
const char *index_type_name(uint32_t index_type);

#endif
