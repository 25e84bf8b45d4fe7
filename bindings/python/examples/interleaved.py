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
