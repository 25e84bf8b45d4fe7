"""The README's Python example: tangents written into the interleaved vertex array in place."""

import numpy as np

import tbasis

vertex = np.dtype([("position", "<f4", 3), ("normal", "<f4", 3), ("uv", "<f4", 2), ("tangent", "<f4", 4)])
vertices = np.zeros(4, dtype=vertex)
vertices["position"] = [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]]
vertices["normal"] = [0, 0, 1]
vertices["uv"] = [[0, 0], [1, 0], [1, 1], [0, 1]]
indices = np.array([0, 1, 2, 0, 2, 3], dtype=np.uint32)

# Each field is a strided view into `vertices`: read and written in place, nothing copied.
tbasis.generate(vertices["position"], vertices["normal"], vertices["uv"], indices, out=vertices["tangent"])
print(vertices["tangent"])  # [1, 0, 0, 1] for every vertex

# MikkTSpace per corner, glTF's V convention, and what the call found.
corners, report = tbasis.generate_corners(
    vertices["position"], vertices["normal"], vertices["uv"], indices, method="mikktspace", flip_v=True, report=True
)
print(corners[0], report.degenerate_triangles)  # [1, 0, 0, -1] 0

# An index past the last vertex: nothing is written, and the error names the index.
try:
    tbasis.generate(vertices["position"], vertices["normal"], vertices["uv"], indices + 1, out=vertices["tangent"])
except tbasis.IndexOutOfRangeError as error:
    print(error)  # index 5 (triangle 1, corner 2) is 4, not in range for 4 vertices
