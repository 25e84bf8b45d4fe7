/* The status fixture: one valid call whose every buffer lives in one arena, so that a call made
   invalid on purpose can be checked to have written no byte of it. */
#ifndef FIXTURE_H
#define FIXTURE_H

#include "meshes.h"

enum { FIX_BUFFER = 1 << 15 };

/* Every byte a fixture call may legitimately read or write, compared whole after each error. */
typedef struct arena {
    unsigned char positions[FIX_BUFFER], normals[FIX_BUFFER], texcoords[FIX_BUFFER], indices[FIX_BUFFER];
    unsigned char tangents[FIX_BUFFER], bitangents[FIX_BUFFER], scratch[FIX_BUFFER];
} arena;

typedef struct fixture {
    arena memory, before;
    const test_mesh *source; /* small, with u16 indices */
    tbasis_mesh mesh;
    tbasis_options options;
    tbasis_output output;
    const tbasis_mesh *mesh_arg;
    const tbasis_output *output_arg;
} fixture;

/* A valid call (method LENGYEL, policy INHERIT): packed inputs with u16 indices, tangents and
   bitangents behind guard bytes, every other byte the sentinel pattern. */
void fixture_reset(fixture *f);

/* The same triangles as u32 indices. */
void fixture_use_u32(fixture *f);

#endif
