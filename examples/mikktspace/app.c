/*
 * A program written against mikktspace.h, as engines and tools that vendor mikktspace.c are:
 * tangents for a quad and a triangle through genTangSpaceDefault, printed per face vertex.
 *
 * Before, with mikktspace.c compiled in (app.c, mikktspace.c and mikktspace.h in one folder):
 *   cc -O2 app.c mikktspace.c -lm -o app
 *   ./app
 * After, relinked to tbasis's drop-in: mikktspace.c dropped from the build, app.c and
 * mikktspace.h unchanged (tbasis is a clone of its repository, built with `cargo build --release`):
 *   cc -O2 app.c -Ltbasis/target/release -ltbasis_mikktspace -o app
 *   LD_LIBRARY_PATH=tbasis/target/release ./app
 * or statically:
 *   cc -O2 app.c tbasis/target/release/libtbasis_mikktspace.a -lpthread -ldl -lm -o app
 *   ./app
 *
 * Each build prints the same lines (tests/mikktspace_dropin.rs runs these commands; with CMake,
 * tests/install.rs builds CMakeLists.txt beside this file both ways).
 */
#include <stdio.h>

#include "mikktspace.h"

/* Face 0 a quad, face 1 a triangle sharing its edge 1-2, face 2 a pentagon, which mikktspace.c
   ignores. Each face vertex indexes these arrays. */
static const float positions[7][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0.2f}, {0, 1, 0}, {2, 0.5f, 0.3f},
                                      {3, 0, 0}, {4, 0, 0}};
static const float texcoords[7][2] = {{0, 0}, {0.5f, 0}, {0.5f, 0.5f}, {0, 0.5f}, {0.8f, 0.3f}, {1, 0}, {1, 1}};
static const int faces[3][5] = {{0, 1, 2, 3, -1}, {1, 4, 2, -1, -1}, {1, 5, 6, 4, 2}};
static const int face_sizes[3] = {4, 3, 5};

static int get_num_faces(const SMikkTSpaceContext *context)
{
    (void)context;
    return 3;
}

static int get_num_vertices_of_face(const SMikkTSpaceContext *context, const int face)
{
    (void)context;
    return face_sizes[face];
}

static void get_position(const SMikkTSpaceContext *context, float out[], const int face, const int vert)
{
    int k;
    (void)context;
    for (k = 0; k < 3; k++)
        out[k] = positions[faces[face][vert]][k];
}

static void get_normal(const SMikkTSpaceContext *context, float out[], const int face, const int vert)
{
    (void)context;
    (void)face;
    (void)vert;
    out[0] = 0.0f;
    out[1] = 0.0f;
    out[2] = 1.0f;
}

static void get_tex_coord(const SMikkTSpaceContext *context, float out[], const int face, const int vert)
{
    (void)context;
    out[0] = texcoords[faces[face][vert]][0];
    out[1] = texcoords[faces[face][vert]][1];
}

static void set_tspace_basic(const SMikkTSpaceContext *context, const float tangent[], const float sign,
                             const int face, const int vert)
{
    int *calls = (int *)context->m_pUserData;
    ++*calls;
    printf("face %d vertex %d: tangent (%.9g, %.9g, %.9g), sign %+.0f\n", face, vert, tangent[0], tangent[1],
           tangent[2], sign);
}

int main(void)
{
    SMikkTSpaceInterface interface = {0};
    SMikkTSpaceContext context;
    int calls = 0, result;
    interface.m_getNumFaces = get_num_faces;
    interface.m_getNumVerticesOfFace = get_num_vertices_of_face;
    interface.m_getPosition = get_position;
    interface.m_getNormal = get_normal;
    interface.m_getTexCoord = get_tex_coord;
    interface.m_setTSpaceBasic = set_tspace_basic;
    context.m_pInterface = &interface;
    context.m_pUserData = &calls;
    result = genTangSpaceDefault(&context);
    printf("genTangSpaceDefault returned %d after %d tangents\n", result, calls);
    return result == 1 ? 0 : 1;
}
