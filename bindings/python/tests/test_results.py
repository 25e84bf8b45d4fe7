"""What the tangents are: methods, policies, threshold, flip_v, bitangents, reports, and the
listing's exact bits."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray

import tbasis
from meshes import Mesh, assert_frames, collapse_uvs_around, torus, zero_uv_area_triangles
from support import same_bits

Method, Policy = tbasis.Method, tbasis.Policy
# The methods that sum tangents per vertex (MIKKTSPACE works per corner: test_corners.py).
PER_VERTEX_METHODS = [m for m in Method if m != Method.MIKKTSPACE]


@pytest.fixture
def collapsed() -> tuple[Mesh, int]:
    """A torus where every triangle at one vertex has collapsed UVs, and that vertex's index."""
    mesh = torus(jitter=0.005, random_diagonals=True, seed=7)
    vertex = 12 * 13 + 6  # grid vertex (12, 6), away from the seams
    collapse_uvs_around(mesh, vertex)
    return mesh, vertex


def angle_degrees(tangents: NDArray[Any], truth: NDArray[np.float64]) -> NDArray[np.float64]:
    cosine = np.einsum("ij,ij->i", tangents[:, :3].astype(np.float64), truth)
    degrees: NDArray[np.float64] = np.degrees(np.arccos(np.clip(cosine / np.linalg.norm(truth, axis=1), -1, 1)))
    return degrees


@pytest.mark.parametrize("method", PER_VERTEX_METHODS)
def test_every_method_gives_unit_frames_close_to_the_true_tangent(method: tbasis.Method) -> None:
    mesh = torus(nu=48, nv=24, jitter=0.002, random_diagonals=True, seed=3)
    tangents, report = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method, report=True)
    assert tangents.shape == (mesh.count, 4) and tangents.dtype == np.float32
    assert_frames(tangents, mesh.normals)
    assert np.all(tangents[:, 3] == 1.0)
    assert np.mean(angle_degrees(tangents, mesh.true_tangents)) < 1.0
    assert report == tbasis.Report(0, None, 0, 0, 0, 0, 0, 0, 0)


def test_names_and_enum_members_are_the_same_choice() -> None:
    mesh = torus(jitter=0.01, random_diagonals=True, seed=5)
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    for method in Method:
        assert same_bits(tbasis.generate(*args, method=method), tbasis.generate(*args, method=method.value))
    assert Method("mikktspace") is Method.MIKKTSPACE and Method.MIKKTSPACE.value == "mikktspace"
    assert Policy("reject") is Policy.REJECT and isinstance(Policy.SKIP, str) and Policy.SKIP.value == "skip"


def test_methods_differ_and_default_is_angle() -> None:
    mesh = torus(jitter=0.01, random_diagonals=True, seed=5)
    results: dict[tbasis.Method, NDArray[np.float32]] = {
        m: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=m) for m in PER_VERTEX_METHODS
    }
    assert same_bits(results[Method.DEFAULT], results[Method.ANGLE])
    assert same_bits(results[Method.DEFAULT], tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices))
    named = [results[m] for m in (Method.LENGYEL, Method.ANGLE, Method.AREA, Method.UNIFORM)]
    for i in range(len(named)):
        for j in range(i + 1, len(named)):
            assert not np.array_equal(named[i], named[j]), (i, j)


@pytest.mark.parametrize("policy", [Policy.SKIP, Policy.INHERIT, Policy.DEFAULT])
def test_skip_and_inherit_keep_frames_valid_on_collapsed_uvs(
    collapsed: tuple[Mesh, int], policy: tbasis.Policy
) -> None:
    mesh, vertex = collapsed
    degenerate = zero_uv_area_triangles(mesh)
    assert len(degenerate) >= 6
    tangents, report = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy=policy, report=True)
    assert_frames(tangents, mesh.normals)
    assert report.degenerate_triangles == len(degenerate)
    assert report.first_degenerate_triangle == degenerate[0]
    if policy == Policy.SKIP:
        # The vertex whose every triangle collapsed falls back to a frame built from its normal.
        assert report.fallback_vertices >= 1 and report.inherited_vertices == 0
    else:
        # It takes its tangent from its neighbours instead: close to the true direction.
        assert report.inherited_vertices >= 1 and report.fallback_vertices == 0
        assert angle_degrees(tangents[[vertex]], mesh.true_tangents[[vertex]])[0] < 10.0
        assert tangents[vertex, 3] == 1.0


