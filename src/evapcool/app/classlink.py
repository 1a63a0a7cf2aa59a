"""The applet in a class competition (`evapcool --class URL`, docs/class.md).

Talks to the class server's API with urllib on a thread of its own, so the frame loop
never waits for the network: it fetches the open challenge and joins with the player's
name, then sends the replay code of each win (and of each game lost for good, when the
challenge counts lost games). The app reads what came back with `poll()` each frame and
shows it as notices. Its student token is kept per class (the server and the class's code
in its address, `class_key`) in the data folder (`remember_in`), so an applet started
again joins as the same student, and a student of two classes is herself in each.
"""

from __future__ import annotations

import itertools
import json
import queue
import socket
import threading
import time
import urllib.error
import urllib.request
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any
from urllib.parse import urlsplit, urlunsplit

from evapcool.fileio import atomic_write_text, read_user_text
from evapcool.game.replay import Settings

#: Seconds a request may take before the player is told the server did not answer.
TIMEOUT = 20.0
#: Times a request is sent again while the server answers 503 (a department's database
#: away for a moment): about two minutes at the server's Retry-After of 5 s.
STORE_AWAY_RESENDS = 24
#: The file in the data folder keeping the student token per class: {class_key: token}.
TOKENS_FILE = "class-tokens.json"
TOKENS_MAX_BYTES = 1_000_000
BAD_URL = (
    "--class must be the class server's address: http:// or https:// and a host, "
    "like http://192.168.1.10:8765/ (got {value!r})"
)


def check_url(value: str) -> str:
    """The class server's base address (ending in /), or ValueError saying what is allowed."""
    try:
        parts = urlsplit(value)
        ok = parts.scheme in ("http", "https") and bool(parts.hostname) and parts.port != 0
    except ValueError:
        ok = False
    if not ok or parts.query or parts.fragment:
        raise ValueError(BAD_URL.format(value=value))
    return value if value.endswith("/") else value + "/"


def class_key(base: str) -> str:
    """The key of a class's kept token: its server (scheme, host and port as written the
    same way however typed) and its path with a department class's join code as stored
    (/c/ab-c123 and /c/ABC123 are one class)."""
    parts = urlsplit(check_url(base))
    host = (parts.hostname or "").lower()
    default = {"http": 80, "https": 443}[parts.scheme]
    netloc = host if parts.port in (None, default) else f"{host}:{parts.port}"
    if ":" in host:  # an IPv6 address keeps its brackets
        netloc = f"[{host}]" if parts.port in (None, default) else f"[{host}]:{parts.port}"
    steps = parts.path.split("/")
    if len(steps) >= 3 and steps[1] == "c":
        steps[2] = "".join(ch for ch in steps[2].upper() if ch not in " -")
    return urlunsplit((parts.scheme, netloc, "/".join(steps), "", ""))


@dataclass(frozen=True)
class Challenge:
    """The open challenge: its id, the settings and seed every student plays, whether it
    counts lost games, and its frame limit (a lost game is cut to it)."""

    id: int
    settings: Settings
    seed: int
    lost: bool = False
    max_frames: int | None = None

    @classmethod
    def from_json(cls, doc: dict[str, Any]) -> Challenge:
        s = doc["settings"]
        settings = Settings(
            n_atoms=int(s["n_atoms"]),
            radius=float(s["radius"]),
            escape=str(s["escape"]),
            tc_exponent=float(s["tc_exponent"]),
        )
        limit = doc.get("max_frames")
        return cls(
            int(doc["id"]),
            settings,
            int(doc["seed"]),
            bool(doc.get("lost", False)),
            int(limit) if isinstance(limit, int) else None,
        )


class RefusedError(Exception):
    """The server answered with an error: its message (in the server's words)."""


@dataclass(frozen=True)
class Event:
    """What came back: 'joined' (challenge, name), 'result' (the answer's JSON),
    'refused' (message) or 'unreachable' (why, a word of `_problem`)."""

    kind: str
    value: Any = None
    name: str = ""


