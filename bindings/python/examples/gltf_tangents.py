"""MikkTSpace tangents for a glTF file: load it with trimesh, compute the tangents normal maps are
baked against, write them into a new .glb as each primitive's TANGENT attribute.

    pip install "./bindings/python[gltf]"    # the package with trimesh and Pillow
    python gltf_tangents.py IN.gltf OUT.glb

What trimesh does with glTF (checked by the tests, for trimesh 4 and 5):

- It flips V on load: its UVs are ``(u, 1 - v)`` of the file's TEXCOORD_0, V pointing up. That is
  exactly the ``v' = 1 - v`` MikkTSpace is run on for glTF, so ``flip_v=False`` here. (Reading
  TEXCOORD_0 from the file directly, V points down: ``flip_v=True``.) It flips V back on export.
- It loads TEXCOORD_0 only for primitives that have a material; the others are left out here.
- It does not load a TANGENT attribute, and exports ``vertex_attributes["TANGENT"]`` as the custom
  attribute ``_TANGENT``, so the written file is renamed to TANGENT afterwards.
- ``process=False`` keeps the file's vertices: merging them would change the tangents.

MikkTSpace gives a tangent per triangle corner; where the corners of one vertex disagree (mirror
seams), ``split_corners`` duplicates that vertex, and every attribute gets the copies. Without
Pillow, trimesh drops the images and textures on load, so the example refuses to run without it.
"""

from __future__ import annotations

import importlib
import json
import struct
import sys

import numpy as np

import tbasis

NEEDS = (
    'gltf_tangents.py needs trimesh and Pillow (without Pillow the written file would lose its images and '
    'textures): pip install "tbasis[gltf]", or from a clone pip install "./bindings/python[gltf]"'
)


def importable(module: str) -> bool:
    try:
        importlib.import_module(module)
    except ImportError:
        return False
    return True


if not (importable("trimesh") and importable("PIL.Image")):
    sys.exit(NEEDS)

import trimesh  # noqa: E402  (after the check, which names the extra to install)


def with_tangents(mesh: trimesh.Trimesh, visual: trimesh.visual.TextureVisuals) -> trimesh.Trimesh:
    """A copy of ``mesh`` (whose visual is ``visual``) with MikkTSpace tangents, its seam vertices split."""
    uv = visual.uv
    corners = tbasis.generate_corners(mesh.vertices, mesh.vertex_normals, uv, mesh.faces, method="mikktspace")
    split = tbasis.split_corners(mesh.faces, len(mesh.vertices), corners)
    tangents = np.empty((len(mesh.vertices) + len(split.sources), 4), dtype=np.float32)
    # After the split, all corners of a vertex carry the same tangent: the vertex's.
    tangents[split.indices.ravel()] = corners
    result = trimesh.Trimesh(
        vertices=tbasis.apply_split(mesh.vertices, split.sources),
        faces=split.indices,
        vertex_normals=tbasis.apply_split(mesh.vertex_normals, split.sources),
        visual=trimesh.visual.TextureVisuals(uv=tbasis.apply_split(uv, split.sources), material=visual.material),
        vertex_attributes={
            key: tbasis.apply_split(value, split.sources) for key, value in mesh.vertex_attributes.items()
        },
        metadata=mesh.metadata,
        process=False,
    )
    result.vertex_attributes["TANGENT"] = tangents
    return result


def rename_attribute(glb: bytes, old: str, new: str) -> bytes:
    """``glb`` with every primitive attribute ``old`` renamed ``new`` in its JSON chunk."""
    magic, version, _ = struct.unpack_from("<4sII", glb, 0)
    length, kind = struct.unpack_from("<I4s", glb, 12)
    assert magic == b"glTF" and kind == b"JSON"
    document = json.loads(glb[20 : 20 + length])
    for mesh in document.get("meshes", []):
        for primitive in mesh["primitives"]:
            attributes = primitive["attributes"]
            if old in attributes:
                attributes[new] = attributes.pop(old)
    text = json.dumps(document, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)  # chunks are 4-byte aligned; JSON pads with spaces
    rest = glb[20 + length :]
    header = struct.pack("<4sII", magic, version, 20 + len(text) + len(rest))
    return header + struct.pack("<I4s", len(text), b"JSON") + text + rest


def main(source: str, target: str) -> None:
    scene = trimesh.load_scene(source, process=False)
    for name, geometry in list(scene.geometry.items()):
        visual = getattr(geometry, "visual", None)
        if not (isinstance(visual, trimesh.visual.TextureVisuals) and visual.uv is not None):
            print(f"{name}: no texture coordinates as trimesh reads it, left as it is")
            continue
        assert isinstance(geometry, trimesh.Trimesh)
        scene.geometry[name] = with_tangents(geometry, visual)
        appended = len(scene.geometry[name].vertices) - len(geometry.vertices)
        print(f"{name}: {len(geometry.vertices)} vertices, {appended} appended at seams")
    glb = scene.export(file_type="glb")
    assert isinstance(glb, bytes)
    with open(target, "wb") as file:
        file.write(rename_attribute(glb, "_TANGENT", "TANGENT"))


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit(f"usage: {sys.argv[0]} IN.gltf OUT.glb")
    main(sys.argv[1], sys.argv[2])
