"""Bad input: the library's statuses as TbasisError, the binding's own TypeError/ValueError, and the
caller's memory left as it was."""

import numpy as np
import pytest

import tbasis
from meshes import torus

Status = tbasis.Status


@pytest.fixture
def mesh():
    return torus(nu=6, nv=4)


def interleaved_with_sentinel(mesh):
    vertices = mesh.interleaved()
    vertices["tangent"] = -3.25
    return vertices, vertices.copy()


def call(vertices, indices, **options):
    return tbasis.generate(
        vertices["position"], vertices["normal"], vertices["uv"], indices, out=vertices["tangent"], **options
    )


@pytest.mark.parametrize(
    "case, status",
    [
        ("index_out_of_range", Status.INDEX_OUT_OF_RANGE),
        ("index_count", Status.INVALID_INDEX_COUNT),
        ("unindexed_count", Status.INVALID_INDEX_COUNT),
        ("method", Status.UNKNOWN_METHOD),
        ("policy", Status.UNKNOWN_POLICY),
        ("threshold", Status.INVALID_THRESHOLD),
        ("legacy_without_texcoords", Status.NULL_POINTER),
    ],
)
def test_library_errors_raise_with_status_and_message_and_write_nothing(mesh, case, status):
    vertices, before = interleaved_with_sentinel(mesh)
    indices, options = mesh.indices.copy(), {}
    if case == "index_out_of_range":
        indices[5] = mesh.count
    elif case == "index_count":
        indices = indices[:-1]
    elif case == "unindexed_count":
        assert mesh.count % 3 != 0
        indices = None
    elif case == "method":
        options["method"] = 9
    elif case == "policy":
        options["policy"] = 99
    elif case == "threshold":
        options["threshold"] = -1.0
    with pytest.raises(tbasis.TbasisError) as caught:
        if case == "legacy_without_texcoords":
            tbasis.generate(
                vertices["position"], vertices["normal"], None, indices, policy=tbasis.Policy.LEGACY,
                out=vertices["tangent"],
            )
        else:
            call(vertices, indices, **options)
    error = caught.value
    assert error.status == status and isinstance(error.status, int)
    assert error.message == tbasis.status_string(status)
    assert len(error.message) > 10 and error.message in str(error)
    assert error.report is None
    assert vertices.tobytes() == before.tobytes()


def test_out_overlapping_an_input_is_refused(mesh):
    block = np.zeros((mesh.count, 8), dtype=np.float32)
    block[:, :3], block[:, 3:6] = mesh.positions, mesh.normals
    uvs = mesh.uvs.copy()
    before = block.copy()
    # Tangents over the normals' bytes: the library refuses, since it validates before writing.
    with pytest.raises(tbasis.TbasisError) as caught:
        tbasis.generate(block[:, :3], block[:, 3:6], uvs, mesh.indices, out=block[:, 3:7])
    assert caught.value.status == Status.OVERLAP
    assert np.array_equal(block, before)


def test_unknown_status_still_has_a_message():
    error = tbasis.TbasisError(1000)
    assert error.status == 1000 and error.message and "1000" in str(error)


@pytest.mark.parametrize(
    "make, exception, words",
    [
        (lambda m: dict(positions=m.positions.tolist()), TypeError, "numpy float32 array"),
        (lambda m: dict(positions=m.positions.astype(np.float64)), TypeError, "float32"),
        (lambda m: dict(positions=m.positions.astype(">f4")), TypeError, "float32"),
        (lambda m: dict(normals=m.normals[:-1]), ValueError, "rows"),
        (lambda m: dict(texcoords=m.uvs[:-3]), ValueError, "rows"),
        (lambda m: dict(positions=m.positions[:, :2]), ValueError, "shape"),
        (lambda m: dict(texcoords=m.positions), ValueError, "shape"),
        (lambda m: dict(positions=np.asfortranarray(m.positions)), ValueError, "contiguous"),
        (lambda m: dict(positions=m.positions[::-1]), ValueError, "negative"),
        (lambda m: dict(indices=m.indices.astype(np.int32)), TypeError, "uint16 or uint32"),
        (lambda m: dict(indices=m.indices.astype(np.int64)), TypeError, "uint16 or uint32"),
        (lambda m: dict(indices=m.indices.tolist()), TypeError, "numpy"),
        (lambda m: dict(indices=m.indices.reshape(-1, 2)), ValueError, "shape"),
        (lambda m: dict(out=np.zeros((m.count, 4), dtype=np.float64)), TypeError, "float32"),
        (lambda m: dict(out=np.zeros((m.count, 3), dtype=np.float32)), ValueError, "shape"),
        (lambda m: dict(out=np.zeros((m.count + 1, 4), dtype=np.float32)), ValueError, "rows"),
        (lambda m: dict(bitangents=np.zeros((m.count, 4), dtype=np.float32)), ValueError, "shape"),
        (lambda m: dict(threads=-1), ValueError, "threads"),
        (lambda m: dict(method=2**32), ValueError, "method"),
    ],
)
def test_bad_arrays_and_options_raise_before_the_call(mesh, monkeypatch, make, exception, words):
    def no_call(*args):
        raise AssertionError("the library was called")

    monkeypatch.setattr(tbasis, "_invoke", no_call)
    arguments = dict(positions=mesh.positions, normals=mesh.normals, texcoords=mesh.uvs, indices=mesh.indices)
    arguments.update(make(mesh))
    with pytest.raises(exception, match=words):
        tbasis.generate(**arguments)


def test_read_only_out_is_refused(mesh):
    out = np.zeros((mesh.count, 4), dtype=np.float32)
    out.flags.writeable = False
    with pytest.raises(ValueError, match="read-only"):
        tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out)
    assert not out.any()


def test_tbasis_library_pointing_nowhere_is_an_error(monkeypatch, tmp_path):
    missing = tmp_path / "libtbasis.so"
    monkeypatch.setenv("TBASIS_LIBRARY", str(missing))
    with pytest.raises(FileNotFoundError, match="TBASIS_LIBRARY"):
        tbasis.find_library()


def test_missing_build_names_every_place_tried(monkeypatch, tmp_path):
    monkeypatch.delenv("TBASIS_LIBRARY", raising=False)
    monkeypatch.setattr(tbasis, "__file__", str(tmp_path / "bindings" / "python" / "tbasis.py"))
    with pytest.raises(FileNotFoundError) as caught:
        tbasis.find_library()
    message = str(caught.value)
    for profile in ("release", "debug"):
        assert str(tmp_path / "target" / profile / tbasis._library_name()) in message
    assert "TBASIS_LIBRARY" in message and "cargo build" in message


def test_repository_build_is_found_without_the_variable(monkeypatch, tmp_path):
    monkeypatch.delenv("TBASIS_LIBRARY", raising=False)
    monkeypatch.setattr(tbasis, "__file__", str(tmp_path / "bindings" / "python" / "tbasis.py"))
    debug = tmp_path / "target" / "debug" / tbasis._library_name()
    debug.parent.mkdir(parents=True)
    debug.write_bytes(b"")
    assert tbasis.find_library() == debug
    release = tmp_path / "target" / "release" / tbasis._library_name()
    release.parent.mkdir(parents=True)
    release.write_bytes(b"")
    assert tbasis.find_library() == release
