"""Every error class, raised by real input where the package or the library can meet it, each
naming what was expected or what is at fault, and leaving every output as it was."""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import textwrap
from typing import Any, Callable

import numpy as np
import pytest
from numpy.typing import NDArray

import tbasis
import tbasis._errors
import tbasis._native
from meshes import Mesh, collapse_uvs_around, torus
from support import same_bits

SENTINEL = np.float32(-3.25)


@pytest.fixture
def mesh() -> Mesh:
    return torus(nu=6, nv=4)


def sentinel_vertices(mesh: Mesh) -> tuple[NDArray[Any], bytes]:
    vertices = mesh.interleaved()
    vertices["tangent"] = SENTINEL
    return vertices, vertices.tobytes()


def raises(error: type[tbasis.Error], words: str, call: Callable[[], Any]) -> tbasis.Error:
    with pytest.raises(error, match=words) as caught:
        call()
    assert type(caught.value) is error and type(caught.value).__module__.startswith("tbasis")
    return caught.value


def test_every_class_is_a_tbasis_error_and_the_fitting_builtin() -> None:
    builtins = {
        tbasis.InvalidDtypeError: TypeError,
        tbasis.InvalidLayoutError: ValueError,
        tbasis.InvalidOptionError: ValueError,
        tbasis.MissingTexcoordsError: ValueError,
        tbasis.InvalidIndexCountError: ValueError,
        tbasis.IndexOutOfRangeError: IndexError,
        tbasis.OverlapError: ValueError,
        tbasis.InvalidFrameError: ValueError,
        tbasis.TooManyVerticesError: OverflowError,
        tbasis.OutOfMemoryError: MemoryError,
        tbasis.DegenerateUvError: Exception,
        tbasis.InternalError: Exception,
    }
    assert set(builtins) == {
        cls for cls in vars(tbasis).values() if isinstance(cls, type) and issubclass(cls, tbasis.Error)
    } - {tbasis.Error}
    for cls, builtin in builtins.items():
        assert issubclass(cls, tbasis.Error) and issubclass(cls, builtin), cls
        assert cls.__module__ == "tbasis" and cls.__doc__


