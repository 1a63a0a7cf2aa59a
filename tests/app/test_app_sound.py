"""The desktop's sound (issue 48) under SDL's `disk` audio driver: the applet plays a game
in a child process whose mixer writes its output to a file; the raw samples read back hold
a tick where each atom left (at the pitch its energy gave), and silence when muted."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from evapcool.app.sound import RATE, approach_pitch, chord_wave, tick_pitch, tick_wave

#: The child: a knife game at a low trap; after each frame that ticked, it waits until the
#: mixer has written 0.25 s more (the file grows), so each tick stands alone in the file.
CHILD = textwrap.dedent(
    """
    import json, os, sys
    import pygame
    from evapcool.app.applet import App
    from evapcool.game.rules import Game, GameConfig
    out, muted = sys.argv[1], sys.argv[2] == "muted"
    app = App(Game(GameConfig(seed=4, escape="knife", n_atoms=49)), data_dir=sys.argv[3],
              config_dir=sys.argv[3], screen=(640, 672))
    sound = app.teaching.sound
    assert sound.available, "the disk driver gave no mixer"
    sound.muted = muted
    rate, fmt, channels = pygame.mixer.get_init()
    step = rate * channels * abs(fmt) // 8
    played = []
    sound.on_play = lambda name, pitch: played.append(
        (name, pitch, os.path.getsize(out) if os.path.exists(out) else 0))
    def settle(seconds):
        start = os.path.getsize(out) if os.path.exists(out) else 0
        for _ in range(200000):
            if os.path.exists(out) and os.path.getsize(out) >= start + seconds * step:
                return
            pygame.time.wait(5)
        raise SystemExit("the disk driver stopped writing")
    settle(0.3)
    app.game.paused = False
    ticks = 0
    for frame in range(900):
        app.game.set_trap_height(max(60.0, 330.0 - frame))  # a ramp: atoms leave now and then
        before = len(played)
        app.frame(None)
        if len(played) > before:
            ticks += any(name == "tick" for name, _, _ in played[before:])
            settle(0.6)  # the longest tone (0.4 s) is over: each frame's sounds stand alone
        if ticks >= 5:
            break
    settle(0.3)
    print(json.dumps({"rate": rate, "format": fmt, "channels": channels, "played": played}))
    app.close()
    """
)


def run_child(tmp_path, muted: bool) -> tuple[dict, np.ndarray]:
    out = tmp_path / ("muted.raw" if muted else "sound.raw")
    env = {
        **os.environ,
        "SDL_AUDIODRIVER": "disk",
        "SDL_DISKAUDIOFILE": str(out),
        "SDL_VIDEODRIVER": "dummy",
    }
    done = subprocess.run(
        [sys.executable, "-c", CHILD, str(out), "muted" if muted else "on", str(tmp_path)],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    info = json.loads(done.stdout.strip().splitlines()[-1])
    assert info["format"] == -16 and info["channels"] == 1, info
    return info, np.fromfile(out, dtype="<i2").astype(float)


def bursts(samples: np.ndarray, rate: int) -> list[tuple[int, int]]:
    """(start, end) sample of each sound separated from the next by 50 ms of silence."""
    loud = np.flatnonzero(np.abs(samples) > 200)
    if loud.size == 0:
        return []
    gaps = np.flatnonzero(np.diff(loud) > 0.05 * rate)
    starts = [loud[0], *loud[gaps + 1]]
    ends = [*loud[gaps], loud[-1]]
    return list(zip(starts, ends, strict=True))


def pitch_of(samples: np.ndarray, rate: int) -> float:
    spectrum = np.abs(np.fft.rfft(samples * np.hanning(len(samples)), n=1 << 16))
    return float(np.argmax(spectrum) * rate / (1 << 16))


def test_ticks_are_heard_where_atoms_left(tmp_path):
    info, samples = run_child(tmp_path, muted=False)
    rate = info["rate"]
    played = info["played"]
    assert sum(1 for name, _, _ in played if name == "tick") >= 5, played
    # Each frame that played something is one burst in the file, in order, where it played.
    frames_played = sorted({at for _, _, at in played})
    found = bursts(samples, rate)
    assert len(found) == len(frames_played), (found, frames_played)
    slack = 4 * 512 * 2  # the mixer's and the driver's buffers, bytes
    for (start, _), at in zip(found, frames_played, strict=True):
        assert at - slack <= 2 * start <= at + 2 * rate // 4
    # A frame with one tick alone sounds at that tick's pitch: its atom's energy.
    checked = 0
    for (start, end), at in zip(found, frames_played, strict=True):
        here = [(name, pitch) for name, pitch, a in played if a == at]
        if len(here) == 1 and here[0][0] == "tick":
            measured = pitch_of(samples[start : end + 1], rate)
            assert abs(measured - here[0][1]) < 0.05 * here[0][1], (measured, here)
            checked += 1
    assert checked >= 1


def test_muted_is_silence(tmp_path):
    info, samples = run_child(tmp_path, muted=True)
    assert info["played"] == []
    assert samples.size > RATE // 2  # the driver ran and wrote
    assert np.count_nonzero(samples) == 0


def test_pitch_follows_energy_and_the_approach_tone_rises():
    pitches = [tick_pitch(r) for r in (0.5, 1.0, 2.0, 3.0)]
    assert pitches == sorted(pitches) and len(set(pitches)) == 4
    assert approach_pitch(1.9) < approach_pitch(1.5) < approach_pitch(1.05)
    wave = tick_wave(tick_pitch(1.0)).astype(float)
    assert abs(pitch_of(wave, RATE) - tick_pitch(1.0)) < 0.05 * tick_pitch(1.0)
    assert chord_wave().size > RATE  # the chord lasts over a second


@pytest.mark.usefixtures("own_folders")
def test_m_mutes_and_unmutes_and_class_mode_starts_muted(make_app):
    import pygame
    from apphelp import key

    from evapcool.app.sound import Sound

    assert not Sound(True, 1.0, muted=True).audible  # what the applet makes in class mode

    app = make_app()
    sound = app.teaching.sound
    assert sound.available  # the tests' dummy audio driver
    assert sound.audible
    key(app, pygame.K_m)
    assert not sound.audible and app.visible_notices[-1] == "Sound muted"
    key(app, pygame.K_m)
    assert sound.audible


@pytest.mark.usefixtures("own_folders")
def test_the_win_sounds_a_chord_and_a_lost_game_a_falling_tone(make_app):
    from apphelp import frames

    won = make_app()
    won.game.paused = False
    won.game.sim.force_win()
    frames(won, 2)
    assert [name for name, _ in won.teaching.sound.log].count("chord") == 1
    lost = make_app(escape="knife")
    lost.game.paused = False
    frames(lost, 1)
    lost.game.set_trap_height(25.0)  # the knife takes nearly every atom: no condensing now
    frames(lost, 5)
    assert lost.game.too_few_atoms is not None
    names = [name for name, _ in lost.teaching.sound.log]
    assert names.count("falling") == 1 and "chord" not in names
    assert names.count("tick") >= 1


#: The child: the applet where SDL can open no audio device (a driver that does not exist),
#: a knife game that loses atoms, then key M.
NO_DEVICE_CHILD = textwrap.dedent(
    """
    import json, sys
    sys.path.insert(0, sys.argv[2])
    import pygame
    from apphelp import frames, key
    from evapcool.app.applet import App
    from evapcool.game.rules import Game, GameConfig
    app = App(Game(GameConfig(seed=4, escape="knife", n_atoms=49)), data_dir=sys.argv[1],
              config_dir=sys.argv[1], screen=(640, 672))
    sound = app.teaching.sound
    app.game.paused = False
    app.game.set_trap_height(60.0)
    frames(app, 60)
    key(app, pygame.K_m)
    print(json.dumps({"available": sound.available, "audible": sound.audible,
                      "played": sound.log, "escaped": 49 - app.game.sim.n_trapped,
                      "notice": app.visible_notices[-1]}))
    app.close()
    """
)


def test_no_audio_device_means_no_sound_and_m_says_why(tmp_path):
    env = {**os.environ, "SDL_AUDIODRIVER": "evapcool-none", "SDL_VIDEODRIVER": "dummy"}
    tests = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    done = subprocess.run(
        [sys.executable, "-c", NO_DEVICE_CHILD, str(tmp_path), tests],
        env=env,
        capture_output=True,
        text=True,
        timeout=300,
        check=False,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    info = json.loads(done.stdout.strip().splitlines()[-1])
    assert info["escaped"] > 0  # atoms left: a tick each, were there a device
    assert info["available"] is False and info["audible"] is False
    assert info["played"] == []
    assert info["notice"] == "No sound: no audio device was found."
