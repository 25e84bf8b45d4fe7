// An engine-style vertex buffer: positions, normals, UVs and tangents interleaved in one
// std::vector<Vertex>, with the tangents written in place by one tbasis_generate call. The mesh
// is a cube of 24 vertices (4 per face, so each face keeps its own normal and UVs) and 36 indices;
// two faces have their texture mirrored, so their tangents must have w = -1.
//
//   c++ -std=c++11 -Wall -Wextra -Werror -pedantic interleaved.cpp $(pkg-config --cflags --libs tbasis)
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "tbasis.h"

struct Vertex {
    float position[3];
    float normal[3];
    float uv[2];
    float tangent[4];
};

// Writes the tangents into the same vertex array the positions, normals and UVs come from.
static tbasis_status compute_tangents(std::vector<Vertex>& vertices, const std::vector<uint32_t>& indices)
{
    if (vertices.empty())
        return TBASIS_OK;  // data() may be null: no member to point at
    tbasis_mesh mesh = {};
    mesh.vertex_count = vertices.size();
    mesh.positions = vertices.data()->position;
    mesh.positions_stride = sizeof(Vertex);
    mesh.normals = vertices.data()->normal;
    mesh.normals_stride = sizeof(Vertex);
    mesh.texcoords = vertices.data()->uv;
    mesh.texcoords_stride = sizeof(Vertex);
    mesh.indices = indices.data();
    mesh.index_count = indices.size();
    mesh.index_type = TBASIS_INDEX_U32;

    tbasis_output output = {};
    output.tangents = vertices.data()->tangent;
    output.tangents_stride = sizeof(Vertex);

    return tbasis_generate(&mesh, nullptr /* defaults */, &output, nullptr);
}

namespace {

struct Vec3 {
    float x, y, z;
};

Vec3 cross(Vec3 a, Vec3 b)
{
    return Vec3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

float dot(Vec3 a, Vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}

Vec3 scale(Vec3 a, float s)
{
    return Vec3{a.x * s, a.y * s, a.z * s};
}

// A face of the cube [-1, 1]^3: its normal and two edge directions with cross(along, up) ==
// normal, so the corners below wind counterclockwise seen from outside.
struct Face {
    Vec3 normal, along, up;
    bool mirrored;  // u runs along -along instead of +along
};

const Face faces[6] = {
    {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}, false},
    {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}, true},
    {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}, false},
    {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}, false},
    {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}, false},
    {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}, true},
};

void build_cube(std::vector<Vertex>& vertices, std::vector<uint32_t>& indices)
{
    static const float corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const Face& face : faces) {
        const uint32_t first = static_cast<uint32_t>(vertices.size());
        for (const auto& corner : corners) {
            const float s = corner[0], t = corner[1];
            Vertex v = {};
            v.position[0] = face.normal.x + s * face.along.x + t * face.up.x;
            v.position[1] = face.normal.y + s * face.along.y + t * face.up.y;
            v.position[2] = face.normal.z + s * face.along.z + t * face.up.z;
            v.normal[0] = face.normal.x;
            v.normal[1] = face.normal.y;
            v.normal[2] = face.normal.z;
            v.uv[0] = face.mirrored ? (1 - s) / 2 : (1 + s) / 2;
            v.uv[1] = (1 + t) / 2;
            vertices.push_back(v);
        }
        const uint32_t quad[6] = {0, 1, 2, 0, 2, 3};
        for (uint32_t corner : quad)
            indices.push_back(first + corner);
    }
}

bool near(float a, float b)
{
    return std::fabs(a - b) <= 1e-5f;  // false for NaN
}

}  // namespace

int main()
{
    std::vector<Vertex> vertices;
    std::vector<uint32_t> indices;
    build_cube(vertices, indices);
    if (vertices.size() != 24 || indices.size() != 36) {
        std::fprintf(stderr, "interleaved: built %zu vertices and %zu indices\n", vertices.size(), indices.size());
        return 1;
    }
    const std::vector<Vertex> before = vertices;

    const tbasis_status status = compute_tangents(vertices, indices);
    if (status != TBASIS_OK) {
        std::fprintf(stderr, "interleaved: tbasis_generate: %s\n", tbasis_status_string(status));
        return 1;
    }

    int failures = 0;
    for (size_t i = 0; i < vertices.size(); ++i) {
        const Vertex& v = vertices[i];
        const Face& face = faces[i / 4];
        const Vec3 t{v.tangent[0], v.tangent[1], v.tangent[2]};
        const float w = v.tangent[3];
        // u grows along the tangent; v grows along w * cross(normal, tangent).
        const Vec3 expected = face.mirrored ? scale(face.along, -1) : face.along;
        const float expected_w = dot(cross(face.normal, expected), face.up) > 0 ? 1.0f : -1.0f;
        const char* problem = nullptr;
        if (!near(dot(t, t), 1))
            problem = "not unit length";
        else if (!near(dot(t, face.normal), 0))
            problem = "not orthogonal to the normal";
        else if (w != 1 && w != -1)
            problem = "|w| is not 1";
        else if (!near(dot(t, expected), 1) || w != expected_w)
            problem = "not the direction of increasing u";
        for (int k = 0; k < 3 && !problem; ++k) {
            if (v.position[k] != before[i].position[k] || v.normal[k] != before[i].normal[k])
                problem = "an input changed";
        }
        if (!problem && (v.uv[0] != before[i].uv[0] || v.uv[1] != before[i].uv[1]))
            problem = "an input changed";
        if (problem) {
            std::fprintf(stderr, "interleaved: vertex %zu: tangent (%g, %g, %g, %g) %s; expected (%g, %g, %g, %g)\n",
                         i, t.x, t.y, t.z, w, problem, expected.x, expected.y, expected.z, expected_w);
            ++failures;
        }
    }
    if (failures != 0)
        return 1;
    std::printf("interleaved: %zu vertices, %zu tangents written in place, ok\n", vertices.size(),
                vertices.size());
    return 0;
}
