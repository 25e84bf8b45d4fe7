"""The examples run and do what they say; the facts about trimesh that gltf_tangents.py relies on."""

from __future__ import annotations

import runpy
import subprocess
import sys
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import trimesh
from numpy.typing import NDArray

import gltf
import tbasis
from meshes import torus
from support import CORPUS, EXAMPLES, require_corpus_file, same_bits

MIRROR_TEST = CORPUS / "khronos" / "NormalTangentMirrorTest.glb"  # stored tangents: mikktspace-exact


def test_interleaved_example_writes_tangents_in_place(capsys: pytest.CaptureFixture[str]) -> None:
    names = runpy.run_path(str(EXAMPLES / "interleaved.py"))
    vertices = names["vertices"]
    assert np.array_equal(vertices["tangent"], np.tile(np.array([1, 0, 0, 1], dtype=np.float32), (4, 1)))
    assert np.array_equal(vertices["uv"], [[0, 0], [1, 0], [1, 1], [0, 1]])
    assert np.array_equal(names["corners"], np.tile(np.array([1, 0, 0, -1], dtype=np.float32), (6, 1)))
    printed = capsys.readouterr().out.splitlines()
    assert printed[:4] == ["[[1. 0. 0. 1.]", " [1. 0. 0. 1.]", " [1. 0. 0. 1.]", " [1. 0. 0. 1.]]"]
    assert printed[4:] == [
        "[ 1.  0.  0. -1.] 0",
        "index 5 (triangle 1, corner 2) is 4, not in range for 4 vertices",
    ]


def write_glb(
    path: Path, positions: NDArray[Any], normals: NDArray[Any], uvs: NDArray[Any], faces: NDArray[Any]
) -> None:
    """A glb written by trimesh from V-up texture coordinates, with a material so that trimesh
    reads them back."""
    visual = trimesh.visual.TextureVisuals(uv=uvs, material=trimesh.visual.material.PBRMaterial())
    mesh = trimesh.Trimesh(vertices=positions, faces=faces, vertex_normals=normals, visual=visual, process=False)
    path.write_bytes(trimesh.Scene(mesh).export(file_type="glb"))


def attribute_names(path: Path) -> set[str]:
    document, _ = gltf.read(path)
    return {name for mesh in document["meshes"] for primitive in mesh["primitives"] for name in primitive["attributes"]}


def run_example(source: Path, target: Path) -> str:
    run = subprocess.run(
        [sys.executable, str(EXAMPLES / "gltf_tangents.py"), str(source), str(target)],
        capture_output=True,
        text=True,
        cwd=target.parent,
    )
    assert run.returncode == 0, run.stderr
    return run.stdout


def test_trimesh_flips_v_and_does_not_keep_tangent(tmp_path: Path) -> None:
    mesh = torus(nu=8, nv=4)
    path = tmp_path / "torus.glb"
    write_glb(path, mesh.positions, mesh.normals, mesh.uvs, mesh.indices.reshape(-1, 3))
    (stored,) = gltf.primitives(path)
    assert stored.texcoords is not None
    # The file holds V down, as glTF has it: trimesh flipped it on export, and flips it on load.
    np.testing.assert_allclose(stored.texcoords, np.stack([mesh.uvs[:, 0], 1 - mesh.uvs[:, 1]], 1), atol=1e-7)
    loaded = next(iter(trimesh.load_scene(path, process=False).geometry.values()))
    assert isinstance(loaded, trimesh.Trimesh) and isinstance(loaded.visual, trimesh.visual.TextureVisuals)
    np.testing.assert_allclose(loaded.visual.uv, mesh.uvs, atol=1e-7)
    # A TANGENT attribute is not loaded, and one added is written as the custom _TANGENT.
    with_tangent = tmp_path / "tangent.glb"
    loaded.vertex_attributes["TANGENT"] = np.zeros((len(loaded.vertices), 4), dtype=np.float32)
    with_tangent.write_bytes(trimesh.Scene(loaded).export(file_type="glb"))
    assert "_TANGENT" in attribute_names(with_tangent) and "TANGENT" not in attribute_names(with_tangent)
    reloaded = next(iter(trimesh.load_scene(with_tangent, process=False).geometry.values()))
    assert isinstance(reloaded, trimesh.Trimesh) and "TANGENT" not in reloaded.vertex_attributes


