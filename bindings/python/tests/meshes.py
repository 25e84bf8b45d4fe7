"""Test meshes and checks shared by the binding's tests."""

from dataclasses import dataclass

import numpy as np

VERTEX = np.dtype([("position", "<f4", 3), ("normal", "<f4", 3), ("uv", "<f4", 2), ("tangent", "<f4", 4)])


@dataclass
class Mesh:
    positions: np.ndarray  # (n, 3) float32
    normals: np.ndarray  # (n, 3) float32
    uvs: np.ndarray  # (n, 2) float32
    indices: np.ndarray  # (3m,) uint32
    true_tangents: np.ndarray  # (n, 3) float64, the analytic dP/du direction

    @property
    def count(self):
        return len(self.positions)

    def interleaved(self, dtype=VERTEX):
        """The same mesh as one structured array, tangents zeroed."""
        vertices = np.zeros(self.count, dtype=dtype)
        vertices["position"] = self.positions
        vertices["normal"] = self.normals
        vertices["uv"] = self.uvs
        return vertices


def torus(nu=24, nv=12, jitter=0.0, seed=1, random_diagonals=False):
    """A UV-mapped torus (seam vertices duplicated): analytic normals, w = +1 everywhere."""
    rng = np.random.default_rng(seed)
    u, v = np.meshgrid(np.arange(nu + 1) / nu, np.arange(nv + 1) / nv, indexing="ij")
    a, b = 2 * np.pi * u.ravel(), 2 * np.pi * v.ravel()
    ring = np.stack([np.cos(a), np.sin(a), np.zeros_like(a)], axis=1)
    up = np.array([0.0, 0.0, 1.0])
    positions = (1.0 + 0.35 * np.cos(b))[:, None] * ring + (0.35 * np.sin(b))[:, None] * up
    positions += jitter * rng.standard_normal(positions.shape)
    normals = np.cos(b)[:, None] * ring + np.sin(b)[:, None] * up
    uvs = np.stack([u.ravel(), v.ravel()], axis=1)
    true_tangents = np.stack([-np.sin(a), np.cos(a), np.zeros_like(a)], axis=1)

    triangles = []
    for i in range(nu):
        for j in range(nv):
            p, q = i * (nv + 1) + j, (i + 1) * (nv + 1) + j
            c00, c10, c11, c01 = p, q, q + 1, p + 1
            if random_diagonals and rng.random() < 0.5:
                triangles += [(c00, c10, c01), (c10, c11, c01)]
            else:
                triangles += [(c00, c10, c11), (c00, c11, c01)]
    return Mesh(
        positions.astype(np.float32),
        normals.astype(np.float32),
        uvs.astype(np.float32),
        np.array(triangles, dtype=np.uint32).ravel(),
        true_tangents,
    )


def collapse_uvs_around(mesh, vertex):
    """Gives `vertex` and its neighbours one UV, so every triangle at `vertex` is degenerate."""
    triangles = mesh.indices.reshape(-1, 3)
    around = np.unique(triangles[(triangles == vertex).any(axis=1)])
    mesh.uvs[around] = mesh.uvs[vertex]
    return around


def zero_uv_area_triangles(mesh):
    """Indices of triangles whose UV determinant is exactly zero."""
    t = mesh.uvs[mesh.indices.reshape(-1, 3)].astype(np.float64)
    e1, e2 = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]
    return np.flatnonzero(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] == 0)


def assert_frames(tangents, normals, rows=slice(None)):
    """Every (selected) tangent is unit length, orthogonal to its normal, with w exactly ±1."""
    t = tangents[rows].astype(np.float64)
    n = normals[rows].astype(np.float64)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    assert np.all(np.isfinite(t))
    np.testing.assert_allclose(np.linalg.norm(t[:, :3], axis=1), 1.0, atol=1e-5)
    np.testing.assert_allclose(np.einsum("ij,ij->i", t[:, :3], n), 0.0, atol=1e-5)
    assert np.all(np.abs(t[:, 3]) == 1.0)


def same_bits(a, b):
    """Bitwise equality of two float32 arrays (NaN payloads and signed zeros included)."""
    a, b = np.ascontiguousarray(a), np.ascontiguousarray(b)
    return a.shape == b.shape and np.array_equal(a.view(np.uint32), b.view(np.uint32))
