"""to_tangent_space and from_tangent_space over arrays of vectors."""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

import tbasis
from meshes import torus
from support import same_bits


def frames() -> tuple[NDArray[np.float32], NDArray[np.float32]]:
    mesh = torus(jitter=0.01, random_diagonals=True, seed=6)
    return mesh.normals, tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, flip_v=True)


def test_against_the_definition_in_double_precision() -> None:
    normals, tangents = frames()
    rng = np.random.default_rng(1)
    directions = rng.standard_normal((len(normals), 3)).astype(np.float32)
    local = tbasis.to_tangent_space(normals, tangents, directions)
    assert local.shape == directions.shape and local.dtype == np.float32
    n = normals.astype(np.float64)
    t = tangents[:, :3].astype(np.float64)
    b = tangents[:, 3:].astype(np.float64) * np.cross(n, t)
    matrices = np.stack([t, b, n], axis=2)  # columns T, B, N
    expected = np.linalg.solve(matrices, directions.astype(np.float64)[..., None])[..., 0]
    np.testing.assert_allclose(local, expected, rtol=1e-5, atol=1e-5)
    back = tbasis.from_tangent_space(normals, tangents, local)
    np.testing.assert_allclose(back, directions, rtol=1e-5, atol=1e-5)
    np.testing.assert_allclose(back, np.einsum("vij,vj->vi", matrices, local.astype(np.float64)), rtol=1e-5, atol=1e-6)


def test_broadcasting_in_place_output_and_single_vectors() -> None:
    normals, tangents = frames()
    light = np.array([0.0, 0.6, 0.8], dtype=np.float32)
    everywhere = tbasis.to_tangent_space(normals, tangents, light)
    assert everywhere.shape == normals.shape
    assert same_bits(everywhere, tbasis.to_tangent_space(normals, tangents, np.tile(light, (len(normals), 1))))
    for row in (0, 17, len(normals) - 1):
        assert same_bits(tbasis.to_tangent_space(normals[row], tangents[row], light), everywhere[row])
    assert tbasis.to_tangent_space([0, 0, 1], [1, 0, 0, -1], [0.0, 0.6, 0.8]).tolist() == [
        0.0,
        np.float32(-0.6),
        np.float32(0.8),
    ]

    directions = np.tile(light, (len(normals), 1))
    result = tbasis.to_tangent_space(normals, tangents, directions, out=directions)
    assert result is directions and same_bits(directions, everywhere)
    grid = tbasis.from_tangent_space(normals.reshape(5, -1, 3), tangents.reshape(5, -1, 4), [0, 0, 1])
    assert grid.shape == (5, len(normals) // 5, 3)
    np.testing.assert_allclose(grid.reshape(-1, 3), normals, atol=1e-7)
