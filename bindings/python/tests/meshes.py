"""Generated test meshes and checks on tangent frames."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

VERTEX = np.dtype([("position", "<f4", 3), ("normal", "<f4", 3), ("uv", "<f4", 2), ("tangent", "<f4", 4)])


@dataclass
class Mesh:
    positions: NDArray[np.float32]  # (n, 3)
    normals: NDArray[np.float32]  # (n, 3)
    uvs: NDArray[np.float32]  # (n, 2)
    indices: NDArray[np.uint32]  # (3m,)
    true_tangents: NDArray[np.float64]  # (n, 3), the analytic dP/du direction

    @property
    def count(self) -> int:
        return len(self.positions)

    def interleaved(self, dtype: np.dtype[Any] = VERTEX) -> NDArray[Any]:
        """The same mesh as one structured array, tangents zeroed."""
        vertices = np.zeros(self.count, dtype=dtype)
        vertices["position"] = self.positions
        vertices["normal"] = self.normals
        vertices["uv"] = self.uvs
        return vertices


def torus(nu: int = 24, nv: int = 12, jitter: float = 0.0, seed: int = 1, random_diagonals: bool = False) -> Mesh:
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

    p = np.arange(nu)[:, None] * (nv + 1) + np.arange(nv)[None, :]
    c00, c10 = p.ravel(), p.ravel() + nv + 1
    c11, c01 = c10 + 1, c00 + 1
    flip = rng.random(c00.size) < 0.5 if random_diagonals else np.zeros(c00.size, dtype=bool)
    first = np.where(flip[:, None], np.stack([c00, c10, c01], 1), np.stack([c00, c10, c11], 1))
    second = np.where(flip[:, None], np.stack([c10, c11, c01], 1), np.stack([c00, c11, c01], 1))
    triangles = np.stack([first, second], axis=1).reshape(-1, 3)
    return Mesh(
        positions.astype(np.float32),
        normals.astype(np.float32),
        uvs.astype(np.float32),
        triangles.astype(np.uint32).ravel(),
        true_tangents,
    )


def collapse_uvs_around(mesh: Mesh, vertex: int) -> NDArray[np.uint32]:
    """Gives ``vertex`` and its neighbours one UV, so every triangle at ``vertex`` is degenerate."""
    triangles = mesh.indices.reshape(-1, 3)
    around: NDArray[np.uint32] = np.unique(triangles[(triangles == vertex).any(axis=1)])
    mesh.uvs[around] = mesh.uvs[vertex]
    return around


def zero_uv_area_triangles(mesh: Mesh) -> NDArray[np.intp]:
    """Indices of triangles whose UV determinant is exactly zero."""
    t = mesh.uvs[mesh.indices.reshape(-1, 3)].astype(np.float64)
    e1, e2 = t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]
    return np.flatnonzero(e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] == 0)


def assert_frames(tangents: NDArray[Any], normals: NDArray[Any]) -> None:
    """Every tangent is unit length, orthogonal to its normal, with w exactly +1 or -1."""
    t = tangents.astype(np.float64)
    n = normals.astype(np.float64)
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    assert np.all(np.isfinite(t))
    np.testing.assert_allclose(np.linalg.norm(t[:, :3], axis=1), 1.0, atol=1e-5)
    np.testing.assert_allclose(np.einsum("ij,ij->i", t[:, :3], n), 0.0, atol=1e-5)
    assert np.all(np.abs(t[:, 3]) == 1.0)
