"""A private X server with a window manager for tests: Xvfb plus openbox.

`XServer(width, height)` starts Xvfb on a display number it picks and openbox on it;
`stop()` ends both (only the processes it started). Tests drive the applet in a
real window there (SDL_VIDEODRIVER=x11) and read window geometry with xdotool.
"""

from __future__ import annotations

import os
import select
import shutil
import subprocess
import time

NEEDED = ("Xvfb", "openbox", "xdotool", "xprop", "xmessage")


def missing_tools() -> list[str]:
    return [tool for tool in NEEDED if shutil.which(tool) is None]


def _start_xvfb(width: int, height: int, seconds: float = 15.0) -> tuple[subprocess.Popen, str]:
    """Xvfb on a display number it picks itself (-displayfd: no race with another test run
    taking the same free-looking number), once it accepts clients; (process, ":N")."""
    read, write = os.pipe()
    screen = f"{width}x{height}x24"
    try:
        xvfb = subprocess.Popen(
            ["Xvfb", "-displayfd", str(write), "-screen", "0", screen, "-nolisten", "tcp"],
            pass_fds=(write,),
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
    finally:
        os.close(write)
    with os.fdopen(read) as pipe:
        ready = select.select([pipe], [], [], seconds)[0]
        number = pipe.readline().strip() if ready else ""
    if not number.isdigit():
        xvfb.kill()
        xvfb.wait()
        raise RuntimeError("Xvfb did not start")
    return xvfb, f":{number}"


class XServer:
    """Xvfb with one screen of the given size, managed by openbox."""

    def __init__(self, width: int, height: int) -> None:
        self.size = (width, height)
        self._procs: list[subprocess.Popen] = []
        xvfb, self.display = _start_xvfb(width, height)
        self._procs.append(xvfb)
        for _ in range(3):
            wm = subprocess.Popen(
                ["openbox", "--sm-disable"],
                env=self.env(),
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            if self._wait(self._wm_running, wm) and self._wm_manages(wm):
                self._procs.append(wm)
                break
            wm.kill()
            wm.wait()
        else:
            self.stop()
            raise RuntimeError("openbox did not start")

    def env(self, **extra: str) -> dict[str, str]:
        return {**os.environ, "DISPLAY": self.display, **extra}

    def _wm_running(self) -> bool:
        out = subprocess.run(
            ["xprop", "-root", "_NET_SUPPORTING_WM_CHECK"],
            env=self.env(),
            capture_output=True,
            text=True,
        ).stdout
        return "window id" in out

    def _client_list(self) -> str:
        return subprocess.run(
            ["xprop", "-root", "_NET_CLIENT_LIST"], env=self.env(), capture_output=True, text=True
        ).stdout

    def _wm_manages(self, wm: subprocess.Popen, tries: int = 5) -> bool:
        """openbox names itself on the root window early in its start; a window mapped
        before its start is done may never be managed, and SDL then waits forever for it
        to appear. So a probe window (xmessage) must be managed, and gone again, first."""
        for _ in range(tries):
            probe = subprocess.Popen(
                ["xmessage", "-geometry", "+0+0", "window manager probe"],
                env=self.env(),
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
            )
            managed = self._wait(lambda: "0x" in self._client_list(), probe, 3.0)
            probe.terminate()
            probe.wait()
            if managed and self._wait(lambda: "0x" not in self._client_list(), wm):
                return True
            if wm.poll() is not None:
                return False
        return False

    @staticmethod
    def _wait(ready, proc: subprocess.Popen, seconds: float = 15.0) -> bool:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            if proc.poll() is not None:
                return False
            if ready():
                return True
            time.sleep(0.05)
        return False

    def xdotool(self, *args: str) -> str:
        return subprocess.run(
            ["xdotool", *args], env=self.env(), capture_output=True, text=True, check=True
        ).stdout

    def geometry(self, window_id: int) -> tuple[int, int, int, int]:
        """(x, y, width, height) of a window's client area on the screen, from xdotool."""
        out = self.xdotool("getwindowgeometry", str(window_id)).split()
        x, y = (int(v) for v in out[out.index("Position:") + 1].split(","))
        w, h = (int(v) for v in out[out.index("Geometry:") + 1].split("x"))
        return x, y, w, h

    def stop(self) -> None:
        for proc in reversed(self._procs):
            if proc.poll() is None:
                proc.terminate()
                try:
                    proc.wait(5)
                except subprocess.TimeoutExpired:
                    proc.kill()
                    proc.wait()
        self._procs.clear()
