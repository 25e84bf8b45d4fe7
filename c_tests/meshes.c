#include "meshes.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PI_F 3.14159265358979f

static int allocate(test_mesh *m, const char *name, long vertex_count, long triangle_count, int indexed)
{
    memset(m, 0, sizeof *m);
    snprintf(m->name, sizeof m->name, "%s", name);
    m->vertex_count = vertex_count;
    m->triangle_count = triangle_count;
    m->positions = calloc((size_t)vertex_count * 3 + 1, sizeof(float));
    m->normals = calloc((size_t)vertex_count * 3 + 1, sizeof(float));
    m->texcoords = calloc((size_t)vertex_count * 2 + 1, sizeof(float));
    if (indexed)
        m->indices32 = calloc((size_t)triangle_count * 3 + 1, sizeof(uint32_t));
    if (!m->positions || !m->normals || !m->texcoords || (indexed && !m->indices32)) {
        mesh_free(m);
        return -1;
    }
    return 0;
}

/* Fills indices16 from indices32 when every index fits. */
static int finish(test_mesh *m)
{
    long k;
    if (m->indices32 == NULL || m->vertex_count > 65536)
        return 0;
    m->indices16 = calloc((size_t)m->triangle_count * 3 + 1, sizeof(uint16_t));
    if (m->indices16 == NULL) {
        mesh_free(m);
        return -1;
    }
    for (k = 0; k < 3 * m->triangle_count; k++)
        m->indices16[k] = (uint16_t)m->indices32[k];
    return 0;
}

static void set3(float *packed, long i, float x, float y, float z)
{
    packed[3 * i] = x;
    packed[3 * i + 1] = y;
    packed[3 * i + 2] = z;
}

static void set_unit3(float *packed, long i, float x, float y, float z)
{
    float inverse = 1.0f / sqrtf(x * x + y * y + z * z);
    set3(packed, i, x * inverse, y * inverse, z * inverse);
}

/* Two triangles per cell of a (columns + 1) x (rows + 1) vertex lattice, the diagonal alternating
   so both splits occur. */
static void lattice_triangles(uint32_t *out, int columns, int rows)
{
    int i, j;
    long k = 0;
    for (j = 0; j < rows; j++) {
        for (i = 0; i < columns; i++) {
            uint32_t a = (uint32_t)(j * (columns + 1) + i), b = a + 1;
            uint32_t c = a + (uint32_t)(columns + 1), d = c + 1;
            if ((i + j) % 2 == 0) {
                uint32_t tri[6] = {a, b, d, a, d, c};
                memcpy(out + k, tri, sizeof tri);
            } else {
                uint32_t tri[6] = {a, b, c, b, d, c};
                memcpy(out + k, tri, sizeof tri);
            }
            k += 6;
        }
    }
}

/* Deterministic jitter in [-0.5, 0.5) so coordinates are not all round numbers. */
static float jitter(unsigned long *state)
{
    *state = *state * 6364136223846793005UL + 1442695040888963407UL;
    return (float)((*state >> 40) & 0xFFFFFF) / 16777216.0f - 0.5f;
}

int mesh_grid(test_mesh *m, int columns, int rows, int degenerate)
{
    long lattice = (long)(columns + 1) * (rows + 1);
    unsigned long seed = 12345;
    int i, j;
    if (allocate(m, degenerate ? "grid_degenerate" : "grid", lattice + (degenerate != 0),
                 2L * columns * rows, 1) != 0)
        return -1;
    for (j = 0; j <= rows; j++) {
        for (i = 0; i <= columns; i++) {
            long v = (long)j * (columns + 1) + i;
            float x = ((float)i + 0.3f * jitter(&seed)) / (float)columns * 4.0f;
            float y = ((float)j + 0.3f * jitter(&seed)) / (float)rows * 3.0f;
            float z = 0.25f * sinf(1.7f * x) * cosf(2.3f * y);
            float dzdx = 0.25f * 1.7f * cosf(1.7f * x) * cosf(2.3f * y);
            float dzdy = -0.25f * 2.3f * sinf(1.7f * x) * sinf(2.3f * y);
            float u = fabsf((float)i / (float)columns - 0.5f) * 2.0f;
            float vv = (float)j / (float)rows * 1.5f;
            set3(m->positions, v, x, y, z);
            set_unit3(m->normals, v, -dzdx, -dzdy, 1.0f);
            if (degenerate && j >= rows / 3 && j <= rows / 3 + 2)
                vv = u; /* every UV of the band lies on one line */
            m->texcoords[2 * v] = u;
            m->texcoords[2 * v + 1] = vv;
        }
    }
    if (degenerate) {
        set3(m->positions, lattice, 9.0f, 9.0f, 9.0f);
        set3(m->normals, lattice, 0.0f, 0.0f, 1.0f);
    }
    lattice_triangles(m->indices32, columns, rows);
    return finish(m);
}

