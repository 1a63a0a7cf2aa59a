"""The students' join address as the projector says it: whether a phone can reach it, and
the command that fixes it when not."""

from __future__ import annotations

import html
import ipaddress
import shlex
from urllib.parse import urlsplit

__all__ = ["command_html", "loopback"]


def loopback(url: str) -> bool:
    """Whether a join address is this computer's own (127.x, ::1, localhost): no phone
    reaches it."""
    host = (urlsplit(url).hostname or "").lower()
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return host == "localhost" or host.endswith(".localhost")


def command_html(command: str) -> str:
    """A shell command for the projector: "evapcool class" and each option whole (no break
    splits "--lan"), a value (a long path, an address) free to wrap anywhere."""
    words = shlex.split(command)

    def piece(word: str, value: bool) -> str:
        kind = "command value" if value else "command"
        return f'<span class="{kind}">{html.escape(shlex.quote(word))}</span>'

    head = f'<span class="command">{html.escape(shlex.join(words[:2]))}</span>'
    rest = [piece(w, not w.startswith("-")) for w in words[2:]]
    return " ".join([head, *rest])
