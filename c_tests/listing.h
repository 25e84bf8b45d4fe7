/*
 * A C99 port of the listing CalculateTangentArray from Eric Lengyel, "Computing Tangent Space
 * Basis Vectors for an Arbitrary Mesh" (2001): the reference the library's LEGACY policy must
 * match bit for bit. Layouts are packed: 3 floats per position and normal, 2 per texcoord,
 * 4 per tangent (x, y, z, w).
 *
 * Each function returns the number of triangles whose UV determinant is exactly zero (where the
 * listing divides by zero), or -1 when its working memory cannot be allocated.
 */
#ifndef LISTING_H
#define LISTING_H

#include <stdint.h>

long listing_tangents_u16(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                          long triangleCount, const uint16_t *triangle, float *tangent);

long listing_tangents_u32(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                          long triangleCount, const uint32_t *triangle, float *tangent);

/* Unindexed: triangle a is vertices 3a, 3a+1, 3a+2 (vertexCount / 3 triangles). */
long listing_tangents_unindexed(long vertexCount, const float *vertex, const float *normal, const float *texcoord,
                                float *tangent);

#endif
