"""Memory layouts: strided fields of one vertex array read and written in place, every other
layout and dtype converted once, with the same bits."""

from __future__ import annotations

import tracemalloc
from typing import Any, Callable

import numpy as np
import pytest
from numpy.typing import NDArray

import tbasis
import tbasis._native
from meshes import VERTEX, Mesh, assert_frames, torus
from support import same_bits


@pytest.fixture(scope="module")
def mesh() -> Mesh:
    return torus(jitter=0.01, random_diagonals=True)


@pytest.fixture(scope="module")
def expected(mesh: Mesh) -> NDArray[np.float32]:
    return tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)


def address(array: NDArray[Any]) -> int:
    data: tuple[int, bool] = array.__array_interface__["data"]
    return data[0]


def test_interleaved_in_place_matches_separate_arrays(mesh: Mesh, expected: NDArray[np.float32]) -> None:
    assert expected.shape == (mesh.count, 4) and expected.dtype == np.float32
    assert_frames(expected, mesh.normals)
    vertices = mesh.interleaved()
    before = vertices.copy()
    result = tbasis.generate(
        vertices["position"], vertices["normal"], vertices["uv"], mesh.indices, out=vertices["tangent"]
    )
    assert np.shares_memory(result, vertices)
    assert same_bits(vertices["tangent"], expected)
    for field in ("position", "normal", "uv"):  # only the tangent field changed
        assert same_bits(vertices[field], before[field])


def test_the_library_gets_the_callers_own_memory(mesh: Mesh, monkeypatch: pytest.MonkeyPatch) -> None:
    seen: list[tuple[Any, ...]] = []
    real: Callable[..., Any] = tbasis._native.generate

    def spy(*args: Any) -> Any:
        seen.append(args)
        return real(*args)

    monkeypatch.setattr(tbasis._native, "generate", spy)
    vertices = mesh.interleaved()
    bitangents = np.zeros((mesh.count, 3), dtype=np.float32)
    tbasis.generate(
        vertices["position"],
        vertices["normal"],
        vertices["uv"],
        mesh.indices,
        method="area",
        policy="skip",
        flip_v=True,
        threads=3,
        threshold=0.25,
        out=vertices["tangent"],
        bitangents=bitangents,
    )
    (args,) = seen
    fields = VERTEX.fields
    assert fields is not None
    positions, normals, texcoords, indices, method, policy, threshold, flip_v, threads, tangents, written = args
    for array, field in ((positions, "position"), (normals, "normal"), (texcoords, "uv"), (tangents, "tangent")):
        assert address(array) == address(vertices) + fields[field][1], field
        assert array.strides == (VERTEX.itemsize, 4), field
    assert address(indices) == address(mesh.indices) and address(written) == address(bitangents)
    assert (method, policy, threshold, flip_v, threads) == (3, 2, 0.25, True, 3)


def test_padded_odd_stride_and_unaligned_fields(mesh: Mesh, expected: NDArray[np.float32]) -> None:
    # Fields at odd offsets in a 51-byte record: nothing is aligned, nothing is copied.
    dtype = np.dtype(
        {
            "names": ["uv", "position", "tangent", "normal"],
            "formats": [("<f4", 2), ("<f4", 3), ("<f4", 4), ("<f4", 3)],
            "offsets": [1, 10, 23, 39],
            "itemsize": 51,
        }
    )
    vertices = mesh.interleaved(dtype)
    assert not vertices["position"].flags.aligned
    tbasis.generate(vertices["position"], vertices["normal"], vertices["uv"], mesh.indices, out=vertices["tangent"])
    assert same_bits(vertices["tangent"], expected)


@pytest.mark.parametrize(
    "convert",
    [
        lambda a: a.astype(np.float64),
        lambda a: a.astype(">f4"),
        lambda a: np.asfortranarray(a),
        lambda a: a[::-1][::-1],
        lambda a: np.repeat(a, 2, axis=1)[:, ::2],
        lambda a: a.tolist(),
    ],
    ids=["float64", "big-endian", "fortran", "reversed-view", "column-strided", "list"],
)
def test_other_layouts_and_dtypes_are_converted_once_to_the_same_bits(
    mesh: Mesh, expected: NDArray[np.float32], convert: Callable[[NDArray[np.float32]], Any]
) -> None:
    got = tbasis.generate(convert(mesh.positions), convert(mesh.normals), convert(mesh.uvs), mesh.indices)
    assert same_bits(got, expected)


def test_reversed_and_broadcast_rows_are_converted(mesh: Mesh) -> None:
    flat = torus(nu=6, nv=4)
    normal = np.array([0, 0, 1], dtype=np.float32)
    broadcast = np.broadcast_to(normal, flat.normals.shape)
    assert broadcast.strides[0] == 0
    assert same_bits(
        tbasis.generate(flat.positions, broadcast, flat.uvs, flat.indices),
        tbasis.generate(flat.positions, np.tile(normal, (flat.count, 1)), flat.uvs, flat.indices),
    )
    backwards = tbasis.generate(flat.positions[::-1], flat.normals[::-1], flat.uvs[::-1], flat.count - 1 - flat.indices)
    assert same_bits(backwards[::-1], tbasis.generate(flat.positions, flat.normals, flat.uvs, flat.indices))