@pytest.mark.parametrize(
    "case, error, words",
    [
        (
            "index_out_of_range",
            tbasis.IndexOutOfRangeError,
            r"index 5 \(triangle 1, corner 2\) is 35, not in range for 35 vertices",
        ),
        ("negative_index", tbasis.IndexOutOfRangeError, r"index 4 \(triangle 1, corner 1\) is -1"),
        ("index_count", tbasis.InvalidIndexCountError, "143 indices .* must be a multiple of 3"),
        ("unindexed_count", tbasis.InvalidIndexCountError, r"35 indices \(or unindexed vertices\) .* multiple of 3"),
        ("method", tbasis.InvalidOptionError, "method must be one of 'default', 'lengyel'"),
        ("policy_as_number", tbasis.InvalidOptionError, "policy must be one of"),
        ("policy_name", tbasis.InvalidOptionError, "policy must be one of"),
        ("flip_v_not_a_bool", tbasis.InvalidOptionError, "flip_v must be True or False, not 'no'"),
        ("threshold", tbasis.InvalidOptionError, "threshold must be finite and not negative"),
        ("threshold_nan", tbasis.InvalidOptionError, "threshold must be finite"),
        ("threshold_overflow", tbasis.InvalidOptionError, "degenerate_threshold inf is not a finite number >= 0"),
        ("threads", tbasis.InvalidOptionError, "threads must be between 0 and 2\\*\\*32 - 1, not -1"),
        ("threads_float", tbasis.InvalidOptionError, "threads must be an integer"),
        ("legacy_without_legacy_form", tbasis.InvalidOptionError, "method Angle has no legacy form"),
        (
            "legacy_without_texcoords",
            tbasis.MissingTexcoordsError,
            "texcoords is None, but .* needs texture coordinates",
        ),
        ("mikktspace_without_texcoords", tbasis.MissingTexcoordsError, "method 'mikktspace' always does"),
        ("reject", tbasis.DegenerateUvError, "triangle 0 has degenerate texture coordinates"),
        ("normals_rows", tbasis.InvalidLayoutError, "normals has 34 rows, positions has 35"),
        ("texcoords_shape", tbasis.InvalidLayoutError, r"texcoords must have shape \(n, 2\), not \(35, 3\)"),
        ("indices_shape", tbasis.InvalidLayoutError, r"indices must have shape \(k,\) or \(m, 3\), not \(72, 2\)"),
        ("positions_dtype", tbasis.InvalidDtypeError, "positions must hold real numbers .* not dtype complex64"),
        ("positions_strings", tbasis.InvalidDtypeError, "positions must hold real numbers"),
        ("indices_dtype", tbasis.InvalidDtypeError, "indices must be integers .* not dtype float32"),
        ("bitangents_type", tbasis.InvalidDtypeError, "bitangents must be True, False or a float32 array, not str"),
        ("bitangents_shape", tbasis.InvalidLayoutError, r"bitangents must have shape \(35, 3\), not \(35, 4\)"),
    ],
)
def test_bad_input_raises_and_writes_nothing(mesh: Mesh, case: str, error: type[tbasis.Error], words: str) -> None:
    vertices, before = sentinel_vertices(mesh)
    bitangents: Any = np.full((mesh.count, 3), SENTINEL)
    arguments: dict[str, Any] = dict(
        positions=vertices["position"],
        normals=vertices["normal"],
        texcoords=vertices["uv"],
        indices=mesh.indices.copy(),
    )
    options: dict[str, Any] = {}
    if case == "index_out_of_range":
        arguments["indices"][5] = mesh.count
    elif case == "negative_index":
        arguments["indices"] = mesh.indices.astype(np.int64)
        arguments["indices"][4] = -1
    elif case == "index_count":
        arguments["indices"] = mesh.indices[:-1]
    elif case == "unindexed_count":
        assert mesh.count % 3 != 0
        arguments["indices"] = None
    elif case == "method":
        options["method"] = "mikk"
    elif case == "policy_as_number":
        options["policy"] = 3
    elif case == "policy_name":
        options["policy"] = "skipp"
    elif case == "flip_v_not_a_bool":
        options["flip_v"] = "no"
    elif case == "threshold":
        options["threshold"] = -1.0
    elif case == "threshold_nan":
        options["threshold"] = float("nan")
    elif case == "threshold_overflow":
        options["threshold"] = 1e300  # finite as a Python float, infinite as the library's float32
    elif case == "threads":
        options["threads"] = -1
    elif case == "threads_float":
        options["threads"] = 2.0
    elif case == "legacy_without_legacy_form":
        options["method"] = "angle"
        options["policy"] = "legacy"
    elif case == "legacy_without_texcoords":
        arguments["texcoords"] = None
        options["policy"] = "legacy"
    elif case == "mikktspace_without_texcoords":
        arguments["texcoords"] = None
        options["method"] = "mikktspace"
    elif case == "reject":
        uvs = vertices["uv"].copy()
        collapse_uvs_around(Mesh(mesh.positions, mesh.normals, uvs, mesh.indices, mesh.true_tangents), 0)
        arguments["texcoords"] = uvs
        options["policy"] = "reject"
    elif case == "normals_rows":
        arguments["normals"] = mesh.normals[:-1]
    elif case == "texcoords_shape":
        arguments["texcoords"] = mesh.positions
    elif case == "indices_shape":
        arguments["indices"] = mesh.indices.reshape(-1, 2)
    elif case == "positions_dtype":
        arguments["positions"] = mesh.positions.astype(np.complex64)
    elif case == "positions_strings":
        arguments["positions"] = np.full((mesh.count, 3), "x")
    elif case == "indices_dtype":
        arguments["indices"] = mesh.indices.astype(np.float32)
    elif case == "bitangents_type":
        bitangents = "yes"
    elif case == "bitangents_shape":
        bitangents = np.full((mesh.count, 4), SENTINEL)
    raised = raises(
        error, words, lambda: tbasis.generate(**arguments, **options, out=vertices["tangent"], bitangents=bitangents)
    )
    assert vertices.tobytes() == before
    if isinstance(bitangents, np.ndarray):
        assert np.all(bitangents == SENTINEL)
    if error in (tbasis.InvalidDtypeError, tbasis.InvalidLayoutError):
        assert raised.status is None  # the package's own check: the library was not called
    if error is tbasis.IndexOutOfRangeError:
        assert isinstance(raised, tbasis.IndexOutOfRangeError)
        assert (raised.position, raised.triangle) in ((5, 1), (4, 1))
        assert raised.value in (mesh.count, -1)
    if error is tbasis.DegenerateUvError:
        assert isinstance(raised, tbasis.DegenerateUvError)
        assert raised.triangle == 0 and raised.report.degenerate_triangles > 0 and raised.status == 11
    if error is tbasis.InvalidOptionError and case.startswith("threshold_overflow"):
        assert raised.status == 14  # the library's check, not the package's


