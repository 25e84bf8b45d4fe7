#include "check.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int provoked[LAST_STATUS + 1];

int expect_status(const char *what, tbasis_status got, tbasis_status want)
{
    if (got == want && want <= LAST_STATUS)
        provoked[want] = 1;
    return check(got == want, "%s: status %u (%s), expected %u (%s)", what, (unsigned)got, tbasis_status_string(got),
                 (unsigned)want, tbasis_status_string(want));
}

/* Varies with the position so a shifted or partial write cannot reproduce it. */
static unsigned char sentinel_byte(size_t i)
{
    return (unsigned char)(0xA5u ^ (i * 131u + (i >> 8)));
}

void sentinel_fill(void *buffer, size_t size)
{
    unsigned char *bytes = buffer;
    size_t i;
    for (i = 0; i < size; i++)
        bytes[i] = sentinel_byte(i);
}

/* Whether bytes [from, to) of a buffer filled by sentinel_fill still hold the pattern. */
static int pattern_holds(const unsigned char *bytes, size_t from, size_t to)
{
    size_t i;
    for (i = from; i < to; i++)
        if (bytes[i] != sentinel_byte(i))
            return 0;
    return 1;
}

int sentinel_intact(const void *buffer, size_t size)
{
    return pattern_holds(buffer, 0, size);
}

int guarded_alloc(guarded *g, size_t size)
{
    g->size = size;
    g->allocation = malloc(size + 2 * GUARD_BYTES);
    g->inner = g->allocation ? g->allocation + GUARD_BYTES : NULL;
    if (g->allocation)
        sentinel_fill(g->allocation, size + 2 * GUARD_BYTES);
    return g->allocation ? 0 : -1;
}

int guarded_intact(const guarded *g)
{
    return pattern_holds(g->allocation, 0, g->size + 2 * GUARD_BYTES);
}

int guards_intact(const guarded *g)
{
    return pattern_holds(g->allocation, 0, GUARD_BYTES) &&
           pattern_holds(g->allocation, GUARD_BYTES + g->size, g->size + 2 * GUARD_BYTES);
}

void guarded_reset(guarded *g)
{
    sentinel_fill(g->allocation, g->size + 2 * GUARD_BYTES);
}

void guarded_free(guarded *g)
{
    free(g->allocation);
    memset(g, 0, sizeof *g);
}

static uint32_t bits_of(float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof bits);
    return bits;
}

int check_float_bits(const char *what, const float *expected, const float *actual, size_t count)
{
    size_t i;
    if (memcmp(expected, actual, count * sizeof(float)) == 0)
        return check(1, "%s", what);
    for (i = 0; i < count && bits_of(expected[i]) == bits_of(actual[i]); i++)
        ;
    return check(0, "%s: float %zu of %zu is %08lx (%g), expected %08lx (%g)", what, i, count,
                 (unsigned long)bits_of(actual[i]), actual[i], (unsigned long)bits_of(expected[i]), expected[i]);
}

size_t count_nonfinite(const float *values, size_t count)
{
    size_t i, found = 0;
    for (i = 0; i < count; i++)
        found += !isfinite(values[i]);
    return found;
}

const char *bitangent_problem(const double n[3], const float t[4], const float b[3], double tolerance)
{
    double expected[3];
    int k;
    expected[0] = t[3] * (n[1] * t[2] - n[2] * t[1]);
    expected[1] = t[3] * (n[2] * t[0] - n[0] * t[2]);
    expected[2] = t[3] * (n[0] * t[1] - n[1] * t[0]);
    for (k = 0; k < 3; k++) {
        if (isnan(expected[k])) {
            if (!isnan(b[k]))
                return "bitangent is a number where w * cross(n, t) is NaN";
        } else if (!(fabs(b[k] - expected[k]) <= tolerance)) {
            return "bitangent differs from w * cross(n, t)";
        }
    }
    return NULL;
}

static double dot3(const double a[3], const double b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/* The tangent part of frame_problem; sets *usable_normal and, when it is set, unit_normal. */
static const char *tangent_check(const float n[3], const float t[4], int *usable_normal, double unit_normal[3])
{
    const double tolerance = 1e-5;
    double tangent[3], largest = 0.0, length;
    int k;
    *usable_normal = 1;
    for (k = 0; k < 3; k++) {
        tangent[k] = t[k];
        *usable_normal = *usable_normal && isfinite(n[k]);
        if (fabs(n[k]) > largest)
            largest = fabs(n[k]);
    }
    *usable_normal = *usable_normal && largest > 0.0;
    if (!(isfinite(tangent[0]) && isfinite(tangent[1]) && isfinite(tangent[2])))
        return "tangent is not finite";
    if (!(t[3] == 1.0f || t[3] == -1.0f))
        return "w is not exactly +1 or -1";
    if (!(fabs(sqrt(dot3(tangent, tangent)) - 1.0) <= tolerance))
        return "tangent is not unit length";
    if (*usable_normal) {
        /* Scaled by the largest component first, so tiny or huge normals normalize too. */
        double scaled[3];
        for (k = 0; k < 3; k++)
            scaled[k] = n[k] / largest;
        length = sqrt(dot3(scaled, scaled));
        for (k = 0; k < 3; k++)
            unit_normal[k] = scaled[k] / length;
        if (!(fabs(dot3(tangent, unit_normal)) <= tolerance))
            return "tangent is not orthogonal to the normal";
    }
    return NULL;
}

const char *tangent_problem(const float n[3], const float t[4])
{
    double unit_normal[3];
    int usable_normal;
    return tangent_check(n, t, &usable_normal, unit_normal);
}

const char *frame_problem(const float n[3], const float t[4], const float b[3])
{
    const double tolerance = 1e-5;
    double tangent[3], bitangent[3], unit_normal[3];
    int k, usable_normal;
    const char *problem = tangent_check(n, t, &usable_normal, unit_normal);
    if (problem != NULL)
        return problem;
    if (usable_normal)
        return bitangent_problem(unit_normal, t, b, tolerance);
    for (k = 0; k < 3; k++) {
        tangent[k] = t[k];
        bitangent[k] = b[k];
    }
    if (!(fabs(sqrt(dot3(bitangent, bitangent)) - 1.0) <= tolerance))
        return "bitangent is not unit length (unusable normal)";
    if (!(fabs(dot3(bitangent, tangent)) <= tolerance))
        return "bitangent is not orthogonal to the tangent (unusable normal)";
    return NULL;
}
