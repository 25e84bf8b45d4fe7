/* Check counting and the comparisons every test group shares. */
#ifndef CHECK_H
#define CHECK_H

#include <stddef.h>

#include "counted.h"
#include "tbasis.h"

/* The highest status value the header defines. */
#define LAST_STATUS TBASIS_ERROR_NO_LEGACY_FORM

/* Which statuses some check has seen returned on purpose (main checks that each error was). */
extern int provoked[LAST_STATUS + 1];

/* One check: a call returned `want`; records it in `provoked`. Returns whether it did. */
int expect_status(const char *what, tbasis_status got, tbasis_status want);

/* A byte pattern no computation produces by accident, and whether a buffer still holds it. */
void sentinel_fill(void *buffer, size_t size);
int sentinel_intact(const void *buffer, size_t size);

/* Memory for `size` bytes between `guard` sentinel bytes on each side; sentinel_buffer_intact
   tests all of it. */
typedef struct guarded {
    unsigned char *allocation;
    size_t size;
    void *inner;
} guarded;
enum { GUARD_BYTES = 64 };
int guarded_alloc(guarded *g, size_t size);
int guarded_intact(const guarded *g);
/* Whether the guard bytes (not the inner bytes) still hold the pattern. */
int guards_intact(const guarded *g);
/* Refills all of it with the pattern. */
void guarded_reset(guarded *g);
void guarded_free(guarded *g);

/* One check: `count` floats bit for bit (memcmp), naming the first difference. */
int check_float_bits(const char *what, const float *expected, const float *actual, size_t count);

/* Number of non-finite values among `count` floats. */
size_t count_nonfinite(const float *values, size_t count);

/* NULL when bitangent b equals w * cross(n, t.xyz) to within `tolerance` per component (NaN where
   the product is NaN), else what is wrong. */
const char *bitangent_problem(const double n[3], const float t[4], const float b[3], double tolerance);

/* The library's promise for every policy but LEGACY: NULL when t is a finite unit tangent with w
   exactly +1 or -1, orthogonal to the normalized normal, and b = w * cross(n_unit, t); without a
   usable normal, b must still be a unit vector orthogonal to t. Else what is wrong. */
const char *frame_problem(const float n[3], const float t[4], const float b[3]);

/* frame_problem for a tangent alone (no bitangent written). */
const char *tangent_problem(const float n[3], const float t[4]);

#endif