def test_the_same_errors_per_corner(mesh: Mesh) -> None:
    out = np.full((len(mesh.indices), 4), SENTINEL)
    bad = mesh.indices.astype(np.uint16)
    bad[7] = 1000
    error = raises(
        tbasis.IndexOutOfRangeError,
        r"index 7 \(triangle 2, corner 1\) is 1000",
        lambda: tbasis.generate_corners(mesh.positions, mesh.normals, mesh.uvs, bad, method="mikktspace", out=out),
    )
    assert error.status == 4
    raises(
        tbasis.InvalidLayoutError,
        r"out must have shape \(144, 4\), not \(35, 4\)",
        lambda: tbasis.generate_corners(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out[:35]),
    )
    assert np.all(out == SENTINEL)


@pytest.mark.parametrize(
    "make, error, words",
    [
        (
            lambda n: np.zeros((n, 4), dtype=np.float64),
            tbasis.InvalidDtypeError,
            "out must have dtype float32, not float64",
        ),
        (lambda n: [[0.0] * 4] * n, tbasis.InvalidDtypeError, "out must be a numpy array of dtype float32, not list"),
        (
            lambda n: np.zeros((n, 3), dtype=np.float32),
            tbasis.InvalidLayoutError,
            r"out must have shape \(35, 4\), not \(35, 3\)",
        ),
        (lambda n: np.zeros((n + 1, 4), dtype=np.float32), tbasis.InvalidLayoutError, r"out must have shape \(35, 4\)"),
        (lambda n: np.asfortranarray(np.zeros((n, 4), dtype=np.float32)), None, ""),
    ],
)
def test_out_is_checked(mesh: Mesh, make: Callable[[int], Any], error: Any, words: str) -> None:
    out = make(mesh.count)
    if error is None:  # Fortran order: written through a temporary, which is fine
        tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out)
        assert same_bits(out, tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices))
        return
    raises(error, words, lambda: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out))
    assert not np.any(np.asarray(out))


@pytest.mark.parametrize("name, width", [("out", 4), ("bitangents", 3)])
def test_a_read_only_output_is_refused(mesh: Mesh, name: str, width: int) -> None:
    array = np.zeros((mesh.count, width), dtype=np.float32)
    array.flags.writeable = False
    output: dict[str, Any] = {name: array}
    raises(
        tbasis.InvalidLayoutError,
        f"{name} is read-only",
        lambda: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, **output),
    )
    assert not array.any()


def test_bitangents_overlapping_an_input_are_refused(mesh: Mesh) -> None:
    block = np.zeros((mesh.count, 6), dtype=np.float32)
    block[:, :3] = mesh.positions
    before = block.copy()
    raises(
        tbasis.OverlapError,
        "the bitangents output shares bytes with the positions buffer",
        lambda: tbasis.generate(block[:, :3], mesh.normals, mesh.uvs, mesh.indices, bitangents=block[:, 2:5]),
    )
    assert np.array_equal(block, before)


def test_out_overlapping_an_input_is_refused(mesh: Mesh) -> None:
    block = np.zeros((mesh.count, 8), dtype=np.float32)
    block[:, :3], block[:, 3:6] = mesh.positions, mesh.normals
    before = block.copy()
    # Tangents over the normals' bytes: the library refuses before it writes anything.
    error = raises(
        tbasis.OverlapError,
        "the tangents output shares bytes with the normals buffer",
        lambda: tbasis.generate(block[:, :3], block[:, 3:6], mesh.uvs, mesh.indices, out=block[:, 3:7]),
    )
    assert error.status == 10
    assert np.array_equal(block, before)
    tangents = np.zeros((mesh.count, 4), np.float32)
    raises(
        tbasis.OverlapError,
        "the tangents output shares bytes with the bitangents buffer",
        lambda: tbasis.generate(
            mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=tangents, bitangents=tangents[:, :3]
        ),
    )


