"""Per-corner tangents, the seam split and apply_split."""

from __future__ import annotations

import numpy as np
import pytest

import tbasis
from meshes import Mesh, assert_frames, torus
from support import same_bits


def mirrored_torus() -> Mesh:
    """A torus whose UVs are mirrored on one half, the mirror line's vertices shared."""
    mesh = torus(nu=16, nv=8, jitter=0.002, random_diagonals=True, seed=4)
    u = mesh.uvs[:, 0]
    mesh.uvs[:, 0] = np.where(u > 0.5, 1.0 - u, u)
    return mesh


def test_mikktspace_per_corner_on_a_quad() -> None:
    positions = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
    normals = np.tile(np.array([0, 0, 1], dtype=np.float32), (4, 1))
    corners, report = tbasis.generate_corners(
        positions, normals, positions[:, :2], [[0, 1, 2], [0, 2, 3]], method=tbasis.Method.MIKKTSPACE, report=True
    )
    assert corners.shape == (6, 4) and np.all(corners == [1, 0, 0, 1])
    assert report.split_vertices == 0 and report.first_degenerate_triangle is None


@pytest.mark.parametrize("method", [m for m in tbasis.Method if m != tbasis.Method.MIKKTSPACE])
def test_per_vertex_methods_give_each_corner_its_vertexs_bits_off_folds(method: tbasis.Method) -> None:
    mesh = torus(jitter=0.01, random_diagonals=True, seed=9)
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    corners = tbasis.generate_corners(*args, method=method)
    assert same_bits(corners, tbasis.generate(*args, method=method)[mesh.indices])


def test_split_makes_per_corner_tangents_per_vertex() -> None:
    mesh = mirrored_torus()
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    corners, report = tbasis.generate_corners(*args, method="mikktspace", report=True)
    assert_frames(corners, mesh.normals[mesh.indices])
    assert np.any(corners[:, 3] == -1) and np.any(corners[:, 3] == 1)

    split = tbasis.split_corners(mesh.indices, mesh.count, corners)
    assert split.indices.dtype == np.uint32 and split.sources.dtype == np.uint32
    assert split.indices.shape == mesh.indices.shape and len(split.sources) > 0
    # The vertices that get copies are those whose corners disagree.
    assert report.split_vertices == len(np.unique(split.sources))
    assert np.array_equal(split.indices[split.indices < mesh.count], mesh.indices[split.indices < mesh.count])
    # Each appended vertex copies the vertex of the corners that moved to it.
    moved = split.indices >= mesh.count
    assert np.array_equal(split.sources[split.indices[moved] - mesh.count], mesh.indices[moved])

    grown = [tbasis.apply_split(a, split.sources) for a in (mesh.positions, mesh.normals, mesh.uvs)]
    assert [len(a) for a in grown] == [mesh.count + len(split.sources)] * 3
    assert same_bits(grown[0][mesh.count :], mesh.positions[split.sources])
    tangents = np.zeros((len(grown[0]), 4), dtype=np.float32)
    tangents[split.indices] = corners
    # Every corner now reads its own tangent through its vertex, and the split mesh needs no more.
    assert same_bits(tangents[split.indices], corners)
    again = tbasis.generate_corners(grown[0], grown[1], grown[2], split.indices, method="mikktspace")
    assert len(tbasis.split_corners(split.indices, len(grown[0]), again).sources) == 0


def test_split_keeps_the_index_shape_and_handles_unindexed_meshes() -> None:
    plus, minus = [1.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, -1.0]
    corners = np.array([plus, plus, plus, minus, minus, minus], dtype=np.float32)
    split = tbasis.split_corners(np.array([[0, 1, 2], [0, 2, 1]], dtype=np.uint16), 3, corners)
    assert split.indices.tolist() == [[0, 1, 2], [3, 4, 5]] and split.sources.tolist() == [0, 2, 1]
    # Unindexed, every corner is its own vertex: nothing to split.
    unindexed = tbasis.split_corners(None, 6, corners)
    assert unindexed.indices.tolist() == list(range(6)) and unindexed.sources.size == 0
    # Vertices beyond those the indices use keep their numbers; appended ones follow all of them.
    wide = tbasis.split_corners([0, 1, 2, 0, 2, 1], 1000, corners)
    assert wide.indices.tolist() == [0, 1, 2, 1000, 1001, 1002] and wide.sources.tolist() == [0, 2, 1]


def test_apply_split_grows_any_attribute() -> None:
    sources = np.array([2, 0, 2], dtype=np.uint32)
    colours = np.arange(12, dtype=np.uint8).reshape(3, 4)
    assert tbasis.apply_split(colours, sources).tolist() == colours.tolist() + [
        colours[2].tolist(),
        colours[0].tolist(),
        colours[2].tolist(),
    ]
    weights = np.arange(3.0)
    assert tbasis.apply_split(weights, sources).tolist() == [0.0, 1.0, 2.0, 2.0, 0.0, 2.0]
    records = np.zeros(3, dtype=[("joint", "<u2", 4), ("weight", "<f4", 4)])
    records["joint"][:, 0] = [7, 8, 9]
    assert tbasis.apply_split(records, sources)["joint"][:, 0].tolist() == [7, 8, 9, 9, 7, 9]
    assert tbasis.apply_split(weights, np.zeros(0, np.int64)).tolist() == weights.tolist()