def test_default_policy_is_inherit_and_legacy_for_mikktspace(collapsed: tuple[Mesh, int]) -> None:
    mesh, _ = collapsed
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    assert same_bits(tbasis.generate(*args), tbasis.generate(*args, policy="inherit"))
    # MIKKTSPACE's default is LEGACY: exactly mikktspace.c, which repairs nothing.
    mikk = tbasis.generate_corners(*args, method="mikktspace")
    assert same_bits(mikk, tbasis.generate_corners(*args, method="mikktspace", policy="legacy"))
    assert not same_bits(mikk, tbasis.generate_corners(*args, method="mikktspace", policy="inherit"))


def test_reject_reports_the_first_degenerate_triangle(collapsed: tuple[Mesh, int]) -> None:
    mesh, _ = collapsed
    with pytest.raises(tbasis.DegenerateUvError) as caught:
        tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy="reject")
    first = int(zero_uv_area_triangles(mesh)[0])
    assert caught.value.triangle == caught.value.report.first_degenerate_triangle == first
    assert caught.value.report.degenerate_triangles == len(zero_uv_area_triangles(mesh))
    assert f"triangle {first}" in str(caught.value)


def test_reject_accepts_a_clean_mesh() -> None:
    mesh = torus(jitter=0.005)
    rejected = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy=Policy.REJECT)
    assert same_bits(rejected, tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices))


def test_legacy_keeps_the_listings_inf_and_nan(collapsed: tuple[Mesh, int]) -> None:
    mesh, vertex = collapsed
    tangents, report = tbasis.generate(
        mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method="lengyel", policy="legacy", report=True
    )
    assert report.degenerate_triangles == len(zero_uv_area_triangles(mesh))
    assert not np.all(np.isfinite(tangents[vertex, :3]))
    assert np.isfinite(tangents[0]).all()


def test_threshold_changes_what_counts_as_degenerate() -> None:
    mesh = torus(nu=8, nv=4)
    mesh.uvs[:, 1] *= 1e-3  # UV triangles with aspect ratio ~1000: quality ~1e-3
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    assert tbasis.generate(*args, report=True)[1].degenerate_triangles == 0
    assert tbasis.generate(*args, threshold=0.5, report=True)[1].degenerate_triangles == len(mesh.indices) // 3
    # None is the library's default, 1e-5; 0.0 is a threshold, not "the default" as in C.
    assert same_bits(tbasis.generate(*args, threshold=1e-5), tbasis.generate(*args))
    mesh.uvs[:, 1] *= 1e-3
    assert tbasis.generate(*args, threshold=0.0, report=True)[1].degenerate_triangles == 0
    assert tbasis.generate(*args, report=True)[1].degenerate_triangles == len(mesh.indices) // 3


def test_flip_v_negates_w() -> None:
    mesh = torus(jitter=0.01, random_diagonals=True, seed=11)
    for method in (Method.LENGYEL, Method.ANGLE):
        plain = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method)
        flipped = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method, flip_v=True)
        assert np.all(plain[:, 3] == 1.0)
        assert np.all(flipped[:, 3] == -plain[:, 3])
        np.testing.assert_allclose(flipped[:, :3], plain[:, :3], atol=1e-4)