@pytest.mark.parametrize(
    "make",
    [
        lambda n: np.zeros((n, 4), dtype=">f4"),
        lambda n: np.zeros((n, 8), dtype=np.float32)[:, ::2],
        lambda n: np.zeros((4, n), dtype=np.float32).T,
        lambda n: np.zeros((2 * n, 4), dtype=np.float32)[::-2],
    ],
    ids=["big-endian", "column-strided", "transposed", "reversed"],
)
def test_out_in_any_float32_layout_is_written(
    mesh: Mesh, expected: NDArray[np.float32], make: Callable[[int], NDArray[Any]]
) -> None:
    out = make(mesh.count)
    result = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out)
    assert result is out
    assert same_bits(np.asarray(out, dtype=np.float32), expected)


def test_index_types_shapes_and_strides_agree() -> None:
    # An unindexed mesh is a triangle soup: expand the torus so every corner is its own vertex.
    base = torus(nu=16, nv=8, jitter=0.01, random_diagonals=True)
    corners = base.indices
    positions, normals, uvs = base.positions[corners], base.normals[corners], base.uvs[corners]
    sequential = np.arange(len(corners), dtype=np.uint32)
    assert len(corners) < 65536
    unindexed = tbasis.generate(positions, normals, uvs)
    assert_frames(unindexed, normals)
    for indices in (sequential, sequential.astype(np.uint16), sequential.reshape(-1, 3), sequential.astype(np.int64)):
        assert same_bits(tbasis.generate(positions, normals, uvs, indices), unindexed), indices.dtype

    # Shared vertices: every integer type, (k,) and (m, 3), strided index arrays give the same bits.
    u32 = tbasis.generate(base.positions, base.normals, base.uvs, base.indices)
    for dtype in (np.uint16, np.int32, np.int64, np.uint64, ">u4"):
        assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, base.indices.astype(dtype)), u32), (
            dtype
        )
    spread = np.zeros(2 * len(base.indices), dtype=np.uint32)
    spread[::2] = base.indices
    assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, spread[::2]), u32)
    triangles = np.zeros(len(base.indices) // 3, dtype=[("corners", "<u2", 3), ("material", "<u2")])
    triangles["corners"] = base.indices.reshape(-1, 3)
    assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, triangles["corners"]), u32)
    assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, base.indices.tolist()), u32)
    # And differ from the soup: sharing vertices changes the sums.
    assert not np.allclose(u32[base.indices], unindexed)


def test_strided_indices_are_read_in_place(monkeypatch: pytest.MonkeyPatch) -> None:
    base = torus(nu=6, nv=4)
    spread = np.zeros(2 * len(base.indices), dtype=np.uint16)
    spread[::2] = base.indices
    seen: list[Any] = []
    real: Callable[..., Any] = tbasis._native.generate

    def spy(*args: Any) -> Any:
        seen.append(args[3])
        return real(*args)

    monkeypatch.setattr(tbasis._native, "generate", spy)
    tbasis.generate(base.positions, base.normals, base.uvs, spread[::2])
    assert address(seen[0]) == address(spread) and seen[0].strides == (4,)


def test_huge_stride_is_not_copied() -> None:
    # 4 KiB records: a copy of any one attribute would allocate 0.5-1 MiB through numpy, which
    # tracemalloc sees; the call itself allocates only its scratch, inside the library.
    count = 30_000
    spacing = np.dtype(
        {
            "names": ["position", "normal", "uv", "tangent"],
            "formats": [("<f4", 3), ("<f4", 3), ("<f4", 2), ("<f4", 4)],
            "offsets": [0, 1024, 2048, 3072],
            "itemsize": 4096,
        }
    )
    small = torus(nu=149, nv=199)
    assert small.count == count
    vertices = np.zeros(count, dtype=spacing)
    vertices["position"], vertices["normal"], vertices["uv"] = small.positions, small.normals, small.uvs
    tracemalloc.start()
    try:
        tbasis.generate(
            vertices["position"], vertices["normal"], vertices["uv"], small.indices, out=vertices["tangent"]
        )
        _, peak = tracemalloc.get_traced_memory()
    finally:
        tracemalloc.stop()
    assert peak < 64 * 1024, f"peak {peak} bytes allocated by Python during the call"
    assert_frames(vertices["tangent"], small.normals)
    assert same_bits(vertices["tangent"], tbasis.generate(small.positions, small.normals, small.uvs, small.indices))


def test_read_only_inputs_and_empty_meshes() -> None:
    mesh = torus(nu=4, nv=3)
    frozen = [a.copy() for a in (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)]
    for array in frozen:
        array.flags.writeable = False
    assert same_bits(tbasis.generate(*frozen), tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices))
    empty = np.zeros((0, 3), dtype=np.float32)
    assert tbasis.generate(empty, empty, np.zeros((0, 2), dtype=np.float32)).shape == (0, 4)
    assert tbasis.generate_corners(empty, empty, None, np.zeros(0, np.uint32)).shape == (0, 4)
