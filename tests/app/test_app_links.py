"""Setups as links on the desktop (issue 48): the page's options read and written, locks and
hidden parts honoured, one notice per bad option in the page's words; the run saved as a
lab CSV that the lab reads and plots; key D's sentence."""

from __future__ import annotations

import json
from pathlib import Path

import pygame
import pytest
from apphelp import frames, key

from evapcool.app import cli, links
from evapcool.app.applet import App
from evapcool.game.rules import Game, GameConfig
from evapcool.lab.experiment import load_result

ROOT = Path(__file__).resolve().parents[2]
SHARED = json.loads((ROOT / "web" / "src" / "link-options.json").read_text("utf-8"))["options"]

pytestmark = pytest.mark.usefixtures("own_folders")


def test_the_desktop_knows_the_pages_options_and_values():
    assert list(links.LINK_OPTIONS) == [o["name"] for o in SHARED]
    values = {o["name"]: o.get("values") for o in SHARED}
    assert list(links.LOCKABLE) == values["lock"]
    assert list(links.HIDEABLE) == values["hide"]
    trap = next(o for o in SHARED if o["name"] == "trap")
    assert (trap["low"], trap["high"]) == (25, 450)


def test_a_link_gives_its_setup():
    s = links.parse_link(
        "https://example.org/evapcool.html?atoms=100&escape=knife&trap=300&lock=trap,speed"
        "&hide=help,chart&theme=projector&seed=7&speed=2&tc-law=cup&sound=off"
    )
    assert s.notices == []
    assert (s.atoms, s.escape, s.trap, s.seed, s.speed, s.tc_law) == (
        100,
        "knife",
        300,
        7,
        2,
        "cup",
    )
    assert (s.lock, s.hide, s.theme, s.sound) == (
        ("trap", "speed"),
        ("help", "chart"),
        "projector",
        "off",
    )


def test_one_notice_per_bad_option_in_the_pages_words():
    s = links.parse_link("?atoms=0x20&trap=9000&lock=trap,nose&colour=red&seed=1&seed=2&theme=pink")
    assert s.atoms is None and s.trap is None and s.lock == () and s.theme is None
    assert len(s.notices) == 6, s.notices
    assert (
        'Address: atoms must be a whole number from 1 to 20000 (got "0x20"); ignored.' in s.notices
    )
    assert 'Address: trap must be a number from 25 to 450 px (got "9000"); ignored.' in s.notices
    assert any(
        n.startswith("Address: lock must be a list separated by commas of") for n in s.notices
    )
    assert any(n.startswith('Address: unknown option "colour"') for n in s.notices)
    assert "Address: seed is given 2 times; give it once. Ignored." in s.notices


def test_print_link_then_open_gives_the_same_setup(capsys, tmp_path):
    argv = [
        "--atoms",
        "60",
        "--escape",
        "knife",
        "--trap",
        "300",
        "--lock",
        "trap",
        "--hide",
        "help",
        "--seed",
        "7",
        "--theme",
        "projector",
        "--print-link",
    ]
    assert cli.main(argv) == 0
    link = capsys.readouterr().out.strip()
    assert link.startswith(links.PAGE_URL + "?")
    again = links.parse_link(link)
    assert again.notices == []
    assert (again.atoms, again.escape, again.trap, again.seed) == (60, "knife", 300, 7)
    assert (again.lock, again.hide, again.theme) == (("trap",), ("help",), "projector")
    shot = tmp_path / "shot.png"
    from evapcool.cli import main as top

    assert top(["open", link, "--frames", "2", "--screenshot", str(shot)]) == 0
    assert shot.is_file()


def test_bad_link_options_are_notices_in_the_window(capsys):
    status = cli.main(["--link", "?atoms=abc&trap=1", "--frames", "1"])
    assert status == 0  # refused options are ignored, as on the page


def make(tmp_path, **kw) -> App:
    config = kw.pop("config", {})
    return App(
        Game(GameConfig(seed=1, **config)),
        data_dir=tmp_path / "data",
        config_dir=tmp_path / "config",
        screen=(640, 672),
        **kw,
    )


