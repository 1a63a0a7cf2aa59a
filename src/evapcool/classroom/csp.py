"""Content-Security-Policy of the class server's pages: each page's one script and one
style named by hash, and nothing from elsewhere."""

from __future__ import annotations

import base64
import hashlib

__all__ = ["page_policy", "source_hash"]


def source_hash(text: str) -> str:
    """A script's or style's CSP source: 'sha256-<base64 of its SHA-256>'."""
    return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() + "'"


def page_policy(script: str, style: str, frames: str = "'none'") -> str:
    """The policy of a page: its one script and one style, talking to this server only
    (frames: what it may show in a frame; the projector, this server's game page)."""
    return (
        f"default-src 'none'; script-src {source_hash(script)}; "
        f"style-src {source_hash(style)}; connect-src 'self'; frame-src {frames}; "
        "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
    )
