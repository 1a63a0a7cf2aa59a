"""Settings in the applet: the overlay, saving, restart, bad files and command-line overrides."""

from __future__ import annotations

import json

import numpy as np
import pygame
import pytest
from apphelp import NOTICE_STRIP, key

from evapcool import i18n
from evapcool.app import applet
from evapcool.app.cli import main
from evapcool.game.settings import max_atoms
from evapcool.physics.simulation import TC_EXPONENT_CUP, TC_EXPONENT_SEED
from evapcool.view.screen import BORDER_TOP, ScreenMap


@pytest.fixture
def dirs(tmp_path, monkeypatch):
    data, config = tmp_path / "data", tmp_path / "config"
    # The command line reads these; the App below gets them as arguments.
    monkeypatch.setenv("EVAPCOOL_DATA_DIR", str(data))
    monkeypatch.setenv("EVAPCOOL_CONFIG_DIR", str(config))
    return data, config


def saved(config) -> dict:
    return json.loads((config / "settings.json").read_text(encoding="utf-8"))


def notice_pixels(app) -> int:
    px = pygame.surfarray.array3d(app.window.surface).astype(int)
    box = px[NOTICE_STRIP.left : NOTICE_STRIP.right, NOTICE_STRIP.top : NOTICE_STRIP.bottom]
    return int(np.count_nonzero((box[..., 0] > 90) & (box[..., 1] < 60) & (box[..., 2] < 60)))


def test_settings_round_trip_through_the_overlay_and_restart(make_app, dirs):
    app = make_app()
    config = dirs[1]
    key(app, pygame.K_o)
    assert app.overlay == "settings"
    key(app, pygame.K_LEFT, 6)  # atoms 49 -> 44 -> 39 -> 34 -> 29 -> 24 -> 19
    key(app, pygame.K_RIGHT, 3)  # -> 20 -> 25 -> 30
    key(app, pygame.K_DOWN)
    key(app, pygame.K_LEFT, 2)  # radius 12 -> 10
    key(app, pygame.K_DOWN)
    key(app, pygame.K_RIGHT)  # Tc law: seed -> cup
    key(app, pygame.K_DOWN)
    key(app, pygame.K_RIGHT)  # escape: rim -> knife
    key(app, pygame.K_SPACE)  # the overlay has the keys: no pause toggle, no trap change
    assert app.game.paused and app.game.trap_height == 400.0
    assert not (config / "settings.json").exists()  # nothing saved before closing
    key(app, pygame.K_RETURN)
    assert app.overlay is None
    file = saved(config)
    assert (file["n_atoms"], file["radius"], file["tc_law"], file["escape"]) == (
        30,
        10.0,
        "cup",
        "knife",
    )
    assert app.game.sim.n_atoms == 49  # Restart applies them
    key(app, pygame.K_r)
    sim = app.game.sim
    assert (sim.n_atoms, float(sim.radii[0]), sim.escape_rule) == (30, 10.0, "knife")
    assert sim.tc_exponent == pytest.approx(TC_EXPONENT_CUP)

    # A new session starts from the saved settings.
    again = make_app()
    key(again, pygame.K_r)
    assert (again.game.sim.n_atoms, again.game.sim.escape_rule) == (30, "knife")

    # Esc leaves the overlay without saving.
    key(again, pygame.K_o)
    key(again, pygame.K_RIGHT, 3)
    key(again, pygame.K_ESCAPE)
    assert again.overlay is None and again.running and saved(config)["n_atoms"] == 30


def test_a_bad_value_in_the_file_falls_back_with_a_visible_notice(make_app, dirs):
    config = dirs[1]
    config.mkdir()
    (config / "settings.json").write_text(
        json.dumps({"n_atoms": "lots", "radius": 12, "tc_law": "cup", "escape": "knife"}),
        encoding="utf-8",
    )
    app = make_app()
    app.frame(None)
    assert app.options.settings.n_atoms == 49 and app.options.settings.tc_law == "cup"
    assert any("n_atoms" in n and "default" in n for n in app.visible_notices)
    assert notice_pixels(app) > 2000
    key(app, pygame.K_r)
    assert app.game.sim.n_atoms == 49 and app.game.sim.escape_rule == "knife"