class ClassLink:
    """The applet's connection to one class server; every request runs on its thread."""

    def __init__(
        self, base: str, name: str, timeout: float = TIMEOUT, *, named: bool = True
    ) -> None:
        self.base = check_url(base)
        self.name = name
        #: The player gave the name (--name), rather than the login's being taken.
        self.named = named
        self.timeout = timeout
        self.token: str | None = None
        self.challenge: Challenge | None = None
        self.tokens_file: Path | None = None
        self._tasks: queue.Queue[Callable[[], None]] = queue.Queue()
        self._events: queue.Queue[Event] = queue.Queue()
        self._thread = threading.Thread(target=self._work, name="evapcool-class", daemon=True)

    def remember_in(self, folder: Path) -> None:
        """Keep the student token for this server in `folder` (the app's data folder)."""
        self.tokens_file = folder / TOKENS_FILE

    def start(self) -> None:
        """Fetch the challenge and join, in the background."""
        self._thread.start()
        self._tasks.put(self._join)

    def submit(self, code: str) -> None:
        """Send a won game's replay code, in the background (after the join)."""
        self._tasks.put(lambda: self._submit(code))

    def poll(self) -> list[Event]:
        """What came back since the last call (never waits)."""
        found = []
        while True:
            try:
                found.append(self._events.get_nowait())
            except queue.Empty:
                return found

    # -- on the link's thread -----------------------------------------------------------------
    def _work(self) -> None:
        while True:
            task = self._tasks.get()
            try:
                task()
            except RefusedError as exc:
                self._events.put(Event("refused", str(exc)))
            except (OSError, ValueError, KeyError, TypeError) as exc:
                # The network, or an answer that is not the class server's: say so once.
                self._events.put(Event("unreachable", _problem(exc)))

    def _join(self) -> None:
        self.challenge = Challenge.from_json(self._call("GET", "api/challenge"))
        kept = self._kept_tokens()
        key = class_key(self.base)
        body = {"name": self.name}
        earlier = kept.get(key, kept.get(self.base))  # the bare address: kept before 45
        if isinstance(earlier, str):
            body["token"] = earlier  # the same student as last time, if still known
        joined = self._call("POST", "api/join", body)
        token = str(joined["token"])
        if self.tokens_file is not None and kept.get(key) != token:
            kept[key] = token
            try:
                self.tokens_file.parent.mkdir(parents=True, exist_ok=True)
                atomic_write_text(self.tokens_file, json.dumps(kept, indent=1))
            except OSError:
                pass  # not kept: the next start joins anew, which the server may refuse
        self.token = token
        self._events.put(Event("joined", self.challenge, str(joined["name"])))

    def _kept_tokens(self) -> dict[str, Any]:
        """The kept tokens ({} without a file, or if it is not one of ours)."""
        if self.tokens_file is None:
            return {}
        try:
            doc = json.loads(read_user_text(self.tokens_file, TOKENS_MAX_BYTES))
        except (OSError, ValueError):
            return {}
        return doc if isinstance(doc, dict) else {}

    def _submit(self, code: str) -> None:
        if self.token is None or self.challenge is None:
            return  # the join failed and said so; nothing to send to
        body = {"challenge": self.challenge.id, "code": code}
        self._events.put(Event("result", self._call("POST", "api/submit", body)))

    def _call(self, method: str, path: str, body: object = None) -> dict[str, Any]:
        """One request; the answer's JSON object, or RefusedError with the server's message."""
        headers = {"Accept": "application/json", "Accept-Language": "en"}
        data = None
        if body is not None:
            data = json.dumps(body).encode("utf-8")
            headers["Content-Type"] = "application/json"
        if self.token is not None:
            headers["Authorization"] = f"Bearer {self.token}"
        request = urllib.request.Request(self.base + path, data, headers, method=method)
        for resend in itertools.count():
            try:
                with urllib.request.urlopen(request, timeout=self.timeout) as answer:
                    doc = json.loads(answer.read(1_000_000))
                break
            except urllib.error.HTTPError as exc:
                if exc.code != 503 or resend >= STORE_AWAY_RESENDS:
                    raise RefusedError(_refusal(exc)) from None
                time.sleep(_wait_asked(exc.headers.get("Retry-After")))
        if not isinstance(doc, dict):
            raise ValueError("not an answer of a class server")
        return doc


def _wait_asked(header: str | None) -> float:
    """Seconds to wait before sending again, from a Retry-After header (1 to 30; 5 if none)."""
    try:
        asked = float(header or "")
    except ValueError:
        return 5.0
    return min(float(round(asked)), 30.0) if 1.0 <= asked < 1e9 else 5.0


def _refusal(exc: urllib.error.HTTPError) -> str:
    """The message of a refusal {"error": {"field", "message"}}, else the HTTP status."""
    try:
        doc = json.loads(exc.read(100_000))
        return str(doc["error"]["message"])
    except (OSError, ValueError, KeyError, TypeError):
        return f"HTTP {exc.code} {exc.reason}"


def _problem(exc: BaseException) -> str:
    """Why a request failed, as one of the words the notice has (desk.class.why.*):
    'refused' (nothing listens there), 'timeout', 'no_host' (the name is unknown),
    'not_class' (something answered, not a class server) or 'network'."""
    reason = exc.reason if isinstance(exc, urllib.error.URLError) else exc
    if isinstance(reason, ConnectionRefusedError):
        return "refused"
    if isinstance(reason, TimeoutError):
        return "timeout"
    if isinstance(reason, socket.gaierror):
        return "no_host"
    if isinstance(exc, (ValueError, KeyError, TypeError)):
        return "not_class"
    return "network"
