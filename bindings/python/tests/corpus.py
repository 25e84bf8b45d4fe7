"""The meshes of ../shared/meshes/ (README: "Test corpus") as float32 arrays."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any, Optional

import numpy as np
from numpy.typing import NDArray

import gltf
from support import CORPUS, require_corpus_file

MANIFEST = CORPUS / "MANIFEST.tsv"


@dataclass
class Part:
    """One primitive (glTF) or geometry (OBJ), its texture coordinates as stored in the file."""

    name: str
    positions: NDArray[np.float32]
    normals: NDArray[np.float32]
    texcoords: Optional[NDArray[np.float32]]
    indices: Optional[NDArray[Any]]
    v_down: bool  # glTF: V points down, so flip_v=True is the file's convention


def manifest() -> dict[str, dict[str, str]]:
    """The manifest's rows by mesh path, relative to the corpus; empty without the corpus."""
    if not MANIFEST.is_file():
        return {}
    header, *lines = MANIFEST.read_text().splitlines()
    columns = header.split("\t")
    rows = [dict(zip(columns, line.split("\t"))) for line in lines if line.strip()]
    return {row["path"]: row for row in rows}


def paths() -> list[str]:
    return list(manifest())


def require_corpus() -> None:
    require_corpus_file(MANIFEST)


def parts(relative: str) -> list[Part]:
    path = CORPUS / relative
    if path.suffix in (".gltf", ".glb"):
        return [_gltf_part(primitive) for primitive in gltf.primitives(path)]
    # trimesh computes missing normals slowly without scipy; files without any get them here.
    return _obj_parts(path, stored_normals=float(manifest()[relative]["has_normals"]) > 0)


def _gltf_part(primitive: gltf.Primitive) -> Part:
    normals = primitive.normals
    if normals is None:
        normals = face_normals(primitive.positions, primitive.indices)
    texcoords = None if primitive.texcoords is None else gltf.texcoords_as_floats(primitive.texcoords)
    return Part(primitive.name, primitive.positions, normals, texcoords, primitive.indices, True)


def _obj_parts(path: Path, stored_normals: bool) -> list[Part]:
    import trimesh

    # process=False: every (v, vt, vn) tuple of the file stays its own vertex.
    scene = trimesh.load_scene(path, process=False)
    found = []
    for name, geometry in scene.geometry.items():
        if not isinstance(geometry, trimesh.Trimesh):
            continue
        uv = getattr(geometry.visual, "uv", None)
        positions = np.asarray(geometry.vertices, dtype=np.float32)
        indices = np.asarray(geometry.faces, dtype=np.uint32).ravel()
        found.append(
            Part(
                f"{path.name}:{name}",
                positions,
                np.asarray(geometry.vertex_normals, dtype=np.float32)
                if stored_normals
                else face_normals(positions, indices),
                None if uv is None else np.asarray(uv, dtype=np.float32),
                indices,
                False,
            )
        )
    return found


def face_normals(positions: NDArray[np.float32], indices: Optional[NDArray[Any]]) -> NDArray[np.float32]:
    """Area-weighted vertex normals, for files that store none."""
    corners = np.arange(len(positions)) if indices is None else np.asarray(indices, dtype=np.int64)
    triangles = corners.reshape(-1, 3)
    p = positions.astype(np.float64)
    face = np.cross(p[triangles[:, 1]] - p[triangles[:, 0]], p[triangles[:, 2]] - p[triangles[:, 0]])
    sums = np.zeros_like(p)
    for k in range(3):
        np.add.at(sums, triangles[:, k], face)
    lengths = np.linalg.norm(sums, axis=1, keepdims=True)
    normals: NDArray[np.float32] = (sums / np.where(lengths > 0, lengths, 1.0)).astype(np.float32)
    return normals
