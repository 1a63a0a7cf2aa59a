"""One rule for every number a path, query or form gives: ASCII digits only, bounded
(`str.isdigit` also takes "²" and "①", which `int` refuses)."""

from __future__ import annotations

from evapcool.classroom.errors import RefusedError

#: The largest id a store holds (SQLite's and PostgreSQL's bigint).
ID_MAX = 2**63 - 1
_DIGITS = frozenset("0123456789")


def digits_value(text: str | None, low: int, high: int) -> int | None:
    """The whole number low..high that `text` spells in ASCII digits, else None (no sign,
    no spaces, at most as many digits as `high` has: int() never sees a long text)."""
    if text is None or not 0 < len(text) <= len(str(high)) or not set(text) <= _DIGITS:
        return None
    value = int(text)
    return value if low <= value <= high else None


def whole_number(text: str | None, field: str, low: int = 1, high: int = ID_MAX) -> int:
    """`digits_value`, or RefusedError 400 naming `field` and the numbers allowed."""
    value = digits_value(text, low, high)
    if value is None:
        raise RefusedError(400, field, "class.error.value", allowed=f"{low}..{high}")
    return value
