#include "fixture.h"

#include "check.h"

#include <string.h>

void fixture_reset(fixture *f)
{
    const test_mesh *m = f->source;
    arena *a = &f->memory;
    sentinel_fill(a, sizeof *a);
    memcpy(a->positions, m->positions, 12 * (size_t)m->vertex_count);
    memcpy(a->normals, m->normals, 12 * (size_t)m->vertex_count);
    memcpy(a->texcoords, m->texcoords, 8 * (size_t)m->vertex_count);
    memcpy(a->indices, m->indices16, 6 * (size_t)m->triangle_count);
    f->mesh = mesh_description(m, TBASIS_INDEX_U16);
    f->mesh.positions = a->positions;
    f->mesh.normals = a->normals;
    f->mesh.texcoords = a->texcoords;
    f->mesh.indices = a->indices;
    memset(&f->options, 0, sizeof f->options);
    f->options.method = TBASIS_METHOD_LENGYEL;
    f->options.degenerate_policy = TBASIS_DEGENERATE_INHERIT;
    memset(&f->output, 0, sizeof f->output);
    f->output.tangents = a->tangents + GUARD_BYTES;
    f->output.tangents_stride = 16;
    f->output.bitangents = a->bitangents + GUARD_BYTES;
    f->output.bitangents_stride = 12;
    f->mesh_arg = &f->mesh;
    f->output_arg = &f->output;
}

void fixture_use_u32(fixture *f)
{
    memcpy(f->memory.indices, f->source->indices32, 12 * (size_t)f->source->triangle_count);
    f->mesh.index_type = TBASIS_INDEX_U32;
}
