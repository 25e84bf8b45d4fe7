"""Just enough of glTF 2.0 to read the corpus: triangle primitives' positions, normals, first
texture coordinates, tangents and indices, as numpy views of the file's buffers (strided where the
file interleaves them), exactly as stored: V pointing down, as glTF has it."""

from __future__ import annotations

import base64
import json
import struct
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Optional
from urllib.parse import unquote

import numpy as np
from numpy.typing import NDArray

COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}
TYPES = {5121: np.uint8, 5123: np.uint16, 5125: np.uint32, 5126: np.float32, 5120: np.int8, 5122: np.int16}
TRIANGLES = 4


@dataclass
class Primitive:
    name: str
    positions: NDArray[np.float32]
    normals: Optional[NDArray[np.float32]]
    texcoords: Optional[NDArray[Any]]  # float32, or normalized integers (KHR_mesh_quantization)
    tangents: Optional[NDArray[np.float32]]
    indices: Optional[NDArray[Any]]


def read(path: Path) -> tuple[dict[str, Any], list[bytes]]:
    """The JSON document and the buffers of a .gltf or .glb file."""
    data = path.read_bytes()
    binary: Optional[bytes] = None
    if data[:4] == b"glTF":
        offset, document = 12, None
        while offset < len(data):
            length, kind = struct.unpack_from("<I4s", data, offset)
            chunk = data[offset + 8 : offset + 8 + length]
            if kind == b"JSON":
                document = json.loads(chunk)
            elif kind == b"BIN\0":
                binary = chunk
            offset += 8 + length
        assert document is not None, path
    else:
        document = json.loads(data)
    buffers = []
    for buffer in document.get("buffers", []):
        uri = buffer.get("uri")
        if uri is None:
            assert binary is not None, path
            buffers.append(binary)
        elif uri.startswith("data:"):
            buffers.append(base64.b64decode(uri.split(",", 1)[1]))
        else:
            buffers.append((path.parent / unquote(uri)).read_bytes())
    return document, buffers


def accessor(document: dict[str, Any], buffers: list[bytes], index: int) -> NDArray[Any]:
    """An accessor's elements as a read-only view of its buffer, ``(count, components)``."""
    description = document["accessors"][index]
    assert "sparse" not in description, "sparse accessors are not needed by the corpus"
    dtype = np.dtype(TYPES[description["componentType"]]).newbyteorder("<")
    components = COMPONENTS[description["type"]]
    count = description["count"]
    view = document["bufferViews"][description["bufferView"]]
    data = buffers[view["buffer"]]
    start = view.get("byteOffset", 0) + description.get("byteOffset", 0)
    stride = view.get("byteStride", components * dtype.itemsize)
    elements: NDArray[Any] = np.ndarray(
        (count, components), dtype=dtype, buffer=data, offset=start, strides=(stride, dtype.itemsize)
    )
    return elements[:, 0] if description["type"] == "SCALAR" else elements


def primitives(path: Path) -> list[Primitive]:
    """Every triangle-list primitive of every mesh in the file."""
    document, buffers = read(path)
    found = []
    for m, mesh in enumerate(document.get("meshes", [])):
        for p, primitive in enumerate(mesh["primitives"]):
            if primitive.get("mode", TRIANGLES) != TRIANGLES:
                continue
            attributes = primitive["attributes"]

            def attribute(name: str) -> Optional[NDArray[Any]]:
                return accessor(document, buffers, attributes[name]) if name in attributes else None

            positions = attribute("POSITION")
            assert positions is not None and positions.dtype == np.float32
            indices = None if "indices" not in primitive else accessor(document, buffers, primitive["indices"])
            found.append(
                Primitive(
                    f"{path.name}:mesh {m} primitive {p}",
                    positions,
                    attribute("NORMAL"),
                    attribute("TEXCOORD_0"),
                    attribute("TANGENT"),
                    indices,
                )
            )
    return found


def texcoords_as_floats(texcoords: NDArray[Any]) -> NDArray[np.float32]:
    """Texture coordinates in [0, 1] from normalized integers (KHR_mesh_quantization), or as they are."""
    if texcoords.dtype.kind == "f":
        return texcoords
    return (texcoords.astype(np.float32) / np.float32(np.iinfo(texcoords.dtype).max)).astype(np.float32)