@pytest.mark.parametrize(
    "layout",
    ["big-endian", "every other column"],
)
def test_out_the_library_cannot_write_in_place_is_refused_when_it_overlaps_an_input(mesh: Mesh, layout: str) -> None:
    # These outs are written through a copy, which shares nothing with the inputs: only the
    # caller's arrays show the overlap, and the copy back would overwrite the input.
    block = np.zeros((mesh.count, 8), dtype=np.float32)
    block[:, :3], block[:, 3:6] = mesh.positions, mesh.normals
    before = block.copy()
    if layout == "big-endian":
        out, other = block.view(">f4")[:, 4:8], "normals"
    else:
        out, other = block[:, ::2], "positions"
    for call in (tbasis.generate, tbasis.generate_corners):
        error = raises(
            tbasis.OverlapError,
            f"the tangents output shares bytes with the {other} buffer",
            lambda: call(block[:, :3], block[:, 3:6], mesh.uvs, None, out=out),
        )
        assert error.status == 10
        assert np.array_equal(block, before)
    # Bitangents written through a copy, tangents in place over two of their columns.
    shared = np.zeros((mesh.count, 6), dtype=np.float32)
    raises(
        tbasis.OverlapError,
        "the tangents output shares bytes with the bitangents buffer",
        lambda: tbasis.generate(
            mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=shared[:, 2:6], bitangents=shared[:, ::2]
        ),
    )
    assert not shared.any()


def test_a_panic_in_the_library_raises_internal_error(mesh: Mesh, monkeypatch: pytest.MonkeyPatch) -> None:
    # The wheel tests/python.rs builds has the test-only feature fault-injection: with
    # TBASIS_INJECT_PANIC set, every call into the library panics there.
    corners = tbasis.generate_corners(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method="mikktspace")
    out = np.zeros((mesh.count, 4), dtype=np.float32)
    corner_out = np.zeros((len(mesh.indices), 4), dtype=np.float32)
    directions = np.zeros((mesh.count, 3), dtype=np.float32)
    frames = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices)
    monkeypatch.setenv("TBASIS_INJECT_PANIC", "1")
    calls: list[Callable[[], Any]] = [
        lambda: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=out),
        lambda: tbasis.generate_corners(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, out=corner_out),
        lambda: tbasis.split_corners(mesh.indices, mesh.count, corners),
        lambda: tbasis.to_tangent_space(mesh.normals, frames, mesh.normals, out=directions),
        lambda: tbasis.from_tangent_space(mesh.normals, frames, mesh.normals, out=directions),
    ]
    for call in calls:
        error = raises(tbasis.InternalError, "the library panicked", call)
        assert error.status == 16
    assert not out.any() and not corner_out.any() and not directions.any()