def test_gltf_example_splits_seams_and_writes_mikktspace_tangents(tmp_path: Path) -> None:
    mesh = torus(nu=16, nv=8, jitter=0.002, random_diagonals=True, seed=4)
    mesh.uvs[:, 0] = np.where(mesh.uvs[:, 0] > 0.5, 1.0 - mesh.uvs[:, 0], mesh.uvs[:, 0])  # a mirror seam
    source, target = tmp_path / "mirrored.glb", tmp_path / "out.glb"
    write_glb(source, mesh.positions, mesh.normals, mesh.uvs, mesh.indices.reshape(-1, 3))
    printed = run_example(source, target)
    assert "TANGENT" in attribute_names(target) and "_TANGENT" not in attribute_names(target)

    (before,) = gltf.primitives(source)
    (after,) = gltf.primitives(target)
    assert before.texcoords is not None and before.indices is not None and before.normals is not None
    assert after.tangents is not None and after.indices is not None
    appended = len(after.positions) - len(before.positions)
    assert appended > 0 and f"{appended} appended at seams" in printed
    # Each corner of the written mesh carries mikktspace.c's tangent for the file's own data,
    # which has V down: flip_v=True there.
    expected = tbasis.generate_corners(
        before.positions, before.normals, before.texcoords, before.indices, method="mikktspace", flip_v=True
    )
    written = after.tangents[after.indices.astype(np.int64)]
    assert same_bits(written[:, 3], expected[:, 3])
    np.testing.assert_allclose(written[:, :3], expected[:, :3], atol=1e-6)
    assert same_bits(after.positions[after.indices.astype(np.int64)], before.positions[before.indices.astype(np.int64)])


def test_gltf_example_refuses_to_run_without_pillow(tmp_path: Path) -> None:
    mesh = torus(nu=8, nv=4)
    source, target = tmp_path / "in.glb", tmp_path / "out.glb"
    write_glb(source, mesh.positions, mesh.normals, mesh.uvs, mesh.indices.reshape(-1, 3))
    # The example run with Pillow made unimportable.
    without_pillow = (
        "import runpy, sys; sys.modules['PIL'] = None; sys.argv = sys.argv[1:]; "
        "runpy.run_path(sys.argv[0], run_name='__main__')"
    )
    run = subprocess.run(
        [sys.executable, "-c", without_pillow, str(EXAMPLES / "gltf_tangents.py"), str(source), str(target)],
        capture_output=True,
        text=True,
    )
    assert run.returncode == 1
    assert 'pip install "tbasis[gltf]"' in run.stderr and "Pillow" in run.stderr
    assert not target.exists()


def test_gltf_example_matches_the_tangents_blender_stored(tmp_path: Path) -> None:
    require_corpus_file(MIRROR_TEST)
    target = tmp_path / "out.glb"
    run_example(MIRROR_TEST, target)
    # With Pillow (the gltf extra), the images and the normal texture are written too (trimesh may
    # write an image once per texture that uses it).
    source_document, _ = gltf.read(MIRROR_TEST)
    written_document, _ = gltf.read(target)
    assert len(written_document.get("images", [])) >= len(source_document["images"]) > 0
    assert any("normalTexture" in material for material in written_document["materials"])
    (stored,) = gltf.primitives(MIRROR_TEST)
    (written,) = gltf.primitives(target)
    assert stored.tangents is not None and written.tangents is not None
    assert len(written.positions) == len(stored.positions)  # the exporter split the seams already
    assert same_bits(written.tangents[:, 3], stored.tangents[:, 3])
    cosine = np.einsum(
        "ij,ij->i", written.tangents[:, :3].astype(np.float64), stored.tangents[:, :3].astype(np.float64)
    )
    cosine /= np.linalg.norm(written.tangents[:, :3], axis=1) * np.linalg.norm(stored.tangents[:, :3], axis=1)
    assert np.degrees(np.arccos(np.clip(cosine, -1, 1))).max() < 0.05

    # With flip_v=True on trimesh's (already flipped) UVs, w would be wrong everywhere.
    loaded = next(iter(trimesh.load_scene(MIRROR_TEST, process=False).geometry.values()))
    assert isinstance(loaded, trimesh.Trimesh) and isinstance(loaded.visual, trimesh.visual.TextureVisuals)
    wrong = tbasis.generate(
        loaded.vertices, loaded.vertex_normals, loaded.visual.uv, loaded.faces, method="mikktspace", flip_v=True
    )
    assert np.all(wrong[:, 3] == -stored.tangents[:, 3])
