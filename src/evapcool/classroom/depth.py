"""How deep parsed JSON nests (standard library only: the verifying workers use it too).

The parser itself refuses nesting past about a thousand levels (RecursionError, which the
callers catch); this bounds it to what a request needs, without recursion of its own.
"""

from __future__ import annotations

#: JSON nesting a request may have (a recording inside a submission needs 4).
MAX_DEPTH = 16


def too_deep(doc: object, limit: int = MAX_DEPTH) -> bool:
    """Whether a parsed JSON value nests arrays and objects deeper than `limit`."""
    level, depth = [doc], 1
    while True:
        # Level by level, keeping only containers: a recording's thousands of numbers are
        # looked at once each, in one comprehension (the server checks every code so).
        containers = [x for x in level if isinstance(x, (list, dict))]
        if not containers:
            return False
        if depth > limit:
            return True
        level = [y for x in containers for y in (x.values() if isinstance(x, dict) else x)]
        depth += 1
