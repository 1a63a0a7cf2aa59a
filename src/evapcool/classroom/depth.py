"""How deep parsed JSON nests (standard library only: the verifying workers use it too).

The parser itself refuses nesting past about a thousand levels (RecursionError, which the
callers catch); this bounds it to what a request needs, without recursion of its own.
"""

from __future__ import annotations

#: JSON nesting a request may have (a recording inside a submission needs 4).
MAX_DEPTH = 16


def too_deep(doc: object, limit: int = MAX_DEPTH) -> bool:
    """Whether a parsed JSON value nests arrays and objects deeper than `limit`."""
    stack: list[tuple[object, int]] = [(doc, 1)]
    while stack:
        item, depth = stack.pop()
        if isinstance(item, (list, dict)):
            if depth > limit:
                return True
            children = item.values() if isinstance(item, dict) else item
            stack.extend((child, depth + 1) for child in children)
    return False
