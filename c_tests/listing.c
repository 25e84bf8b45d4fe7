/*
 * The listing, operation for operation. Every float expression below keeps the listing's operand
 * order; the file must be compiled with -ffp-contract=off so that no multiply-add is fused, and
 * with SSE arithmetic (no excess precision), or the bits stop matching.
 */
#include "listing.h"

#include <float.h>
#include <math.h>
#include <stdlib.h>

#if FLT_EVAL_METHOD != 0
#error "the port needs float arithmetic evaluated in float (FLT_EVAL_METHOD == 0)"
#endif

enum index_kind { UNINDEXED, INDEX_U16, INDEX_U32 };

typedef struct {
    float x, y, z;
} vec3;

static long corner(const void *triangle, enum index_kind kind, long k)
{
    switch (kind) {
    case INDEX_U16:
        return ((const uint16_t *)triangle)[k];
    case INDEX_U32:
        return (long)((const uint32_t *)triangle)[k];
    default:
        return k;
    }
}

static vec3 load3(const float *packed, long i)
{
    vec3 v;
    v.x = packed[3 * i];
    v.y = packed[3 * i + 1];
    v.z = packed[3 * i + 2];
    return v;
}

static void add_to(vec3 *sum, vec3 v)
{
    sum->x += v.x;
    sum->y += v.y;
    sum->z += v.z;
}

/* The listing's Dot: summed left to right. */
static float dot(vec3 a, vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

static vec3 cross(vec3 a, vec3 b)
{
    vec3 c;
    c.x = a.y * b.z - a.z * b.y;
    c.y = a.z * b.x - a.x * b.z;
    c.z = a.x * b.y - a.y * b.x;
    return c;
}

static long calculate(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                      long triangleCount, const void *triangle, enum index_kind kind, float *tangent)
{
    long zero_determinants = 0;
    long a;
    /* tan1 sums dP/du, tan2 dP/dv; calloc stands in for new + ZeroMemory (one extra vec3 so an
       empty mesh still allocates). */
    vec3 *tan1 = calloc((size_t)vertexCount * 2 + 1, sizeof(vec3));
    vec3 *tan2;
    if (tan1 == NULL)
        return -1;
    tan2 = tan1 + vertexCount;

    for (a = 0; a < triangleCount; a++) {
        long i1 = corner(triangle, kind, 3 * a);
        long i2 = corner(triangle, kind, 3 * a + 1);
        long i3 = corner(triangle, kind, 3 * a + 2);

        vec3 v1 = load3(vertex, i1), v2 = load3(vertex, i2), v3 = load3(vertex, i3);
        const float *w1 = texcoord + 2 * i1;
        const float *w2 = texcoord + 2 * i2;
        const float *w3 = texcoord + 2 * i3;

        float x1 = v2.x - v1.x;
        float x2 = v3.x - v1.x;
        float y1 = v2.y - v1.y;
        float y2 = v3.y - v1.y;
        float z1 = v2.z - v1.z;
        float z2 = v3.z - v1.z;

        float s1 = w2[0] - w1[0];
        float s2 = w3[0] - w1[0];
        float t1 = w2[1] - w1[1];
        float t2 = w3[1] - w1[1];

        float det = s1 * t2 - s2 * t1;
        float r = 1.0f / det;
        vec3 sdir, tdir;
        sdir.x = (t2 * x1 - t1 * x2) * r;
        sdir.y = (t2 * y1 - t1 * y2) * r;
        sdir.z = (t2 * z1 - t1 * z2) * r;
        tdir.x = (s1 * x2 - s2 * x1) * r;
        tdir.y = (s1 * y2 - s2 * y1) * r;
        tdir.z = (s1 * z2 - s2 * z1) * r;

        zero_determinants += det == 0.0f;

        add_to(&tan1[i1], sdir);
        add_to(&tan1[i2], sdir);
        add_to(&tan1[i3], sdir);

        add_to(&tan2[i1], tdir);
        add_to(&tan2[i2], tdir);
        add_to(&tan2[i3], tdir);
    }

    for (a = 0; a < vertexCount; a++) {
        vec3 n = load3(normal, a);
        vec3 t = tan1[a];
        float d = dot(n, t);
        vec3 g;
        float inverse_length;

        /* Gram-Schmidt orthogonalize, then Normalize() as a multiply by the reciprocal length. */
        g.x = t.x - n.x * d;
        g.y = t.y - n.y * d;
        g.z = t.z - n.z * d;
        inverse_length = 1.0f / sqrtf(g.x * g.x + g.y * g.y + g.z * g.z);
        tangent[4 * a] = g.x * inverse_length;
        tangent[4 * a + 1] = g.y * inverse_length;
        tangent[4 * a + 2] = g.z * inverse_length;

        /* Handedness. */
        tangent[4 * a + 3] = (dot(cross(n, t), tan2[a]) < 0.0f) ? -1.0f : 1.0f;
    }

    free(tan1);
    return zero_determinants;
}

long listing_tangents_u16(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                          long triangleCount, const uint16_t *triangle, float *tangent)
{
    return calculate(vertexCount, vertex, normal, texcoord, triangleCount, triangle, INDEX_U16, tangent);
}

long listing_tangents_u32(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                          long triangleCount, const uint32_t *triangle, float *tangent)
{
    return calculate(vertexCount, vertex, normal, texcoord, triangleCount, triangle, INDEX_U32, tangent);
}

long listing_tangents_unindexed(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                                float *tangent)
{
    return calculate(vertexCount, vertex, normal, texcoord, vertexCount / 3, NULL, UNINDEXED, tangent);
}
