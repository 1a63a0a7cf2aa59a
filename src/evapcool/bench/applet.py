"""Applet frame time: headless (SDL dummy driver), and in a real window when there is a display.

Headless figures are the applet's own cost (physics, drawing into memory); the real
window adds presenting to the screen. `evapcool bench` prints both when a display is
there (DISPLAY or WAYLAND_DISPLAY on Linux; always on Windows and macOS).
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time

import numpy as np

#: Budget for a 60 FPS display: 16.7 ms per frame; we aim well below.
TARGET_MEDIAN_MS = 4.0
#: With the energy and path charts open beside the scene.
TARGET_PANELS_MEDIAN_MS = 8.0
#: `evapcool --atoms 10000 --radius 1`: 30 frames per second or better.
TARGET_BIG_FPS = 30.0
#: The layout the figures are taken at: a screen where scene and charts fit at scale 1.
BENCH_SCREEN = (1920, 1080)
#: Languages the open help is timed in: Latin alone, and the two with fallback fonts that
#: cost the most to lay out (Japanese: no spaces to wrap at; Arabic: shaped right to left).
HELP_LANGUAGES = ("en", "ja", "ar")


def _video(driver: str | None) -> None:
    """Use this SDL video driver from the next display start (None: SDL's choice)."""
    import pygame

    pygame.display.quit()
    if driver is None:
        os.environ.pop("SDL_VIDEODRIVER", None)
    else:
        os.environ["SDL_VIDEODRIVER"] = driver


def display_available() -> bool:
    """Whether a real window can open here (the applet's own check)."""
    from evapcool.app.cli import _no_display

    return _no_display() is None


def measure(
    frames: int,
    repeats: int,
    seed: int = 1,
    panels: bool = False,
    window: bool = False,
    **config: float,
) -> dict[str, np.ndarray]:
    """Per-frame times (s) of physics, drawing (+ present) and both, from fresh starts.

    panels: open both charts (they record every frame, counted with the physics).
    window: in a real window, frames on the wall clock as the applet plays them (each
    advances elapsed x 30 physics frames); else headless, one physics frame each.
    config: GameConfig fields other than the seed (n_atoms, radius).
    """
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    saved = os.environ.get("SDL_VIDEODRIVER")
    _video(None if window else "dummy")
    import pygame

    from evapcool.app.applet import App
    from evapcool.game.rules import Game, GameConfig

    out: dict[str, list[float]] = {"physics": [], "drawing": [], "total": [], "cpu": []}
    try:
        with tempfile.TemporaryDirectory() as tmp:  # never the user's scores or settings
            for r in range(repeats):
                game = Game(GameConfig(seed=seed + r, **config))
                app = App(game, data_dir=tmp, config_dir=tmp, screen=BENCH_SCREEN)
                if panels:
                    app.toggle_chart("energy")
                    app.toggle_chart("path")
                _time_frames(app, pygame, frames, window, out)
                app.close()
    finally:
        _video(saved)
    return {k: np.array(v) for k, v in out.items()}


def measure_help(language: str, frames: int, window: bool = False) -> dict[str, np.ndarray]:
    """Drawing time (s) of each frame with the help open in this language, wall clock and
    the process's CPU time (presenting not counted), the game playing: the help's
    frame-rate line changes every frame."""
    os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
    saved = os.environ.get("SDL_VIDEODRIVER")
    _video(None if window else "dummy")
    import pygame

    from evapcool import i18n
    from evapcool.app.applet import App
    from evapcool.game.rules import Game, GameConfig

    out: dict[str, list[float]] = {"drawing": [], "cpu": []}
    was = i18n.active().locale
    try:
        i18n.use(language)
        with tempfile.TemporaryDirectory() as tmp:
            app = App(Game(GameConfig(seed=1)), data_dir=tmp, config_dir=tmp, screen=BENCH_SCREEN)
            help_key = {"key": pygame.K_h, "mod": 0, "unicode": "h", "scancode": 0}
            pygame.event.post(pygame.event.Event(pygame.KEYDOWN, **help_key))
            app.game.paused = False
            for k in range(frames + 10):
                app.handle_events(pygame.event.get())
                app.advance(None)
                c0, t0 = time.process_time(), time.perf_counter()
                app.draw()
                if k >= 10:  # the first frames fit the help and fill the caches
                    out["drawing"].append(time.perf_counter() - t0)
                    out["cpu"].append(time.process_time() - c0)
                app.present()  # not counted: the same with the help open or closed
            app.close()
    finally:
        i18n.use(was)
        _video(saved)
    return {k: np.array(v) for k, v in out.items()}


def _time_frames(app, pygame, frames: int, window: bool, out: dict[str, list[float]]) -> None:
    app.game.paused = False
    last = time.perf_counter()
    for k in range(frames + 10):
        c0 = time.process_time()
        t0 = time.perf_counter()
        app.handle_events(pygame.event.get())
        app.advance(t0 - last if window else None)
        last = t0
        t1 = time.perf_counter()
        app.draw()
        app.present()
        t2 = time.perf_counter()
        c2 = time.process_time()
        if k >= 10:  # the first frames warm caches (sprites, fonts, text, chart axes)
            out["physics"].append(t1 - t0)
            out["drawing"].append(t2 - t1)
            out["total"].append(t2 - t0)
            out["cpu"].append(c2 - c0)


def _print_times(t: dict[str, np.ndarray], names: tuple[str, ...]) -> None:
    """One line per part: median and 95th percentile in ms."""
    for name in names:
        ms = t[name] * 1e3
        print(f"  {name:8s} median {np.median(ms):6.2f} ms   p95 {np.percentile(ms, 95):6.2f} ms")


def _fps_line(t: dict[str, np.ndarray]) -> float:
    fps = 1.0 / float(np.median(t["total"]))
    verdict = "meets" if fps >= TARGET_BIG_FPS else "MISSES"
    print(f"  {fps:.1f} frames per second (median) {verdict} the target of >= {TARGET_BIG_FPS:g}")
    return fps


def run(args: argparse.Namespace) -> None:
    """Print the applet's frame time, median and 95th percentile."""
    quick = bool(getattr(args, "quick", False))
    frames, repeats = (150, 2) if quick else (300, 5)
    for panels, target, what in (
        (False, TARGET_MEDIAN_MS, "scene only"),
        (True, TARGET_PANELS_MEDIAN_MS, "energy and path charts open"),
    ):
        t = measure(frames, repeats, panels=panels)
        n = len(t["total"])
        print(f"[applet] frame time at the classic start (49 atoms, headless, {what}), {n} frames:")
        # cpu: the process's CPU time per frame; unlike the wall clock it does not count
        # time the scheduler gave to other programs (a shared machine's noise).
        _print_times(t, ("physics", "drawing", "total", "cpu"))
        med = float(np.median(t["total"]) * 1e3)
        verdict = "meets" if med < target else "MISSES"
        print(f"  total median {med:.2f} ms {verdict} the target of < {target:g} ms")
    n = 60 if quick else 300
    for language in HELP_LANGUAGES:
        t = measure_help(language, n)
        print(f"[applet] the help open in {language} (headless, drawing only), {n} frames:")
        _print_times(t, ("drawing", "cpu"))
    # 10 000 atoms of radius 1 (the fast engine, chosen automatically), from the
    # densest phase at the start; one run, the engine's compiled code loaded first.
    big = {"n_atoms": 10_000, "radius": 1.0}
    t = measure(60 if quick else 150, 1, **big)
    n = len(t["total"])
    print(f"[applet] frame time with 10 000 atoms (R = 1, headless, scene only), {n} frames:")
    _print_times(t, ("physics", "drawing", "total"))
    _fps_line(t)
    if not display_available():
        print("[applet] real window: skipped, no display (set DISPLAY, or run under Xvfb)")
        return
    where = os.environ.get("WAYLAND_DISPLAY") or os.environ.get("DISPLAY") or "the desktop"
    for config, what in (({}, "classic start, 49 atoms"), (big, "10 000 atoms, R = 1")):
        t = measure(60 if quick else 200, 1, window=True, **config)
        n = len(t["total"])
        print(f"[applet] real window on {where}, {what}, played on the wall clock, {n} frames:")
        _print_times(t, ("physics", "drawing", "total"))
        _fps_line(t)
