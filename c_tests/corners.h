/* Per-corner output through the C ABI (tbasis_generate_corners) and scratch sizes per method. */
#ifndef CORNERS_H
#define CORNERS_H

#include "meshes.h"

/* The defaults and LENGYEL+LEGACY (`every_method`: every per-vertex method with policies LEGACY,
   SKIP and INHERIT) on `m` in each index form: each corner has exactly tbasis_generate's bits for
   its vertex, except that a corner at a vertex used with both UV orientations (a mirror fold) may
   have a valid frame of the opposite handedness instead. `clean_fold`: the mesh's folds have no
   degenerate triangle and normals facing the winding, so there every corner's w must be its own
   triangle's UV orientation. Also caller scratch. */
void test_corners(const test_mesh *m, int clean_fold, int every_method);

/* Every status tbasis_generate_corners validates, for the per-vertex methods and
   TBASIS_METHOD_MIKKTSPACE, each error writing no byte; `m` is small and has u16 indices. */
void test_corner_statuses(const test_mesh *m);

/* tbasis_scratch_size for every method and index form, and its SIZE_MAX cases. */
void test_scratch_sizes(const test_mesh *m);

#endif
