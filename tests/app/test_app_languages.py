"""The applet in other languages (issue 23): --lang, the saved setting, the system locale,
the settings screen's Language row, English behind a missing key, and real windows in
German and Arabic under Xvfb whose screenshots the docs show (docs/languages.md)."""

from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np
import pygame
import pytest
from apphelp import key
from xserver import XServer, missing_tools

from evapcool import i18n
from evapcool.app.applet import App
from evapcool.app.cli import main
from evapcool.app.words import choose
from evapcool.game.rules import Game, GameConfig
from evapcool.view.scene import PLAY_RECT

DOCS = Path(__file__).resolve().parents[2] / "docs"


def _run(tmp_path: Path, *args: str) -> int:
    folders = ["--data-dir", str(tmp_path / "d"), "--config-dir", str(tmp_path / "c")]
    return main([*folders, "--frames", "1", *args])


def test_lang_picks_the_language(tmp_path, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    assert _run(tmp_path, "--lang", "de-AT") == 0
    assert i18n.active().locale == "de"
    assert i18n.number(2.5) == "2,5" and i18n.t("settings.title") == "Einstellungen"


def test_a_bad_lang_is_one_line_naming_the_allowed_tags(tmp_path, capsys):
    with pytest.raises(SystemExit) as stop:
        _run(tmp_path, "--lang", "xx")
    assert stop.value.code == 2
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "--lang" in err and "pt-BR" in err and "'xx'" in err


def test_the_saved_setting_then_the_system(tmp_path, monkeypatch):
    monkeypatch.setenv("SDL_VIDEODRIVER", "dummy")
    (tmp_path / "c").mkdir()
    (tmp_path / "c" / "settings.json").write_text(json.dumps({"version": 1, "language": "fr"}))
    monkeypatch.setenv("LANGUAGE", "ja")
    assert _run(tmp_path) == 0
    assert i18n.active().locale == "fr"  # the saved setting beats the system
    assert _run(tmp_path, "--lang", "ko") == 0
    assert i18n.active().locale == "ko"  # --lang beats the saved setting
    (tmp_path / "c" / "settings.json").write_text(json.dumps({"version": 1}))
    assert _run(tmp_path) == 0
    assert i18n.active().locale == "ja"  # "auto": the system's language


def test_the_settings_screen_changes_and_saves_the_language(make_app, tmp_path):
    app = make_app()
    key(app, pygame.K_o)
    key(app, pygame.K_DOWN, 4)  # atoms, radius, Tc law, escape rule, language
    assert app.options.rows()[4] == ("Language", "as the system")
    key(app, pygame.K_RIGHT)  # after "auto": ar
    key(app, pygame.K_RETURN)
    assert i18n.active().locale == "ar" and i18n.is_rtl()
    saved = json.loads(next(tmp_path.rglob("settings.json")).read_text())
    assert saved["language"] == "ar"
    app.frame()
    assert app.window.win.title == i18n.Catalog("ar").t("app.title")
    assert app.help_rows()[0][0] == "المسافة"  # Space, in Arabic


def test_a_missing_key_falls_back_to_english_and_is_reported():
    catalog = i18n.Catalog("de")
    del catalog.messages["win.condensed"]
    i18n.missing_keys.clear()
    assert catalog.t("win.condensed") == "The gas has condensed!"
    assert i18n.missing_keys == {"de": {"win.condensed"}}
    i18n.missing_keys.clear()


# -- real windows (Xvfb + openbox), the screenshots of docs/languages.md ---------------------


@pytest.fixture(scope="module")
def screen():
    missing = missing_tools()
    if missing:
        pytest.skip(f"needs {', '.join(missing)} for a real window manager (apt install them)")
    server = XServer(1024, 768)
    yield server
    server.stop()


def _panel_title(app: App) -> np.ndarray:
    """The help panel's title strip, as drawn in the window."""
    app.frame(1 / 60)
    lay = app.layout
    top = lay.scene.top + round((PLAY_RECT.top + 40) * lay.scale)
    strip = pygame.Rect(lay.scene.left, top, lay.scene.width, round(40 * lay.scale))
    return pygame.surfarray.array3d(app.window.surface.subsurface(strip)).copy()


@pytest.mark.own_process(timeout=120)
@pytest.mark.usefixtures("own_folders")
@pytest.mark.parametrize("tag", ["de", "ar"])
def test_a_real_window_speaks_the_language(screen, monkeypatch, tmp_path, tag):
    pygame.display.quit()
    monkeypatch.setenv("SDL_VIDEODRIVER", "x11")
    monkeypatch.setenv("DISPLAY", screen.display)
    choose(tag)
    app = App(Game(GameConfig(seed=1)), data_dir=tmp_path / "d", config_dir=tmp_path / "c")
    try:
        for _ in range(20):
            app.frame(1 / 60)
        key(app, pygame.K_e)  # the energy chart beside the scene
        key(app, pygame.K_h)  # the help overlay
        for _ in range(60):
            app.frame(1 / 60)
        assert app.window.win.title == i18n.t("app.title") != "Evaporation cooling"
        # The docs' pictures are written only when asked (EVAPCOOL_DOCS_SHOTS=1): a test run
        # leaves the checkout as it was.
        shots = DOCS if os.environ.get("EVAPCOOL_DOCS_SHOTS") == "1" else tmp_path
        pygame.image.save(app.window.surface, str(shots / f"desktop-{tag}.png"))
        translated = _panel_title(app)
        i18n.use("en")
        english = _panel_title(app)
        assert (translated != english).any()  # the help's title is not the English one
    finally:
        app.close()
