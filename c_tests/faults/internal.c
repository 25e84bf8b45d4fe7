/*
 * Every entry point returns TBASIS_ERROR_INTERNAL, and writes nothing (outputs and reports as they
 * were), when the library panics inside it: run against a library built with the test-only
 * feature fault-injection, with TBASIS_INJECT_PANIC set. Without it, the same calls succeed, so
 * the panic is what the statuses show. Prints "internal N" or "ok N" (N calls) and exits 0 when
 * every call agreed.
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tbasis.h"

int main(void)
{
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const float texcoords[] = {0, 0, 1, 0, 0, 1};
    const uint16_t triangle[] = {0, 1, 2};
    const uint32_t indices[] = {0, 1, 2};
    float tangents[12], corners[12], direction[3] = {1, 0, 0}, result[3] = {-7, -7, -7};
    float copy_target[6] = {1, 2, 3, 0, 0, 0};
    uint32_t new_indices[3], sources[3] = {0, 0, 0};
    size_t appended = 0;
    tbasis_mesh mesh;
    tbasis_output output;
    tbasis_status statuses[8];
    tbasis_report reports[2], untouched;
    const char *name[8] = {"tbasis_generate",          "tbasis_generate_corners",  "tbasis_split_corners",
                           "tbasis_copy_split_vertices", "tbasis_calculate_tangent_array",
                           "tbasis_to_tangent_space",   "tbasis_from_tangent_space", "tbasis_scratch_size"};
    int internal = getenv("TBASIS_INJECT_PANIC") != NULL, k, failed = 0;

    memset(&mesh, 0, sizeof mesh);
    mesh.vertex_count = 3;
    mesh.positions = positions;
    mesh.positions_stride = 12;
    mesh.normals = normals;
    mesh.normals_stride = 12;
    mesh.texcoords = texcoords;
    mesh.texcoords_stride = 8;
    mesh.indices = indices;
    mesh.index_count = 3;
    mesh.index_type = TBASIS_INDEX_U32;
    memset(&output, 0, sizeof output);
    output.tangents = tangents;
    output.tangents_stride = 16;
    memset(tangents, 0, sizeof tangents);
    memset(corners, 0, sizeof corners);

    memset(reports, 0x5A, sizeof reports);
    memset(&untouched, 0x5A, sizeof untouched);

    statuses[0] = tbasis_generate(&mesh, NULL, &output, &reports[0]);
    statuses[1] = tbasis_generate_corners(&mesh, NULL, corners, 16, &reports[1]);
    statuses[2] = tbasis_split_corners(&mesh, corners, 16, new_indices, sources, &appended);
    statuses[3] = tbasis_copy_split_vertices(copy_target, 12, 12, 1, sources, 1);
    statuses[4] = tbasis_calculate_tangent_array(3, positions, normals, texcoords, 1, triangle, tangents);
    statuses[5] = tbasis_to_tangent_space(normals, (const float[]){1, 0, 0, 1}, direction, result);
    statuses[6] = tbasis_from_tangent_space(normals, (const float[]){1, 0, 0, 1}, direction, result);
    /* tbasis_scratch_size answers SIZE_MAX where the others return a status. */
    statuses[7] = tbasis_scratch_size(&mesh, NULL) == SIZE_MAX ? TBASIS_ERROR_INTERNAL : TBASIS_OK;

    for (k = 0; k < 8; k++) {
        tbasis_status want = internal ? TBASIS_ERROR_INTERNAL : TBASIS_OK;
        if (statuses[k] != want) {
            printf("%s returned %u (%s), expected %u\n", name[k], statuses[k], tbasis_status_string(statuses[k]), want);
            failed = 1;
        }
    }
    if (internal) {
        static const float zero[12];
        if (memcmp(tangents, zero, sizeof tangents) != 0 || memcmp(corners, zero, sizeof corners) != 0 ||
            result[0] != -7 || appended != 0 || copy_target[3] != 0) {
            printf("an output was written although the call failed\n");
            failed = 1;
        }
        if (memcmp(&reports[0], &untouched, sizeof untouched) != 0 ||
            memcmp(&reports[1], &untouched, sizeof untouched) != 0) {
            printf("a report was written although the call failed\n");
            failed = 1;
        }
        if (strcmp(tbasis_status_string(TBASIS_ERROR_INTERNAL), "internal error") != 0) {
            printf("TBASIS_ERROR_INTERNAL is not named\n");
            failed = 1;
        }
    }
    printf("%s %d\n", internal ? "internal" : "ok", 8);
    return failed;
}