def test_a_locked_trap_stays_and_says_so(tmp_path):
    app = make(tmp_path, lock=("trap", "speed"), config={"start_height": 300.0})
    try:
        assert app.game.trap_height == 300.0
        key(app, pygame.K_DOWN, times=3)
        key(app, pygame.K_PLUS)
        assert app.game.trap_height == 300.0 and app.game.speed == 1.0
        assert "The trap height is fixed by this setup's link." in app.visible_notices
        app.restart()
        assert app.game.trap_height == 300.0  # the link's start height at every start
    finally:
        app.close()


def test_locked_settings_rows_do_not_change(tmp_path):
    app = make(tmp_path, lock=("atoms",), overrides={"n_atoms": 30})
    try:
        key(app, pygame.K_o)
        key(app, pygame.K_RIGHT)
        assert app.options.draft.n_atoms == app.options.settings.n_atoms
        assert "This setting is fixed by this setup's link." in app.visible_notices
        key(app, pygame.K_DOWN)
        key(app, pygame.K_RIGHT)  # radius: free
        key(app, pygame.K_RETURN)
        assert app.options.for_run().n_atoms == 30
    finally:
        app.close()


def test_hidden_parts_are_gone(tmp_path):
    app = make(tmp_path, hide=("help", "restart", "chart"))
    try:
        keys = {k for b in app.bindings for k in b.keys}
        assert pygame.K_h not in keys and pygame.K_r not in keys and pygame.K_e not in keys
        assert app.controls.target_at((176, 624)) is None  # the restart button's place
        assert app.controls.target_at((548, 620)) is None  # the chart button's
        key(app, pygame.K_h)
        assert app.overlay is None
    finally:
        app.close()


def test_save_this_run_is_a_lab_csv_the_lab_reads_and_plots(tmp_path):
    app = make(tmp_path, config={"escape": "knife"})
    try:
        app.game.set_trap_height(150.0)
        app.game.paused = False
        frames(app, 95)
        at = int(app.game.sim.time)  # the key is handled before its frame's physics
        key(app, pygame.K_w)
        path = app.teaching.saved
        assert path is not None and path.parent == tmp_path / "data" / "runs"
        result = load_result(path)
        assert list(result.frame) == [0, 30, 60, 90, at]
        assert result.n_trapped[0] == 49 and result.escaped[-1] == 49 - result.n_trapped[-1] > 0
        assert result.trap_height[-1] == 150.0
        assert result.metadata["replay_code"].startswith("EC1.")
        assert result.parameters["escape"] == "knife"
        pytest.importorskip("matplotlib", reason="the lab's plot needs matplotlib (extra 'lab')")
        result.plot(tmp_path / "run.png")
        assert (tmp_path / "run.png").stat().st_size > 10_000
        pygame.key.set_mods(pygame.KMOD_LSHIFT)
        at = int(app.game.sim.time)
        key(app, pygame.K_w)
        pygame.key.set_mods(0)
        every = load_result(app.teaching.saved)
        assert list(every.frame) == list(range(at + 1))
    finally:
        app.close()


def test_the_save_button_saves(tmp_path):
    from apphelp import click

    app = make(tmp_path)
    try:
        lay = app.layout
        click(app, (round(lay.scene.x + 26 * lay.scale), round(lay.scene.y + 624 * lay.scale)))
        assert app.teaching.saved is not None and app.teaching.saved.is_file()
    finally:
        app.close()


def test_key_d_reads_the_scene(tmp_path):
    app = make(tmp_path, config={"escape": "knife"})
    try:
        key(app, pygame.K_d)
        line = app.visible_notices[-1]
        assert line.startswith("Atoms in the cup: 49; T ") and line.endswith("paused.")
        assert "trap height 400 px" in line
        app.game.set_trap_height(250.0)
        app.game.paused = False
        frames(app, 3)
        assert "atoms leaving" in app.teaching.describe(app.game)
    finally:
        app.close()
