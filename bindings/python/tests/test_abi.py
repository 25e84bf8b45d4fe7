"""The binding mirrors include/tbasis.h: constants, struct fields (order, types, offsets, sizes)."""

import ctypes
import re
import shutil
import subprocess
from pathlib import Path

import pytest

import tbasis

HEADER = Path(__file__).resolve().parents[3] / "include" / "tbasis.h"
STRUCTS = [tbasis.tbasis_mesh, tbasis.tbasis_options, tbasis.tbasis_output, tbasis.tbasis_report]
C_TYPES = {
    "size_t": ctypes.c_size_t,
    "const void *": ctypes.c_void_p,
    "void *": ctypes.c_void_p,
    "uint32_t": ctypes.c_uint32,
    "float": ctypes.c_float,
}


def header_text():
    # Comments dropped so that only declarations are parsed.
    return re.sub(r"//[^\n]*|/\*.*?\*/", "", HEADER.read_text(), flags=re.S)


def python_value(name):
    """The binding's value for a header constant, or None when it has none."""
    suffix = name[len("TBASIS_"):]
    groups = [("METHOD_", tbasis.Method), ("DEGENERATE_", tbasis.Policy), ("ERROR_", tbasis.Status)]
    for prefix, enum in groups:
        if suffix.startswith(prefix):
            member = getattr(enum, suffix[len(prefix):], None)
            return None if member is None else int(member)
    if suffix == "OK":
        return int(tbasis.Status.OK)
    return getattr(tbasis, suffix, None)


def test_every_header_constant_is_mirrored():
    defines = dict(re.findall(r"^#define (TBASIS_\w+) (.+)$", header_text(), flags=re.M))
    assert len(defines) >= 30
    for name, value in defines.items():
        assert python_value(name) == eval(value, {}), name
    # And nothing in the enums that the header does not have (DEFAULT is the header's 0).
    for prefix, enum in [("METHOD_", tbasis.Method), ("DEGENERATE_", tbasis.Policy), ("ERROR_", tbasis.Status)]:
        for member in enum:
            if member.name not in ("DEFAULT", "OK"):
                assert f"TBASIS_{prefix}{member.name}" in defines


@pytest.mark.parametrize("struct", STRUCTS, ids=lambda s: s.__name__)
def test_struct_fields_match_the_header_in_order_and_type(struct):
    body = re.search(r"typedef struct %s \{(.*?)\} %s;" % (struct.__name__, struct.__name__), header_text(), re.S)
    assert body, struct.__name__
    fields = re.findall(r"^\s*(.+?)\s*\b(\w+);\s*$", body.group(1), flags=re.M)
    assert len(fields) == len(struct._fields_)
    for (c_type, c_name), (name, py_type) in zip(fields, struct._fields_):
        assert c_name == name
        assert C_TYPES[c_type.replace("*", " *").replace("  ", " ")] is py_type, (name, c_type)


def test_struct_sizes_and_offsets_match_the_c_compiler(tmp_path):
    compiler = shutil.which("cc") or shutil.which("gcc")
    if compiler is None:
        pytest.skip("no C compiler (cc or gcc) to check the struct layouts with")
    lines = ['#include "tbasis.h"', "#include <stddef.h>", "#include <stdio.h>", "int main(void) {"]
    for struct in STRUCTS:
        lines.append(f'printf("{struct.__name__} %zu\\n", sizeof(struct {struct.__name__}));')
        for name, _ in struct._fields_:
            lines.append(f'printf("{struct.__name__}.{name} %zu\\n", offsetof(struct {struct.__name__}, {name}));')
    lines += ["return 0;", "}"]
    source, exe = tmp_path / "layout.c", tmp_path / "layout"
    source.write_text("\n".join(lines) + "\n")
    subprocess.run([compiler, "-std=c99", "-I", str(HEADER.parent), str(source), "-o", str(exe)], check=True)
    printed = subprocess.run([str(exe)], check=True, capture_output=True, text=True).stdout
    reported = dict(line.rsplit(" ", 1) for line in printed.splitlines())

    expected = {}
    for struct in STRUCTS:
        expected[struct.__name__] = ctypes.sizeof(struct)
        for name, _ in struct._fields_:
            expected[f"{struct.__name__}.{name}"] = getattr(struct, name).offset
    assert {key: int(value) for key, value in reported.items()} == expected


def test_library_version_and_functions():
    assert tbasis.version() == tbasis.VERSION
    lib = tbasis._lib()
    for name in ("tbasis_generate", "tbasis_generate_corners", "tbasis_calculate_tangent_array",
                 "tbasis_scratch_size", "tbasis_status_string", "tbasis_version"):
        assert hasattr(lib, name)
    assert tbasis.status_string(tbasis.Status.OK)
    assert tbasis.status_string(tbasis.Status.OVERLAP) != tbasis.status_string(tbasis.Status.OK)
