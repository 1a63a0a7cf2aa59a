"""Checks a lean install (the wheel without extras): the applet runs, and each optional
feature says in one line which extra to install, with exit status 2 and no traceback.

Run with the venv's python after `pip install evapcool-*.whl` (no extras): .ci/wheel_suite.sh.
"""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
import tempfile
from importlib import metadata
from pathlib import Path

EVAPCOOL = [sys.executable, "-m", "evapcool"]


def run(*args: str, status: int) -> str:
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
    done = subprocess.run([*EVAPCOOL, *args], capture_output=True, text=True, env=env)
    assert "Traceback" not in done.stderr, done.stderr
    assert done.returncode == status, (args, done.returncode, done.stdout, done.stderr)
    return done.stderr


def one_line(err: str, extra: str) -> None:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and f"pip install 'evapcool[{extra}]'" in lines[0], err


def main() -> None:
    for heavy in ("matplotlib", "pandas", "dask", "optuna"):
        assert importlib.util.find_spec(heavy) is None, f"{heavy} came with the lean install"
    version = metadata.version("evapcool")
    out = subprocess.run([*EVAPCOOL, "--version"], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == f"evapcool {version}", out.stdout
    with tempfile.TemporaryDirectory() as tmp:
        t = Path(tmp)
        shot = t / "shot.png"
        folders = ["--data-dir", str(t / "data"), "--config-dir", str(t / "config")]
        run("--frames", "30", "--screenshot", str(shot), *folders, status=0)
        assert shot.stat().st_size > 1000
        one_line(run("lab", "--frames", "5", "--plot", str(t / "p.png"), status=2), "lab")
        # The wheel carries the compiled core: thousands of atoms need nothing more.
        assert importlib.util.find_spec("evapcool.physics._core") is not None, "no core"
        csv = t / "run.csv"
        err = run(
            "lab", "--atoms", "500", "--radius", "2", "--frames", "1", "--engine", "fast",
            "--out", str(csv), status=0,
        )  # fmt: skip
        assert "note" not in err, err
        assert csv.exists()
        page = subprocess.run([*EVAPCOOL, "web", "--print-path"], capture_output=True, text=True)
        assert Path(page.stdout.strip()).is_file(), page
    print(f"lean install of evapcool {version}: applet, version, core, extras' messages all right")


if __name__ == "__main__":
    main()
