"""`evapcool` command line: headless frames + screenshot, and one-line errors (exit 2)."""

from __future__ import annotations

import os
import subprocess
import sys

import pygame
import pytest

from evapcool.app.cli import main

pytestmark = pytest.mark.usefixtures("own_folders")


def run(args: list[str], capsys) -> tuple[int, str, str]:
    try:
        rc = main(args)
    except SystemExit as exc:
        rc = exc.code
    out, err = capsys.readouterr()
    return rc, out, err


def test_frames_and_screenshot_write_the_window(tmp_path, capsys):
    path = tmp_path / "shot.png"
    rc, _, err = run(
        ["--frames", "10", "--seed", "3", "--speed", "2", "--screenshot", str(path)], capsys
    )
    assert (rc, err) == (0, "")
    img = pygame.image.load(str(path))
    assert img.get_size() == (640, 672)
    assert img.get_at((20, 300))[:3] == (79, 79, 79)


def test_options_reach_the_game(tmp_path, monkeypatch, capsys):
    seen = {}
    from evapcool.app import applet

    real = applet.App.run_frames

    def spy(self, n):
        real(self, n)
        seen.update(
            atoms=self.game.sim.n_atoms,
            speed=self.game.speed,
            time=self.game.sim.time,
            radius=float(self.game.sim.radii[0]),
            fullscreen=self.fullscreen,
        )

    monkeypatch.setattr(applet.App, "run_frames", spy)
    rc, _, err = run(
        [
            "--atoms",
            "30",
            "--radius",
            "8",
            "--seed",
            "2",
            "--speed",
            "0.5",
            "--frames",
            "4",
            "--fullscreen",
        ],
        capsys,
    )
    assert (rc, err) == (0, "")
    assert seen == {"atoms": 30, "speed": 0.5, "time": 2.0, "radius": 8.0, "fullscreen": True}


@pytest.mark.parametrize(
    ("args", "names"),
    [
        (["--atoms", "-3"], "--atoms"),
        (["--atoms", "abc"], "--atoms"),
        (["--atoms", "100000"], "--atoms"),  # does not fit in the cup (Simulation's ValueError)
        (["--radius", "nan"], "--radius"),
        (["--radius", "0"], "--radius"),
        (["--radius", "300"], "--radius"),
        (["--seed", "-1"], "--seed"),
        (["--speed", "5"], "--speed"),
        (["--speed", "inf"], "--speed"),
        (["--frames", "-1"], "--frames"),
        (["--frames", "2.5"], "--frames"),
        (["--frames", "1", "--screenshot", "shot.jpg"], "--screenshot"),
        (["--frames", "1", "--screenshot", "/no/such/folder/shot.png"], "--screenshot"),
        (["--screenshot", "shot.png"], "--screenshot"),
        (["--bogus"], "--bogus"),
    ],
)
def test_bad_input_is_one_line_naming_the_parameter_exit_2(args, names, capsys):
    rc, out, err = run(args, capsys)
    assert rc == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert names in lines[0] and lines[0].startswith("evapcool: ")
    assert "Traceback" not in err and out == ""


def test_bad_input_through_the_real_command_has_no_traceback():
    env = dict(os.environ, SDL_VIDEODRIVER="dummy", SDL_AUDIODRIVER="dummy")
    proc = subprocess.run(
        [sys.executable, "-m", "evapcool", "--radius", "-2"],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert proc.returncode == 2
    assert proc.stderr.strip().count("\n") == 0 and "--radius" in proc.stderr
    assert proc.stdout == ""


def test_zero_frames_still_draws_the_start(tmp_path, capsys):
    path = tmp_path / "start.png"
    rc, _, err = run(["--frames", "0", "--seed", "1", "--screenshot", str(path)], capsys)
    assert (rc, err) == (0, "")
    img = pygame.image.load(str(path))
    assert img.get_at((296, 546))[:3] == (0, 0, 0)  # the cup is there
    assert img.get_at((20, 300))[:3] == (79, 79, 79)


def test_no_display_is_one_line_with_the_headless_way_exit_2(monkeypatch, capsys):
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    monkeypatch.delenv("SDL_VIDEODRIVER", raising=False)
    monkeypatch.setattr(sys, "platform", "linux")
    rc, out, err = run(["--seed", "1"], capsys)
    assert rc == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "no display" in lines[0]
    assert "--frames N --screenshot" in lines[0]


def test_no_display_through_the_real_command_exits_at_once():
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.pop("SDL_VIDEODRIVER", None)
    proc = subprocess.run(
        [sys.executable, "-m", "evapcool"], capture_output=True, text=True, env=env, timeout=60
    )
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.count("\n") == 1 and "no display" in proc.stderr


def test_frames_and_screenshot_keep_working_without_a_display(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env.pop("SDL_VIDEODRIVER", None)
    path = tmp_path / "shot.png"
    proc = subprocess.run(
        [sys.executable, "-m", "evapcool", "--frames", "3", "--screenshot", str(path)],
        capture_output=True,
        text=True,
        env=env,
        timeout=120,
    )
    assert (proc.returncode, proc.stderr) == (0, "")
    assert pygame.image.load(str(path)).get_size() == (640, 672)


def test_a_dummy_video_driver_without_frames_is_refused(monkeypatch, capsys):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    monkeypatch.setenv("DISPLAY", ":0")
    rc, _, err = run([], capsys)
    assert rc == 2 and "SDL_VIDEODRIVER=dummy" in err and "--frames N" in err
