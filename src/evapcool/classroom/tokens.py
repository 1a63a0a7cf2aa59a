"""The class server's secrets, kept only as digests: the single class's lecturer's token
and its projector's key, a department class's projector key, the administrator's token."""

from __future__ import annotations

import hashlib
import hmac
import secrets

from evapcool.classroom.store import ClassStore

#: The store's names of the digests of the single class's lecturer's token, its projector's
#: key, and the department's administrator's token.
LECTURER_SECRET = "lecturer"
PROJECTOR_SECRET = "projector"
ADMIN_SECRET = "admin"


def digest(secret: str) -> str:
    """What the store keeps of a secret (SHA-256, hex)."""
    return hashlib.sha256(secret.encode()).hexdigest()


def projector_key(lecturer_token: str) -> str:
    """The projector's key, made from the lecturer's token (so the lecturer's page can give
    it, though the server keeps only digests); it shows replay codes, nothing more."""
    mac = hmac.new(lecturer_token.encode(), b"evapcool projector", hashlib.sha256)
    return mac.hexdigest()[:32]


def room_projector_key(lecturer_digest: str, code: str) -> str:
    """A department class's projector key, made from its lecturer's digest and its code
    (the lecturer's page gives it; the server checks it without storing it)."""
    mac = hmac.new(lecturer_digest.encode(), b"evapcool projector " + code.encode(), "sha256")
    return mac.hexdigest()[:32]


def new_lecturer_token(store: ClassStore) -> str:
    """A new lecturer's token (the last one stops working); the store keeps its digests."""
    token = secrets.token_urlsafe(24)
    store.set_secret(LECTURER_SECRET, digest(token))
    store.set_secret(PROJECTOR_SECRET, digest(projector_key(token)))
    return token


def matches_digest(given: str, wanted: str | None) -> bool:
    """Whether a secret given matches a stored digest (in constant time)."""
    return wanted is not None and secrets.compare_digest(digest(given), wanted)
