"""Memory layouts: interleaved in place against separate arrays, index types, strides, no copies."""

import tracemalloc

import numpy as np
import pytest

import tbasis
from meshes import VERTEX, assert_frames, same_bits, torus


@pytest.fixture(scope="module")
def mesh():
    return torus(jitter=0.01, random_diagonals=True)


def test_interleaved_in_place_matches_separate_arrays(mesh):
    separate = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    assert separate.shape == (mesh.count, 4) and separate.dtype == np.float32
    assert_frames(separate, mesh.normals)

    vertices = mesh.interleaved()
    before = vertices.copy()
    result = tbasis.generate(
        vertices["position"], vertices["normal"], vertices["uv"], mesh.indices, out=vertices["tangent"]
    )
    assert np.shares_memory(result, vertices)
    assert same_bits(vertices["tangent"], separate)
    # Only the tangent field changed.
    for field in ("position", "normal", "uv"):
        assert same_bits(vertices[field], before[field])


def test_padded_odd_stride_and_unaligned_fields(mesh):
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
    expected = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    tbasis.generate(vertices["position"], vertices["normal"], vertices["uv"], mesh.indices, out=vertices["tangent"])
    assert same_bits(vertices["tangent"], expected)


def test_u16_u32_strided_and_unindexed_agree():
    # An unindexed mesh is a triangle soup: expand the torus so every corner is its own vertex.
    base = torus(nu=16, nv=8, jitter=0.01, random_diagonals=True)
    corners = base.indices
    positions, normals, uvs = base.positions[corners], base.normals[corners], base.uvs[corners]
    sequential = np.arange(len(corners), dtype=np.uint32)
    assert len(corners) < 65536

    unindexed = tbasis.generate(positions, normals, uvs)
    assert_frames(unindexed, normals)
    for indices in (
        sequential,
        sequential.astype(np.uint16),
        sequential.reshape(-1, 3),
        sequential.astype(np.uint16).reshape(-1, 3),
    ):
        assert same_bits(tbasis.generate(positions, normals, uvs, indices), unindexed), indices.dtype

    # Shared vertices: u16, u32, (m, 3) and strided index arrays give the same bits.
    u32 = tbasis.generate(base.positions, base.normals, base.uvs, base.indices)
    u16 = tbasis.generate(base.positions, base.normals, base.uvs, base.indices.astype(np.uint16))
    assert same_bits(u16, u32)
    spread = np.zeros(2 * len(base.indices), dtype=np.uint32)
    spread[::2] = base.indices
    assert not spread[::2].flags.c_contiguous
    assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, spread[::2]), u32)
    triangles = np.zeros(len(base.indices) // 3, dtype=[("corners", "<u2", 3), ("material", "<u2")])
    triangles["corners"] = base.indices.reshape(-1, 3)
    assert same_bits(tbasis.generate(base.positions, base.normals, base.uvs, triangles["corners"]), u32)
    # And differ from the soup: sharing vertices changes the sums.
    assert not np.allclose(u32[base.indices], unindexed)


def test_the_call_receives_the_structured_arrays_own_addresses(mesh, monkeypatch):
    seen = {}
    real_invoke = tbasis._invoke

    def spy(c_mesh, options, output, report):
        seen["mesh"] = tbasis.tbasis_mesh.from_buffer_copy(c_mesh)
        seen["output"] = tbasis.tbasis_output.from_buffer_copy(output)
        seen["options"] = tbasis.tbasis_options.from_buffer_copy(options)
        return real_invoke(c_mesh, options, output, report)

    monkeypatch.setattr(tbasis, "_invoke", spy)
    vertices = mesh.interleaved()
    bitangents = np.zeros((mesh.count, 3), dtype=np.float32)
    base = vertices.ctypes.data
    tbasis.generate(
        vertices["position"],
        vertices["normal"],
        vertices["uv"],
        mesh.indices,
        method=tbasis.Method.AREA,
        policy=tbasis.Policy.SKIP,
        flip_v=True,
        threads=3,
        threshold=0.25,
        out=vertices["tangent"],
        bitangents=bitangents,
    )
    c_mesh, output, options = seen["mesh"], seen["output"], seen["options"]
    assert c_mesh.vertex_count == mesh.count
    for field, pointer, stride in (
        ("position", c_mesh.positions, c_mesh.positions_stride),
        ("normal", c_mesh.normals, c_mesh.normals_stride),
        ("uv", c_mesh.texcoords, c_mesh.texcoords_stride),
        ("tangent", output.tangents, output.tangents_stride),
    ):
        assert pointer == base + VERTEX.fields[field][1], field
        assert stride == VERTEX.itemsize == 48, field
    assert c_mesh.indices == mesh.indices.ctypes.data  # packed already: passed as is
    assert (c_mesh.index_count, c_mesh.index_type) == (len(mesh.indices), tbasis.INDEX_U32)
    assert (output.bitangents, output.bitangents_stride) == (bitangents.ctypes.data, 12)
    assert (options.method, options.degenerate_policy, options.flags, options.threads) == (3, 2, 1, 3)
    assert options.degenerate_threshold == np.float32(0.25)
    assert (options.scratch, options.scratch_size) == (None, 0)


def test_huge_stride_is_not_copied():
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


def test_single_vertex_and_empty_meshes():
    empty = np.zeros((0, 3), dtype=np.float32)
    assert tbasis.generate(empty, empty, np.zeros((0, 2), dtype=np.float32)).shape == (0, 4)
    # Without texcoords every vertex gets the fallback frame built from its normal.
    mesh = torus(nu=4, nv=3)
    tangents, report = tbasis.generate_with_report(mesh.positions, mesh.normals, None, mesh.indices)
    assert_frames(tangents, mesh.normals)
    assert report.fallback_vertices == mesh.count
