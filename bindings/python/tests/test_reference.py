"""The reference's ctypes mirrors (reference.py) follow include/tbasis.h field for field: a
missing or misplaced field would let the C library write past them or read the wrong one."""

from __future__ import annotations

import ctypes
import re
from typing import Any

import pytest

import reference
from support import REPOSITORY, require

HEADER = REPOSITORY / "include" / "tbasis.h"
# The C field types the structs use, as ctypes spells them.
CTYPES: dict[str, Any] = {
    "size_t": ctypes.c_size_t,
    "uint32_t": ctypes.c_uint32,
    "float": ctypes.c_float,
    "void *": ctypes.c_void_p,
    "const void *": ctypes.c_void_p,
}


def header_fields(struct: str) -> list[tuple[str, Any]]:
    """The fields of ``struct`` in the header, in order, as (name, ctypes type)."""
    text = HEADER.read_text()
    body = re.search(r"typedef struct %s \{(.*?)\} %s;" % (struct, struct), text, re.S)
    assert body, f"{struct} is not in {HEADER}"
    fields: list[tuple[str, Any]] = []
    for line in body.group(1).splitlines():
        line = line.strip()
        if not line or line.startswith("//"):
            continue
        found = re.fullmatch(r"(.*?)\s*\b(\w+);", line)
        assert found, f"{struct}: cannot read the line {line!r}"
        fields.append((found.group(2), CTYPES[found.group(1)]))
    return fields


@pytest.mark.parametrize(
    "struct, mirror",
    [
        ("tbasis_mesh", reference.Mesh),
        ("tbasis_options", reference.Options),
        ("tbasis_output", reference.Output),
        ("tbasis_report", reference.CReport),
    ],
)
def test_the_mirrors_follow_the_header(struct: str, mirror: type[ctypes.Structure]) -> None:
    require(HEADER.is_file(), f"the header {HEADER}")
    assert [(field[0], field[1]) for field in mirror._fields_] == header_fields(struct)
