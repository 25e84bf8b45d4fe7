"""On every mesh of the corpus, under every method and policy, the package gives the same bits
as the library's C ABI (reference.py): per vertex with bitangents, per corner, the seam split,
the reports and the errors."""

from __future__ import annotations

import dataclasses
from typing import Any, Optional

import numpy as np
import pytest
from numpy.typing import NDArray

import corpus
import reference
import tbasis
from support import same_bits

CODES = {member: code for code, member in enumerate(tbasis.Method)}
POLICY_CODES = {member: code for code, member in enumerate(tbasis.Policy)}
# C statuses the package turns into these classes.
ERRORS = {1: tbasis.MissingTexcoordsError, 11: tbasis.DegenerateUvError, 19: tbasis.InvalidOptionError}


def for_reference(indices: Optional[NDArray[Any]]) -> Optional[NDArray[Any]]:
    """The C ABI takes uint16 or uint32 indices; the package converts other types itself."""
    if indices is None or indices.dtype in (np.uint16, np.uint32):
        return indices
    return indices.astype(np.uint32)


def compare(part: corpus.Part, method: tbasis.Method, policy: tbasis.Policy, corners: bool) -> Optional[str]:
    """What differs between the package and the C ABI, or None."""
    what = f"{part.name} {method.value}/{policy.value}{' per corner' if corners else ''}"
    args = (
        part.positions,
        part.normals,
        part.texcoords,
        for_reference(part.indices),
        CODES[method],
        POLICY_CODES[policy],
    )
    expected = (reference.generate_corners if corners else reference.generate)(*args, flip_v=part.v_down)
    try:
        if corners:
            tangents, report = tbasis.generate_corners(
                part.positions,
                part.normals,
                part.texcoords,
                part.indices,
                method=method,
                policy=policy,
                flip_v=part.v_down,
                threads=2,
                report=True,
            )
            bitangents = None
        else:
            tangents, bitangents, report = tbasis.generate(
                part.positions,
                part.normals,
                part.texcoords,
                part.indices,
                method=method,
                policy=policy,
                flip_v=part.v_down,
                threads=2,
                bitangents=True,
                report=True,
            )
    except tbasis.Error as error:
        if expected.status == 0 or not isinstance(error, ERRORS.get(expected.status, ())):
            return f"{what}: raised {error!r}, the C ABI returned status {expected.status}"
        if isinstance(error, tbasis.DegenerateUvError):
            if dataclasses.astuple(error.report) != expected.report:
                return f"{what}: report {error.report} != {expected.report}"
            if error.triangle != expected.report[1]:
                return f"{what}: names triangle {error.triangle}, the C report {expected.report[1]}"
        return None
    if expected.status != 0:
        return f"{what}: succeeded, the C ABI returned status {expected.status}"
    if dataclasses.astuple(report) != expected.report:
        return f"{what}: report {report} != {expected.report}"
    if not same_bits(tangents, expected.tangents):
        differing = np.count_nonzero(tangents.view(np.uint32) != expected.tangents.view(np.uint32))
        return f"{what}: tangents differ in {differing} floats"
    if bitangents is not None and (expected.bitangents is None or not same_bits(bitangents, expected.bitangents)):
        return f"{what}: bitangents differ"
    return None


@pytest.mark.parametrize("relative", corpus.paths() or ["(no corpus)"])
def test_every_method_and_policy_gives_the_c_abis_bits(relative: str) -> None:
    corpus.require_corpus()
    reference.library()
    parts = corpus.parts(relative)
    assert parts, relative
    problems = []
    for part in parts:
        for method in tbasis.Method:
            for policy in tbasis.Policy:
                for corners in (False, True):
                    problem = compare(part, method, policy, corners)
                    if problem:
                        problems.append(problem)
    assert not problems, "\n".join(problems[:20])


@pytest.mark.parametrize("relative", corpus.paths() or ["(no corpus)"])
def test_seam_split_of_mikktspace_corners_gives_the_c_abis(relative: str) -> None:
    corpus.require_corpus()
    reference.library()
    for part in corpus.parts(relative):
        if part.texcoords is None:
            continue
        corners = tbasis.generate_corners(
            part.positions, part.normals, part.texcoords, part.indices, method="mikktspace", flip_v=part.v_down
        )
        split = tbasis.split_corners(part.indices, len(part.positions), corners)
        status, indices, sources = reference.split_corners(
            part.positions, part.normals, for_reference(part.indices), corners
        )
        assert status == 0, part.name
        assert np.array_equal(split.indices.ravel(), indices), part.name
        assert np.array_equal(split.sources, sources), part.name
