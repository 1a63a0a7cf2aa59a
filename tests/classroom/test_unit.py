"""The class guide's systemd unit, as far as it can be checked without systemd running the
machine: systemd's own verifier reads the unit as the guide gives it, and a department server
started with the unit's options in the sandbox the unit asks for (ProtectSystem=strict: the
whole file system read-only but for /tmp, which PrivateTmp gives it; NoNewPrivileges; no home
to write in) serves a class, verifies a game and writes nothing on the way. What is not
emulated: the user (the test's Python lives in root's home, which no other user can read)."""

from __future__ import annotations

import os
import shlex
import shutil
import subprocess
import sys
from pathlib import Path

import httpx
import pytest
from classhelp import SEED, code, join, open_challenge, start_server
from pghelp import Postgres
from test_proxies import guide_block, unit_options

UNIT = "evapcool-class@.service"
#: The program's own folders (the checkout and its environment), read-only like /opt under
#: the unit even where they lie below /tmp (a CI clone).
PROGRAM = sorted({str(Path(__file__).resolve().parents[2]), sys.prefix})
#: What the unit's settings amount to for the server, run as root in a mount namespace of
#: its own: the root mount read-only, /tmp writable but the program's folders, no new
#: privileges, no home.
SANDBOX = (
    "unshare", "--mount", "--propagation", "private", "sh", "-c",
    "mount --bind /tmp /tmp && mount -o remount,bind,ro / && "
    + "".join(
        f"mount --bind {shlex.quote(p)} {shlex.quote(p)}"
        f" && mount -o remount,bind,ro {shlex.quote(p)} && "
        for p in PROGRAM
    )
    + "exec setpriv --no-new-privs"
    " env -u XDG_DATA_HOME -u XDG_CONFIG_HOME -u XDG_CACHE_HOME -u XDG_STATE_HOME"
    ' HOME=/nonexistent "$@"',
    "sandbox",
)  # fmt: skip


def _verify(unit_text: str, folder: Path) -> str:
    """What `systemd-analyze verify` says of an instance of the unit, in a mount namespace
    where an executable stands at its ExecStart's path (a tmpfs over /opt)."""
    folder.mkdir()
    (folder / UNIT).write_text(unit_text, encoding="utf-8")
    program = "/opt/evapcool/bin/evapcool"
    script = (
        f"mount -t tmpfs tmpfs /opt && mkdir -p {Path(program).parent}"
        f" && printf '#!/bin/sh\\n' > {program} && chmod 755 {program}"
        f' && exec systemd-analyze verify "$1"'
    )
    instance = folder / UNIT.replace("@", "@8765")
    cmd = ["unshare", "--mount", "--propagation", "private", "sh", "-c", script, "-", str(instance)]
    done = subprocess.run(cmd, capture_output=True, text=True, timeout=60, check=False)
    return (done.stdout + done.stderr).strip() + ("" if done.returncode == 0 else " (failed)")


def test_systemd_reads_the_guides_unit_without_a_complaint(tmp_path: Path) -> None:
    if not shutil.which("systemd-analyze"):
        pytest.skip("systemd-analyze is not installed (Debian: apt-get install systemd)")
    if not _sandboxed():
        pytest.skip("needs root, unshare and setpriv (util-linux), and mount namespaces")
    unit = guide_block(UNIT)
    assert "/opt/evapcool/bin/evapcool class" in unit
    assert _verify(unit, tmp_path / "as-given") == ""
    # and the verifier is one that complains (a misspelt setting)
    said = _verify(unit.replace("Restart=", "Restrat="), tmp_path / "misspelt")
    assert "Restrat" in said


def _sandboxed() -> bool:
    """Whether SANDBOX can run here (root, util-linux, mount namespaces allowed)."""
    if os.geteuid() != 0 or not (shutil.which("unshare") and shutil.which("setpriv")):
        return False
    probe = subprocess.run([*SANDBOX, "true"], capture_output=True, timeout=30, check=False)
    return probe.returncode == 0


def test_the_sandbox_is_read_only_but_for_tmp(tmp_path: Path) -> None:
    if not _sandboxed():
        pytest.skip("needs root, unshare and setpriv (util-linux), and mount namespaces")
    here = Path(__file__).with_name("sandbox-probe")
    mine = tmp_path / "probe"
    cmd = [
        *SANDBOX,
        "sh",
        "-c",
        f'touch {mine} && ! touch {here} 2>/dev/null && test "$HOME" = /nonexistent',
    ]
    assert subprocess.run(cmd, timeout=30, check=False).returncode == 0
    assert mine.exists() and not here.exists()


def test_a_server_in_the_units_sandbox_serves_and_verifies(postgres: Postgres) -> None:
    if not _sandboxed():
        pytest.skip("needs root, unshare and setpriv (util-linux), and mount namespaces")
    options = unit_options("https://class.example.edu")
    server = start_server(postgres.new_database(), extra=options, wrap=SANDBOX)
    try:
        admin = {"Authorization": f"Bearer {server.token}"}
        made = httpx.post(server.base + "/api/admin/lecturers", json={"name": "Ada"}, headers=admin)
        assert made.status_code == 200, made.text
        lecturer = {"Authorization": f"Bearer {made.json()['token']}"}
        room = httpx.post(server.base + "/api/classes", json={"name": "Hall"}, headers=lecturer)
        assert room.status_code == 200, room.text
        assert room.json()["join"].startswith("https://class.example.edu/c/")
        server.base += f"/c/{room.json()['code']}"
        server.token = made.json()["token"]
        challenge = open_challenge(server)
        game = {"challenge": challenge["id"], "code": code(SEED, 1)}
        sent = httpx.post(server.base + "/api/submit", json=game, headers=join(server, "Ro"))
        assert sent.status_code == 200, sent.text
        board = httpx.get(server.base + "/api/leaderboard").json()["entries"]
        assert [entry["name"] for entry in board] == ["Ro"]
        server.proc.terminate()
        said = server.proc.stdout.read() if server.proc.stdout else ""
    finally:
        server.stop()
    banner_end = "Press Ctrl+C to stop the server."
    assert banner_end in said and not said.split(banner_end)[1].strip(), said