def test_split_errors(mesh: Mesh) -> None:
    corners = tbasis.generate_corners(mesh.positions, mesh.normals, mesh.uvs, mesh.indices, method="mikktspace")
    bad = mesh.indices.copy()
    bad[10] = 99
    error = raises(
        tbasis.IndexOutOfRangeError,
        r"index 10 \(triangle 3, corner 1\) is 99",
        lambda: tbasis.split_corners(bad, mesh.count, corners),
    )
    assert error.status == 4
    raises(
        tbasis.InvalidLayoutError,
        "corner_tangents has 143 rows, the mesh has 144 corners",
        lambda: tbasis.split_corners(mesh.indices, mesh.count, corners[1:]),
    )
    raises(
        tbasis.InvalidIndexCountError,
        "143 indices .* must be a multiple of 3",
        lambda: tbasis.split_corners(mesh.indices[:-1], mesh.count, corners[:-1]),
    )
    for count in (-1, 2**64):
        raises(
            tbasis.InvalidLayoutError,
            r"vertex_count must be between 0 and 2\*\*64 - 1",
            lambda: tbasis.split_corners(mesh.indices, count, corners),
        )
    # An int64 index of 2**32 or more cannot reach the library: refused, not wrapped around.
    wide = np.array([0, 1, 2**32 + 1], dtype=np.int64)
    error = raises(
        tbasis.IndexOutOfRangeError,
        r"index 2 \(triangle 0, corner 2\) is 4294967297: indices are 32-bit",
        lambda: tbasis.split_corners(wide, 2**33, np.zeros((3, 4), np.float32)),
    )
    assert isinstance(error, tbasis.IndexOutOfRangeError)
    assert (error.position, error.value, error.status) == (2, 2**32 + 1, None)
    # An index past the vertex count before it is the one named, as the library names the first.
    raises(
        tbasis.IndexOutOfRangeError,
        r"index 1 \(triangle 0, corner 1\) is 9, not in range for 4 vertices",
        lambda: tbasis.split_corners(np.array([0, 9, 2**32 + 1], np.int64), 4, np.zeros((3, 4), np.float32)),
    )
    not_a_count: Any = 3.0
    raises(
        tbasis.InvalidDtypeError,
        "vertex_count must be an integer",
        lambda: tbasis.split_corners(mesh.indices, not_a_count, corners),
    )

    # A mirrored triangle appends three vertices, which would need index 2**32.
    plus, minus = [1.0, 0.0, 0.0, 1.0], [1.0, 0.0, 0.0, -1.0]
    mirrored = np.array([plus, plus, plus, minus, minus, minus], dtype=np.float32)
    indices = np.array([0, 1, 2, 0, 2, 1], dtype=np.uint32)
    assert tbasis.split_corners(indices, 2**32 - 3, mirrored).indices.max() == 2**32 - 1
    error = raises(
        tbasis.TooManyVerticesError, "beyond 32 bits", lambda: tbasis.split_corners(indices, 2**32 - 2, mirrored)
    )
    assert error.status == 18

    source_error = raises(
        tbasis.IndexOutOfRangeError,
        r"sources\[1\] is 4, not in range for an attribute of 4 rows",
        lambda: tbasis.apply_split(np.zeros((4, 2)), [0, 4]),
    )
    assert isinstance(source_error, tbasis.IndexOutOfRangeError)
    assert (source_error.position, source_error.value, source_error.triangle) == (1, 4, None)
    raises(tbasis.InvalidDtypeError, "sources must hold integers", lambda: tbasis.apply_split(np.zeros((4, 2)), [0.5]))
    raises(
        tbasis.InvalidLayoutError,
        r"sources must have shape \(k,\), not \(2, 1\)",
        lambda: tbasis.apply_split(np.zeros((4, 2)), np.zeros((2, 1), np.int64)),
    )
    # Nothing split: an empty list of sources (numpy reads it as float64) gives the rows as they were.
    assert np.array_equal(tbasis.apply_split(np.arange(8.0).reshape(4, 2), []), np.arange(8.0).reshape(4, 2))
    raises(tbasis.InvalidLayoutError, "not be a scalar", lambda: tbasis.apply_split(np.float32(1), [0]))


def test_transform_errors_name_the_vector_and_write_nothing() -> None:
    normals = np.tile(np.array([0, 0, 1], dtype=np.float32), (2, 3, 1))
    tangents = np.tile(np.array([1, 0, 0, 1], dtype=np.float32), (2, 3, 1))
    tangents[1, 2] = [0, 0, 1, 1]  # parallel to the normal
    out = np.full((2, 3, 3), SENTINEL)
    error = raises(
        tbasis.InvalidFrameError,
        r"vector \(1, 2\): the tangent frame is singular",
        lambda: tbasis.to_tangent_space(normals, tangents, np.array([0, 1, 0], dtype=np.float32), out=out),
    )
    assert isinstance(error, tbasis.InvalidFrameError) and error.index == (1, 2) and error.status == 17
    assert np.all(out == SENTINEL)
    raises(
        tbasis.InvalidFrameError,
        "vector 1:",
        lambda: tbasis.from_tangent_space(normals[0], [[1, 0, 0, 1], [1, 0, 0, 0], [1, 0, 0, 1]], [0, 0, 1]),
    )
    raises(
        tbasis.InvalidFrameError,
        "the vector:",
        lambda: tbasis.to_tangent_space([0, 0, 1], [1, 0, 0, 1], [np.inf, 0, 0]),
    )
    raises(
        tbasis.InvalidLayoutError,
        "do not broadcast",
        lambda: tbasis.to_tangent_space(normals, tangents[:, :2], [0, 0, 1]),
    )
    raises(
        tbasis.InvalidLayoutError,
        r"tangents must have shape \(..., 4\), not \(3,\)",
        lambda: tbasis.to_tangent_space([0, 0, 1], [1, 0, 0], [0, 0, 1]),
    )
    raises(
        tbasis.InvalidLayoutError,
        r"out must have shape \(2, 3, 3\), not \(6, 3\)",
        lambda: tbasis.to_tangent_space(normals, tangents, [0, 0, 1], out=out.reshape(6, 3)),
    )


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="limits the address space with setrlimit, as on Linux")
def test_out_of_memory_is_an_error_not_a_crash() -> None:
    # In a child process whose address space is capped just above what it uses, the split's
    # working memory for 100 million vertices (1.2 GB) cannot be had.
    script = textwrap.dedent(
        """
        import resource
        import numpy as np
        import tbasis
        size = int(open("/proc/self/statm").read().split()[0]) * resource.getpagesize()
        resource.setrlimit(resource.RLIMIT_AS, (size + 256 * 2**20, resource.RLIM_INFINITY))
        indices = np.array([0, 1, 100_000_000 - 1], dtype=np.uint32)
        try:
            tbasis.split_corners(indices, 100_000_000, np.zeros((3, 4), np.float32))
        except tbasis.OutOfMemoryError as error:
            assert isinstance(error, MemoryError) and error.status == 12
            print("raised", error)
        """
    )
    environment = dict(os.environ, OPENBLAS_NUM_THREADS="1")
    run = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, env=environment)
    assert run.returncode == 0, run.stderr
    assert run.stdout.startswith("raised out of memory"), run.stdout