def test_bitangents_are_w_cross_n_t_in_every_return_shape() -> None:
    mesh = torus(jitter=0.01, seed=2)
    args = (mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    tangents, bitangents = tbasis.generate(*args, flip_v=True, bitangents=True)
    assert bitangents.shape == (mesh.count, 3) and bitangents.dtype == np.float32
    expected = tangents[:, 3:] * np.cross(mesh.normals, tangents[:, :3])
    np.testing.assert_allclose(bitangents, expected, atol=1e-5)

    given = np.full((mesh.count, 3), np.nan, dtype=np.float32)
    again, written, report = tbasis.generate(*args, flip_v=True, bitangents=given, report=True)
    assert written is given and same_bits(given, bitangents) and same_bits(again, tangents)
    assert isinstance(report, tbasis.Report)
    only = tbasis.generate(*args, flip_v=True, bitangents=False)
    assert isinstance(only, np.ndarray) and same_bits(only, tangents)


def test_no_texcoords_gives_every_vertex_the_fallback_frame() -> None:
    mesh = torus(nu=4, nv=3)
    tangents, report = tbasis.generate(mesh.positions, mesh.normals, None, mesh.indices, report=True)
    assert_frames(tangents, mesh.normals)
    assert report.fallback_vertices == mesh.count


def lengyel_listing(
    positions: NDArray[np.float32],
    normals: NDArray[np.float32],
    texcoords: NDArray[np.float32],
    triangles: NDArray[Any],
) -> NDArray[np.float32]:
    """Lengyel's 2001 listing in float32, in its own operation order (no fused multiply-adds)."""
    f = np.float32
    p, w = positions, texcoords
    v1, v2, v3 = p[triangles[:, 0]], p[triangles[:, 1]], p[triangles[:, 2]]
    w1, w2, w3 = w[triangles[:, 0]], w[triangles[:, 1]], w[triangles[:, 2]]
    x1, x2 = v2[:, 0] - v1[:, 0], v3[:, 0] - v1[:, 0]
    y1, y2 = v2[:, 1] - v1[:, 1], v3[:, 1] - v1[:, 1]
    z1, z2 = v2[:, 2] - v1[:, 2], v3[:, 2] - v1[:, 2]
    s1, s2 = w2[:, 0] - w1[:, 0], w3[:, 0] - w1[:, 0]
    t1, t2 = w2[:, 1] - w1[:, 1], w3[:, 1] - w1[:, 1]
    with np.errstate(divide="ignore", invalid="ignore"):
        r = f(1.0) / (s1 * t2 - s2 * t1)
    sdir = np.stack([(t2 * x1 - t1 * x2) * r, (t2 * y1 - t1 * y2) * r, (t2 * z1 - t1 * z2) * r], axis=1)
    tdir = np.stack([(s1 * x2 - s2 * x1) * r, (s1 * y2 - s2 * y1) * r, (s1 * z2 - s2 * z1) * r], axis=1)

    tan1 = np.zeros_like(positions)
    tan2 = np.zeros_like(positions)
    for a, (i1, i2, i3) in enumerate(triangles):  # per vertex, in triangle order
        for i in (i1, i2, i3):
            tan1[i] += sdir[a]
            tan2[i] += tdir[a]

    n, t = normals, tan1
    d = n[:, 0] * t[:, 0] + n[:, 1] * t[:, 1] + n[:, 2] * t[:, 2]
    g = t - n * d[:, None]
    inverse_length = f(1.0) / np.sqrt(g[:, 0] * g[:, 0] + g[:, 1] * g[:, 1] + g[:, 2] * g[:, 2])
    c = np.stack(
        [
            n[:, 1] * t[:, 2] - n[:, 2] * t[:, 1],
            n[:, 2] * t[:, 0] - n[:, 0] * t[:, 2],
            n[:, 0] * t[:, 1] - n[:, 1] * t[:, 0],
        ],
        axis=1,
    )
    handedness = c[:, 0] * tan2[:, 0] + c[:, 1] * tan2[:, 1] + c[:, 2] * tan2[:, 2]
    out = np.empty((len(positions), 4), dtype=np.float32)
    out[:, :3] = g * inverse_length[:, None]
    out[:, 3] = np.where(handedness < 0, f(-1.0), f(1.0))
    return out


@pytest.mark.parametrize("seed", [1, 2])
def test_lengyel_legacy_matches_the_listing_bit_for_bit(seed: int) -> None:
    # Jitter, random diagonals and a mirrored half (w = -1 there) exercise every branch but 1/0.
    mesh = torus(nu=20, nv=10, jitter=0.01, random_diagonals=True, seed=seed)
    mesh.uvs[: mesh.count // 2, 0] *= -1
    expected = lengyel_listing(mesh.positions, mesh.normals, mesh.uvs, mesh.indices.reshape(-1, 3))
    assert np.isfinite(expected).all() and (expected[:, 3] == -1).any() and (expected[:, 3] == 1).any()
    got = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method="lengyel", policy="legacy")
    assert same_bits(got, expected), np.max(np.abs(got - expected))