def _spy(monkeypatch) -> dict:
    seen: dict = {}
    real = applet.App.run_frames

    def spy(self, n):
        real(self, n)
        self.restart()  # overrides hold for the whole run, restarts included
        sim = self.game.sim
        seen.update(
            atoms=sim.n_atoms,
            radius=float(sim.radii[0]),
            p=sim.tc_exponent,
            escape=sim.escape_rule,
        )

    monkeypatch.setattr(applet.App, "run_frames", spy)
    return seen


def test_command_line_flags_override_for_one_run_without_saving(dirs, monkeypatch, capsys):
    config = dirs[1]
    config.mkdir()
    text = json.dumps({"n_atoms": 30, "radius": 10.0, "tc_law": "seed", "escape": "rim"})
    (config / "settings.json").write_text(text, encoding="utf-8")
    seen = _spy(monkeypatch)
    args = ["--atoms", "20", "--tc-law", "cup", "--escape", "knife", "--frames", "2"]
    assert main(args) == 0
    assert seen == {"atoms": 20, "radius": 10.0, "p": TC_EXPONENT_CUP, "escape": "knife"}
    assert (config / "settings.json").read_text(encoding="utf-8") == text
    assert main(["--frames", "1"]) == 0  # without flags: the saved settings
    assert seen == {"atoms": 30, "radius": 10.0, "p": TC_EXPONENT_SEED, "escape": "rim"}
    assert capsys.readouterr().err == ""


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--tc-law", "box"], "--tc-law"),
        (["--escape", "wall"], "--escape"),
        (["--radius", "25"], "--radius"),
        (["--atoms", "5000"], "--atoms"),
        (["--atoms", "200", "--radius", "20"], "--atoms"),
    ],
)
def test_bad_command_line_values_exit_2_with_one_line(dirs, args, option, capsys):
    try:
        rc = main([*args, "--frames", "1"])
    except SystemExit as exc:
        rc = exc.code
    out, err = capsys.readouterr()
    assert rc == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("evapcool: ") and option in lines[0], err
    assert not (dirs[1] / "settings.json").exists()


@pytest.mark.parametrize("radius_presses", [8, -9])  # radius 20 px, and 3 px
def test_the_overlay_caps_the_atoms_so_every_start_fits_below_the_rim(
    make_app, dirs, radius_presses
):
    """Issue 14, item 7: the most atoms the overlay allows all start in the cup, in view."""
    app = make_app()
    key(app, pygame.K_o)
    key(app, pygame.K_DOWN)
    k = pygame.K_RIGHT if radius_presses > 0 else pygame.K_LEFT
    key(app, k, abs(radius_presses))
    key(app, pygame.K_UP)
    key(app, pygame.K_RIGHT, 40)  # more than any cap allows
    draft = app.options.draft
    cap = max_atoms(draft.radius)
    assert draft.n_atoms == cap
    shown = i18n.number(cap)  # grouped the language's way: 1,234
    assert f"(1 to {shown})" in dict(app.options.rows())["Number of atoms"]
    assert any(f"At most {shown} atoms" in line for line in app.options.footer())
    key(app, pygame.K_RETURN)
    key(app, pygame.K_r)
    sim = app.game.sim
    assert sim.n_trapped == cap
    tops = sim.positions[:, 1] + float(sim.radii[0])
    assert tops.max() <= sim.trap_height  # no atom above the rim...
    screen_tops = ScreenMap.of(sim).to_screen(sim.positions)[:, 1] - float(sim.radii[0])
    assert screen_tops.min() >= BORDER_TOP  # ...or under the top border
    assert np.abs(sim.positions[:, 0]).max() < sim.rim_half_width