@pytest.mark.parametrize(
    "status, error",
    [
        (2, tbasis.InvalidLayoutError),
        (5, tbasis.InvalidDtypeError),
        (8, tbasis.InvalidOptionError),
        (9, tbasis.InvalidLayoutError),
        (12, tbasis.OutOfMemoryError),
        (13, tbasis.InternalError),
        (15, tbasis.InvalidLayoutError),
        (16, tbasis.InternalError),
        (99, tbasis.InternalError),
    ],
)
def test_statuses_no_input_reaches_map_to_their_family(status: int, error: type[tbasis.Error]) -> None:
    # The package's own checks come first, so these statuses need a direct LibraryError.
    failure = tbasis._native.LibraryError(status, "what the library says", {})
    mapped = tbasis._errors.from_library(failure)
    assert type(mapped) is error and mapped.status == status
    assert str(mapped) == f"what the library says (status {status})"


def test_errors_survive_pickling(mesh: Mesh) -> None:
    bad = mesh.indices.copy()
    bad[2] = 500
    with pytest.raises(tbasis.IndexOutOfRangeError) as caught:
        tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, bad)
    again = pickle.loads(pickle.dumps(caught.value))
    assert type(again) is tbasis.IndexOutOfRangeError and str(again) == str(caught.value)
    assert (again.position, again.value, again.triangle, again.status) == (2, 500, 0, 4)


def test_options_are_checked_before_the_indices_whatever_their_dtype(mesh: Mesh) -> None:
    unknown: Any = "nope"
    for dtype in (np.uint32, np.int64):
        bad = mesh.indices.astype(dtype)
        bad[1] = mesh.count
        raises(
            tbasis.InvalidOptionError,
            "method must be one of",
            lambda: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, bad, method=unknown),
        )
        error = raises(
            tbasis.IndexOutOfRangeError,
            r"index 1 \(triangle 0, corner 1\)",
            lambda: tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, bad),
        )
        assert error.status == 4  # the library's check, for every index dtype


def test_an_input_given_as_another_array_like_is_checked_for_overlap(mesh: Mesh) -> None:
    buffer = np.zeros((mesh.count, 4), dtype=np.float32)
    buffer[:, :3] = mesh.positions

    class ArrayLike:
        def __array__(self, dtype: Any = None, copy: Any = None) -> NDArray[Any]:
            return buffer[:, :3]

    before = buffer.tobytes()
    raises(
        tbasis.OverlapError,
        "the tangents output shares bytes with the positions buffer",
        lambda: tbasis.generate(ArrayLike(), mesh.normals, mesh.uvs, mesh.indices, out=buffer),
    )
    assert buffer.tobytes() == before


def test_an_empty_list_of_indices_is_an_empty_index_array(mesh: Mesh) -> None:
    tangents = tbasis.generate(mesh.positions, mesh.normals, mesh.uvs, [])
    assert tangents.shape == (mesh.count, 4) and np.all(np.isfinite(tangents))


def test_a_copy_numpy_cannot_allocate_is_out_of_memory_error() -> None:
    try:
        with open("/proc/sys/vm/overcommit_memory") as setting:
            if setting.read().strip() == "1":
                pytest.skip("the system grants any allocation (vm.overcommit_memory = 1)")
    except OSError:
        pass
    huge = np.broadcast_to(np.zeros(3), (2**40, 3))  # float64, so converted: 12 TiB of float32
    error = raises(tbasis.OutOfMemoryError, "no memory for a copy of positions", lambda: tbasis.generate(huge, huge, None))
    assert error.status is None and isinstance(error, MemoryError)
