/*
 * A C99 program using an installed tbasis: checks that header and library versions agree, then
 * computes the tangents of a UV-mapped quad and checks them. Exits nonzero on any mismatch.
 *
 *   cmake -S examples/c -B build -DCMAKE_PREFIX_PATH=PREFIX && cmake --build build
 *   cc -std=c99 consumer.c $(pkg-config --cflags --libs tbasis)
 */
#include <stdio.h>

#include "tbasis.h"

int main(void)
{
    /* The unit square in the z = 0 plane, facing +z, with u along +x and v along +y: every
     * tangent must be (1, 0, 0) with w = +1. */
    static const float positions[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    static const float normals[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    static const float texcoords[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    static const float expected[4] = {1, 0, 0, 1};
    float tangents[4][4] = {{0}};
    tbasis_mesh mesh = {0};
    tbasis_output output = {0};
    tbasis_report report;
    tbasis_status status;
    size_t v;
    int c;

    if (tbasis_version() != TBASIS_VERSION) {
        fprintf(stderr, "consumer: header is version %lu but the library is %lu\n",
                (unsigned long)TBASIS_VERSION, (unsigned long)tbasis_version());
        return 1;
    }

    mesh.vertex_count = 4;
    mesh.positions = positions;
    mesh.positions_stride = sizeof positions[0];
    mesh.normals = normals;
    mesh.normals_stride = sizeof normals[0];
    mesh.texcoords = texcoords;
    mesh.texcoords_stride = sizeof texcoords[0];
    mesh.indices = indices;
    mesh.index_count = 6;
    mesh.index_type = TBASIS_INDEX_U16;
    output.tangents = tangents;
    output.tangents_stride = sizeof tangents[0];

    status = tbasis_generate(&mesh, NULL, &output, &report);
    if (status != TBASIS_OK) {
        fprintf(stderr, "consumer: tbasis_generate: %s\n", tbasis_status_string(status));
        return 1;
    }
    if (report.degenerate_triangles != 0 || report.fallback_vertices != 0) {
        fprintf(stderr, "consumer: %lu degenerate triangles, %lu fallback vertices on a plain quad\n",
                (unsigned long)report.degenerate_triangles, (unsigned long)report.fallback_vertices);
        return 1;
    }
    for (v = 0; v < 4; v++) {
        for (c = 0; c < 4; c++) {
            float error = tangents[v][c] - expected[c];
            if (!(error <= 1e-6f && error >= -1e-6f)) { /* NaN fails too */
                fprintf(stderr, "consumer: vertex %lu tangent (%g, %g, %g, %g), expected (%g, %g, %g, %g)\n",
                        (unsigned long)v, tangents[v][0], tangents[v][1], tangents[v][2], tangents[v][3],
                        expected[0], expected[1], expected[2], expected[3]);
                return 1;
            }
        }
    }
    printf("consumer: tbasis %d.%d.%d, 4 tangents ok\n", TBASIS_VERSION_MAJOR, TBASIS_VERSION_MINOR,
           TBASIS_VERSION_PATCH);
    return 0;
}
