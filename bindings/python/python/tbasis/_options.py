"""Methods and degenerate-UV policies, by name or as enum members."""

from __future__ import annotations

import enum
import math
import operator
from typing import Literal, Optional, SupportsIndex, TypeVar, Union

from ._errors import InvalidOptionError

__all__ = ["Method", "Policy", "MethodName", "PolicyName"]


class Method(str, enum.Enum):
    """How the per-triangle tangents are combined at a vertex (README: "Methods").

    Members are strings, so ``Method.MIKKTSPACE == "mikktspace"``; either form is accepted.
    """

    DEFAULT = "default"
    """The library's default, ``ANGLE``."""
    LENGYEL = "lengyel"
    """Each triangle's unnormalized dP/du, as in Lengyel's listing."""
    ANGLE = "angle"
    """Projected unit tangents weighted by the corner angle in the tangent plane."""
    AREA = "area"
    """Unit face tangents weighted by triangle area."""
    UNIFORM = "uniform"
    """Unit face tangents with equal weights."""
    MIKKTSPACE = "mikktspace"
    """Exactly mikktspace.c's frame per corner; per vertex, its first corner's."""


class Policy(str, enum.Enum):
    """What happens to triangles with degenerate texture coordinates (README: "Degenerate-UV
    policies")."""

    DEFAULT = "default"
    """The method's default: ``LEGACY`` for ``MIKKTSPACE`` (exactly mikktspace.c), else ``INHERIT``."""
    LEGACY = "legacy"
    """Exactly the original computation, inf and NaN included."""
    SKIP = "skip"
    """Degenerate triangles contribute nothing; a vertex left without a tangent falls back."""
    INHERIT = "inherit"
    """Like ``SKIP``, but such a vertex first takes a tangent from its neighbours."""
    REJECT = "reject"
    """Raise ``DegenerateUvError`` naming the first degenerate triangle."""


MethodName = Literal["default", "lengyel", "angle", "area", "uniform", "mikktspace"]
PolicyName = Literal["default", "legacy", "skip", "inherit", "reject"]

# The C values (include/tbasis.h): 0 is each default, the others in the order of the members.
_METHOD_CODES = {member: code for code, member in enumerate(Method)}
_POLICY_CODES = {member: code for code, member in enumerate(Policy)}


def method_code(method: Union[Method, MethodName]) -> int:
    return _METHOD_CODES[_member(Method, method, "method")]


def policy_code(policy: Union[Policy, PolicyName]) -> int:
    return _POLICY_CODES[_member(Policy, policy, "policy")]


_Member = TypeVar("_Member", Method, Policy)


def _member(kind: type[_Member], value: object, what: str) -> _Member:
    try:
        return kind(value)
    except (ValueError, TypeError):
        names = ", ".join(repr(member.value) for member in kind)
        raise InvalidOptionError(f"{what} must be one of {names} or a tbasis.{kind.__name__}, not {value!r}") from None


def threads_value(threads: SupportsIndex) -> int:
    """``threads`` as the library's unsigned 32-bit count."""
    try:
        value = operator.index(threads)
    except TypeError:
        raise InvalidOptionError(f"threads must be an integer, not {threads!r}") from None
    if not 0 <= value < 2**32:
        raise InvalidOptionError(f"threads must be between 0 and 2**32 - 1, not {value}")
    return value


def threshold_value(threshold: Optional[float]) -> Optional[float]:
    """``threshold`` checked; None is the library's default (1e-5)."""
    if threshold is None:
        return None
    try:
        value = float(threshold)
    except (TypeError, ValueError):
        raise InvalidOptionError(f"threshold must be a number or None, not {threshold!r}") from None
    if not (math.isfinite(value) and value >= 0.0):
        raise InvalidOptionError(f"threshold must be finite and not negative, not {value}")
    return value
