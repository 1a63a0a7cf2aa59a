"""Classes (rooms) of a department's server: join codes that are easy to say and type."""

from __future__ import annotations

import secrets

#: Capitals and digits that cannot be mistaken for one another read aloud or on a phone's
#: keyboard: no 0/O/Q/D-like pairs, 1/I/L, 2/Z, 5/S, 8/B, U/V.
CODE_ALPHABET = "ACEFGHJKMNPRTWXY34679"
CODE_LENGTH = 6
#: The class a single-class server (and a file made before classes) holds.
DEFAULT_ROOM = 1


def new_code() -> str:
    """A random join code (the store enforces that no two classes share one)."""
    return "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))


def normal_code(text: str) -> str | None:
    """A join code as typed (any case, spaces or dashes) in its stored form, else None."""
    code = "".join(ch for ch in text.upper() if ch not in " -")
    if len(code) != CODE_LENGTH or any(ch not in CODE_ALPHABET for ch in code):
        return None
    return code
