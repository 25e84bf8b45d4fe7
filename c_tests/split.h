/* Seam splitting through the C ABI: tbasis_split_corners and tbasis_copy_split_vertices. */
#ifndef SPLIT_H
#define SPLIT_H

#include "meshes.h"

/* MIKKTSPACE corners of `m` (which has a mirror fold) in each index form, split: every corner's
   new vertex carries exactly the corner's tangent, no two output vertices share a source vertex
   and a tangent, each used vertex keeps its index for its first tangent, appended vertices copy
   their source's attributes (tbasis_copy_split_vertices), and the split's count is the report's
   split_vertices at least. */
void test_split(const test_mesh *m);

/* Every status the two functions validate, each error writing no byte. */
void test_split_statuses(const test_mesh *m);

#endif
