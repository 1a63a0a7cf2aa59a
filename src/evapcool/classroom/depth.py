"""How deep JSON nests, found without parsing it (standard library only: the verifying
workers use it too)."""

from __future__ import annotations

import re

#: JSON nesting a request may have (a recording inside a submission needs 4).
MAX_DEPTH = 16
_STRINGS = re.compile(rb'"(?:[^"\\]|\\.)*"', re.S)
_BRACKETS = re.compile(rb"[\[\]{}]")


def too_deep(text: bytes, limit: int = MAX_DEPTH) -> bool:
    """Whether JSON text nests arrays and objects deeper than `limit` (strings skipped),
    found without parsing it (the parser recurses, and gives up only past a thousand)."""
    depth = 0
    for bracket in _BRACKETS.finditer(_STRINGS.sub(b'""', text)):
        depth += 1 if bracket.group() in (b"[", b"{") else -1
        if depth > limit:
            return True
    return False
