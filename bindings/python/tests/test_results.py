"""What the tangents are: policies, methods, flip_v, bitangents, and the listing's exact bits."""

import numpy as np
import pytest

import tbasis
from meshes import assert_frames, collapse_uvs_around, same_bits, torus, zero_uv_area_triangles

Method, Policy = tbasis.Method, tbasis.Policy
# The methods that sum tangents per vertex (MIKKTSPACE works per corner; its own tests are elsewhere).
PER_VERTEX_METHODS = [m for m in Method if m != Method.MIKKTSPACE]


@pytest.fixture
def collapsed():
    """A torus where every triangle at one vertex has collapsed UVs, and that vertex's index."""
    mesh = torus(jitter=0.005, random_diagonals=True, seed=7)
    vertex = 12 * 13 + 6  # grid vertex (12, 6), away from the seams
    collapse_uvs_around(mesh, vertex)
    return mesh, vertex


def angle_degrees(tangents, truth):
    cosine = np.einsum("ij,ij->i", tangents[:, :3].astype(np.float64), truth)
    return np.degrees(np.arccos(np.clip(cosine / np.linalg.norm(truth, axis=1), -1, 1)))


@pytest.mark.parametrize("method", PER_VERTEX_METHODS)
def test_every_method_gives_unit_frames_close_to_the_true_tangent(method):
    mesh = torus(nu=48, nv=24, jitter=0.002, random_diagonals=True, seed=3)
    tangents, report = tbasis.generate_with_report(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method)
    assert_frames(tangents, mesh.normals)
    assert np.all(tangents[:, 3] == 1.0)
    assert np.mean(angle_degrees(tangents, mesh.true_tangents)) < 1.0
    assert report.degenerate_triangles == 0 and report.first_degenerate_triangle is None
    assert report.mirrored_vertices == report.fallback_vertices == report.unreferenced_vertices == 0
    assert report.repaired_corners == report.split_vertices == 0


def test_methods_differ_and_default_is_angle():
    mesh = torus(jitter=0.01, random_diagonals=True, seed=5)
    results = {
        m: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=m) for m in PER_VERTEX_METHODS
    }
    assert same_bits(results[Method.DEFAULT], results[Method.ANGLE])
    named = [results[m] for m in (Method.LENGYEL, Method.ANGLE, Method.AREA, Method.UNIFORM)]
    for i in range(len(named)):
        for j in range(i + 1, len(named)):
            assert not np.array_equal(named[i], named[j]), (i, j)


@pytest.mark.parametrize("policy", [Policy.SKIP, Policy.INHERIT, Policy.DEFAULT])
def test_skip_and_inherit_keep_frames_valid_on_collapsed_uvs(collapsed, policy):
    mesh, vertex = collapsed
    degenerate = zero_uv_area_triangles(mesh)
    assert len(degenerate) >= 6
    tangents, report = tbasis.generate_with_report(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy=policy)
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


def test_default_policy_is_inherit(collapsed):
    mesh, _ = collapsed
    default = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    inherit = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy=Policy.INHERIT)
    assert same_bits(default, inherit)


def test_reject_raises_and_leaves_out_untouched(collapsed):
    mesh, _ = collapsed
    vertices = mesh.interleaved()
    vertices["tangent"] = 7.5
    before = vertices.copy()
    with pytest.raises(tbasis.TbasisError) as caught:
        tbasis.generate(
            vertices["position"], vertices["normal"], vertices["uv"], mesh.indices,
            policy=Policy.REJECT, out=vertices["tangent"],
        )
    error = caught.value
    assert error.status == tbasis.Status.DEGENERATE_UV == 11
    assert error.message == tbasis.status_string(11) and error.message in str(error)
    assert error.report.first_degenerate_triangle == zero_uv_area_triangles(mesh)[0]
    assert vertices.tobytes() == before.tobytes()


def test_reject_accepts_a_clean_mesh():
    mesh = torus(jitter=0.005)
    rejected = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, policy=Policy.REJECT)
    assert same_bits(rejected, tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices))


def test_legacy_keeps_the_listings_inf_and_nan(collapsed):
    mesh, vertex = collapsed
    tangents, report = tbasis.generate_with_report(
        mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=Method.LENGYEL, policy=Policy.LEGACY
    )
    assert report.degenerate_triangles == len(zero_uv_area_triangles(mesh))
    assert not np.all(np.isfinite(tangents[vertex, :3]))
    assert np.isfinite(tangents[0]).all()


def test_threshold_changes_what_counts_as_degenerate():
    mesh = torus(nu=8, nv=4)
    mesh.uvs[:, 1] *= 1e-3  # UV triangles with aspect ratio ~1000: quality ~1e-3
    loose = tbasis.generate_with_report(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)[1]
    strict = tbasis.generate_with_report(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, threshold=0.5)[1]
    assert loose.degenerate_triangles == 0
    assert strict.degenerate_triangles == len(mesh.indices) // 3


def test_flip_v_negates_w():
    mesh = torus(jitter=0.01, random_diagonals=True, seed=11)
    for method in (Method.LENGYEL, Method.ANGLE):
        plain = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method)
        flipped = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=method, flip_v=True)
        assert np.all(plain[:, 3] == 1.0)
        assert np.all(flipped[:, 3] == -plain[:, 3])
        np.testing.assert_allclose(flipped[:, :3], plain[:, :3], atol=1e-4)


def test_bitangents_are_w_cross_n_t():
    mesh = torus(jitter=0.01, seed=2)
    bitangents = np.full((mesh.count, 3), np.nan, dtype=np.float32)
    tangents = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, flip_v=True, bitangents=bitangents)
    expected = tangents[:, 3:] * np.cross(mesh.normals, tangents[:, :3])
    np.testing.assert_allclose(bitangents, expected, atol=1e-5)


def test_threads_give_the_same_bits():
    mesh = torus(nu=255, nv=160, jitter=0.002, random_diagonals=True)  # 41k vertices: two workers
    one = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    assert same_bits(tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, threads=4), one)


def lengyel_listing(positions, normals, texcoords, triangles):
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
        tan1[i1] += sdir[a]
        tan1[i2] += sdir[a]
        tan1[i3] += sdir[a]
        tan2[i1] += tdir[a]
        tan2[i2] += tdir[a]
        tan2[i3] += tdir[a]

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
def test_lengyel_legacy_matches_the_listing_bit_for_bit(seed):
    # Jitter, random diagonals and a mirrored half (w = -1 there) exercise every branch but 1/0.
    mesh = torus(nu=20, nv=10, jitter=0.01, random_diagonals=True, seed=seed)
    mesh.uvs[: mesh.count // 2, 0] *= -1
    for array in (mesh.positions, mesh.normals, mesh.uvs):
        assert array.dtype == np.float32
    expected = lengyel_listing(mesh.positions, mesh.normals, mesh.uvs, mesh.indices.reshape(-1, 3))
    assert np.isfinite(expected).all() and (expected[:, 3] == -1).any() and (expected[:, 3] == 1).any()
    got = tbasis.generate(
        mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method=Method.LENGYEL, policy=Policy.LEGACY
    )
    assert same_bits(got, expected), np.max(np.abs(got - expected))
