"""The fast engine's first start: a progress bar in the window while a worker compiles."""

from __future__ import annotations

import sys
import time
import types

import numpy as np
import pygame
import pytest
from apphelp import fake_fast_engine

import evapcool.physics
from evapcool.app import applet, warmup
from evapcool.app.applet import App, StartCancelledError
from evapcool.game.rules import GameConfig
from evapcool.view.scene import MERCURY

pytestmark = pytest.mark.usefixtures("own_folders")


def _filled(app: App, bar: pygame.Rect) -> float:
    """Share of the bar's inside that is red, read off the window's pixels."""
    px = pygame.surfarray.array3d(app.window.surface).astype(int)
    row = px[bar.left + 4 : bar.right - 4, bar.centery]
    red = np.all(row == np.array(MERCURY), axis=-1)
    return float(red.mean())


def _watch(monkeypatch) -> list[tuple[float, str, float | None]]:
    """Record (red share on screen, what, builder's fraction) at every progress frame."""
    seen = []
    real = App.draw_progress

    def spy(self, what, fraction, elapsed):
        bar = real(self, what, fraction, elapsed)
        seen.append((_filled(self, bar), what, fraction))
        return bar

    monkeypatch.setattr(App, "draw_progress", spy)
    return seen


def test_the_first_start_shows_a_bar_that_fills_with_each_step(monkeypatch, tmp_path):
    fake_fast_engine(monkeypatch, steps=5, seconds=0.12)
    seen = _watch(monkeypatch)
    app = App(GameConfig(seed=1), data_dir=tmp_path, config_dir=tmp_path, screen=(1920, 1080))
    try:
        assert app.running and app.game.sim.n_atoms == 49
        assert len(seen) >= 5
        shares = [s for s, _, _ in seen]
        assert shares == sorted(shares)  # it only fills
        for share, _, fraction in seen:
            if fraction is not None:
                assert share == pytest.approx(fraction, abs=0.02)
        whats = {w for _, w, _ in seen}
        # The engine's step names are a programmer's: the player reads the catalog's words.
        assert {
            "Compiling the fast engine: step 2 of 6",
            "Compiling the fast engine: step 4 of 6",
        } <= whats
        assert shares[-1] >= 0.6
        assert warmup.needs_warmup(GameConfig()) is True  # the stand-in never built a fast engine
    finally:
        app.close()


def test_without_prepare_the_bar_moves_and_says_it_compiles(monkeypatch, tmp_path):
    fake_fast_engine(monkeypatch)
    bare = types.ModuleType("evapcool.physics.fast")  # an engine without prepare()
    monkeypatch.setitem(sys.modules, "evapcool.physics.fast", bare)
    monkeypatch.setattr(evapcool.physics, "fast", bare, raising=False)
    real = warmup.make_simulation

    def slow(config):
        time.sleep(0.6)
        return real(config)

    monkeypatch.setattr(warmup, "make_simulation", slow)
    frames: list[np.ndarray] = []
    real_draw = App.draw_progress

    def spy(self, what, fraction, elapsed):
        bar = real_draw(self, what, fraction, elapsed)
        px = pygame.surfarray.array3d(self.window.surface)[bar.left : bar.right, bar.centery]
        frames.append((np.all(px == np.array(MERCURY), axis=-1), what, fraction))
        return bar

    monkeypatch.setattr(App, "draw_progress", spy)
    app = App(GameConfig(seed=1), data_dir=tmp_path, config_dir=tmp_path, screen=(1920, 1080))
    app.close()
    assert len(frames) >= 5
    assert all(what == "Compiling the fast engine" and f is None for _, what, f in frames)
    starts = {int(np.argmax(red)) for red, _, _ in frames}
    assert len(starts) > 2  # a block sliding along the bar: busy, share unknown


def test_closing_the_window_while_it_compiles_ends_the_start(monkeypatch, tmp_path):
    fake_fast_engine(monkeypatch, steps=20, seconds=0.1)
    real = App.draw_progress

    def close_soon(self, what, fraction, elapsed):
        if elapsed > 0.3:
            pygame.event.post(pygame.event.Event(pygame.QUIT))
        return real(self, what, fraction, elapsed)

    monkeypatch.setattr(App, "draw_progress", close_soon)
    t0 = time.monotonic()
    with pytest.raises(StartCancelledError):
        App(GameConfig(seed=1), data_dir=tmp_path, config_dir=tmp_path, screen=(1920, 1080))
    assert time.monotonic() - t0 < 1.5  # did not wait for the 2 s of compiling


def test_a_restart_that_needs_the_engine_shows_the_bar_too(make_app, monkeypatch):
    app = make_app()
    fake_fast_engine(monkeypatch, steps=3, seconds=0.1)
    seen = _watch(monkeypatch)
    app.restart()
    assert seen and app.game.sim.time == 0.0 and app.running


def test_a_quick_build_shows_no_progress_screen(make_app, monkeypatch):
    app = make_app()
    seen = _watch(monkeypatch)
    monkeypatch.setattr(applet.warmup, "needs_warmup", lambda config: False)
    app.restart()
    assert seen == []
