"""The tests run against the installed package, which is complete: the compiled module, the
typing files, the version, the one declared dependency."""

from __future__ import annotations

import importlib.metadata
import re
from pathlib import Path

import tbasis
import tbasis._native
from support import REPOSITORY


def test_the_package_is_the_installed_one_not_the_source_tree() -> None:
    package = Path(tbasis.__file__).resolve().parent
    # The virtual environment may sit in the repository's target directory: what matters is that
    # the package comes from its site-packages, not from the sources.
    sources = REPOSITORY / "bindings" / "python"
    assert sources not in package.parents, f"tbasis was imported from the source tree: {package}"
    assert "site-packages" in package.parts, f"tbasis is not an installed package: {package}"
    assert Path(tbasis._native.__file__).parent == package
    for name in ("py.typed", "_native.pyi"):
        assert (package / name).is_file(), name


def test_one_compiled_module_for_every_cpython_from_39() -> None:
    native = Path(tbasis._native.__file__).name
    assert native.startswith("_native.") and (".abi3." in native or native.endswith(".pyd")), native
    requires = importlib.metadata.metadata("tbasis")["Requires-Python"]
    assert requires == ">=3.9"


def test_version_follows_the_library() -> None:
    major, rest = divmod(tbasis._native.library_version, 1_000_000)
    minor, patch = divmod(rest, 1000)
    assert tbasis.__version__ == f"{major}.{minor}.{patch}" == importlib.metadata.version("tbasis")


def test_numpy_is_the_one_declared_dependency() -> None:
    requirements = importlib.metadata.requires("tbasis") or []
    # Extras (`; extra == ...`) are optional; every other requirement is installed with the package.
    installed = [requirement for requirement in requirements if "extra ==" not in requirement]
    names = [re.split(r"[<>=!~;\[ ]", requirement, maxsplit=1)[0] for requirement in installed]
    assert names == ["numpy"], requirements


def test_the_public_names() -> None:
    for name in tbasis.__all__:
        assert hasattr(tbasis, name), name
    assert [m.value for m in tbasis.Method] == ["default", "lengyel", "angle", "area", "uniform", "mikktspace"]
    assert [p.value for p in tbasis.Policy] == ["default", "legacy", "skip", "inherit", "reject"]