int mesh_torus(test_mesh *m, int rings, int sides)
{
    const float major = 1.0f, minor = 0.35f;
    int i, j;
    if (allocate(m, "torus", (long)(rings + 1) * (sides + 1), 2L * rings * sides, 1) != 0)
        return -1;
    for (j = 0; j <= sides; j++) {
        for (i = 0; i <= rings; i++) {
            long v = (long)j * (rings + 1) + i;
            float phi = 2.0f * PI_F * (float)i / (float)rings;
            float theta = 2.0f * PI_F * (float)j / (float)sides;
            float cp = cosf(phi), sp = sinf(phi), ct = cosf(theta), st = sinf(theta);
            set3(m->positions, v, (major + minor * ct) * cp, (major + minor * ct) * sp, minor * st);
            set_unit3(m->normals, v, ct * cp, ct * sp, st);
            m->texcoords[2 * v] = 3.0f * (float)i / (float)rings;
            m->texcoords[2 * v + 1] = (float)j / (float)sides;
        }
    }
    lattice_triangles(m->indices32, rings, sides);
    return finish(m);
}

int mesh_uv_sphere(test_mesh *m, int slices, int stacks, int pinched)
{
    int i, j;
    if (allocate(m, pinched ? "uv_sphere_pinched" : "uv_sphere", (long)(slices + 1) * (stacks + 1),
                 2L * slices * stacks, 1) != 0)
        return -1;
    for (j = 0; j <= stacks; j++) {
        for (i = 0; i <= slices; i++) {
            long v = (long)j * (slices + 1) + i;
            float theta = PI_F * (float)j / (float)stacks;
            float phi = 2.0f * PI_F * (float)i / (float)slices;
            float x = sinf(theta) * cosf(phi), y = sinf(theta) * sinf(phi), z = cosf(theta);
            float u = (float)i / (float)slices;
            set3(m->positions, v, 1.5f * x, 1.5f * y, 1.5f * z);
            set_unit3(m->normals, v, x, y, z);
            if (pinched && (j == 0 || j == stacks))
                u = 0.5f;
            m->texcoords[2 * v] = u;
            m->texcoords[2 * v + 1] = (float)j / (float)stacks;
        }
    }
    lattice_triangles(m->indices32, slices, stacks);
    return finish(m);
}

int mesh_unindexed(test_mesh *out, const test_mesh *in)
{
    char name[sizeof in->name + 16];
    long k;
    snprintf(name, sizeof name, "%s/unindexed", in->name);
    if (allocate(out, name, 3 * in->triangle_count, in->triangle_count, 0) != 0)
        return -1;
    for (k = 0; k < 3 * in->triangle_count; k++) {
        long v = in->indices32 ? (long)in->indices32[k] : k;
        memcpy(out->positions + 3 * k, in->positions + 3 * v, 3 * sizeof(float));
        memcpy(out->normals + 3 * k, in->normals + 3 * v, 3 * sizeof(float));
        memcpy(out->texcoords + 2 * k, in->texcoords + 2 * v, 2 * sizeof(float));
    }
    return 0;
}

void mesh_free(test_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->texcoords);
    free(m->indices32);
    free(m->indices16);
    memset(m, 0, sizeof *m);
}

tbasis_mesh mesh_description(const test_mesh *m, uint32_t index_type)
{
    tbasis_mesh d;
    memset(&d, 0, sizeof d);
    d.vertex_count = (size_t)m->vertex_count;
    d.positions = m->positions;
    d.positions_stride = 12;
    d.normals = m->normals;
    d.normals_stride = 12;
    d.texcoords = m->texcoords;
    d.texcoords_stride = 8;
    d.indices = mesh_indices(m, index_type);
    d.index_count = d.indices ? (size_t)(3 * m->triangle_count) : 0;
    d.index_type = index_type;
    return d;
}

const void *mesh_indices(const test_mesh *m, uint32_t index_type)
{
    return index_type == TBASIS_INDEX_U16 ? (const void *)m->indices16
           : index_type == TBASIS_INDEX_U32 ? (const void *)m->indices32
                                            : NULL;
}

const char *index_type_name(uint32_t index_type)
{
    return index_type == TBASIS_INDEX_U16 ? "u16" : index_type == TBASIS_INDEX_U32 ? "u32" : "unindexed";
}

size_t corner_count(const tbasis_mesh *d)
{
    return d->indices != NULL ? d->index_count : d->vertex_count;
}

size_t corner_vertex(const tbasis_mesh *d, size_t c)
{
    if (d->indices == NULL)
        return c;
    if (d->index_type == TBASIS_INDEX_U16)
        return ((const uint16_t *)d->indices)[c];
    return ((const uint32_t *)d->indices)[c];
}
