"""What the game sounds like (issue 48): tones synthesized with NumPy, played by pygame's mixer.

Each atom that leaves gives a short tick whose pitch follows its energy; the gas cooling
towards Tc a slow rising tone; the condensate a major chord; a lost game a falling glide.
No sound files. Off where there is no audio device (the mixer does not start), muted by
key M or the settings; class mode starts muted (a room of laptops ticking at once).
"""

from __future__ import annotations

from collections.abc import Callable
from functools import lru_cache

import numpy as np
import pygame

RATE = 22050
#: A tick's pitch from its atom's energy: E / T0 from 0 to 4 spans these, Hz.
TICK_LOW, TICK_HIGH = 420.0, 1680.0
TICK_SECONDS = 0.035
#: The approach tone sounds while T is within this factor of Tc, once a second of play.
APPROACH_FROM = 2.0
APPROACH_EVERY = 30  # frames
#: Ticks heard in one frame at most (a knife lowered at once drops hundreds).
TICKS_PER_FRAME = 3
#: Closing waits at most this many 10 ms steps for the sounds playing to end.
CLOSE_WAIT_STEPS = 150


def _envelope(n: int, attack: int, release: float) -> np.ndarray:
    env = np.exp(-np.arange(n) / (release * RATE))
    env[:attack] *= np.linspace(0.0, 1.0, attack)
    return env


def _pcm(wave: np.ndarray) -> np.ndarray:
    return (np.clip(wave, -1.0, 1.0) * 32000).astype(np.int16)


@lru_cache(maxsize=64)
def tick_wave(pitch: float) -> np.ndarray:
    """A short decaying sine burst at pitch Hz (16-bit mono)."""
    n = int(TICK_SECONDS * RATE)
    t = np.arange(n) / RATE
    return _pcm(0.7 * np.sin(2 * np.pi * pitch * t) * _envelope(n, 40, TICK_SECONDS / 4))


@lru_cache(maxsize=16)
def approach_wave(pitch: float) -> np.ndarray:
    """A soft 0.4 s tone gliding a little up from pitch."""
    n = int(0.4 * RATE)
    t = np.arange(n) / RATE
    phase = 2 * np.pi * (pitch * t + 0.5 * pitch * 0.06 * t * t / 0.4)
    env = np.sin(np.pi * np.arange(n) / n)
    return _pcm(0.25 * np.sin(phase) * env)


@lru_cache(maxsize=1)
def chord_wave() -> np.ndarray:
    """The condensate: a C major chord, 1.4 s."""
    n = int(1.4 * RATE)
    t = np.arange(n) / RATE
    wave = sum(np.sin(2 * np.pi * f * t) for f in (523.25, 659.25, 783.99))
    return _pcm(0.22 * wave * _envelope(n, 200, 0.6))


@lru_cache(maxsize=1)
def falling_wave() -> np.ndarray:
    """A lost game: a glide from 600 Hz down to 150 Hz, 1.2 s."""
    n = int(1.2 * RATE)
    t = np.arange(n) / RATE
    freq = 600.0 * (150.0 / 600.0) ** (t / 1.2)
    phase = 2 * np.pi * np.cumsum(freq) / RATE
    return _pcm(0.4 * np.sin(phase) * _envelope(n, 200, 0.7))


def tick_pitch(energy_ratio: float) -> float:
    """The tick's pitch for an atom that left with E = energy_ratio x T0 (clipped)."""
    f = min(1.0, max(0.0, energy_ratio / 4.0))
    return round(TICK_LOW * (TICK_HIGH / TICK_LOW) ** f, 1)


def approach_pitch(t_over_tc: float) -> float:
    """The approach tone rises as T/Tc falls from 2 to 1: 220 Hz to 440 Hz."""
    f = min(1.0, max(0.0, (APPROACH_FROM - t_over_tc) / (APPROACH_FROM - 1.0)))
    return round(220.0 * 2.0**f, 1)


class Sound:
    """The mixer, if there is one, and what the game asks it to play."""

    def __init__(
        self, enabled: bool, volume: float, muted: bool = False, device: bool = True
    ) -> None:
        """enabled: the setting; volume 0 to 1; muted: this run only (class mode, key M);
        device: whether to look for an audio device at all (not in a headless run)."""
        self.available = device and _start_mixer()
        self.enabled = enabled
        #: Key M turned the sound on for this run although the setting says off.
        self.forced = False
        self.muted = muted
        self.volume = volume
        #: What was played, (name, pitch), for tests and the describe line.
        self.log: list[tuple[str, float]] = []
        self.on_play: Callable[[str, float], None] | None = None
        self._cache: dict[tuple[str, float], pygame.mixer.Sound] = {}

    @property
    def audible(self) -> bool:
        on = self.enabled or self.forced
        return self.available and on and not self.muted and self.volume > 0

    def toggle_mute(self) -> bool:
        """Key M: mute or unmute this run; returns whether it is now heard."""
        if not (self.enabled or self.forced):  # the setting said off: on for this run
            self.forced, self.muted = True, False
        else:
            self.muted = not self.muted
        if self.muted and self.available:
            pygame.mixer.stop()
        return self.audible

    def _play(self, name: str, pitch: float, wave: Callable[[], np.ndarray]) -> None:
        if not self.audible:
            return
        key = (name, pitch)
        sound = self._cache.get(key)
        if sound is None:
            if len(self._cache) > 128:
                self._cache.clear()
            sound = self._cache[key] = pygame.mixer.Sound(buffer=wave().tobytes())
        sound.set_volume(self.volume)
        sound.play()
        self.log.append(key)
        if self.on_play is not None:
            self.on_play(name, pitch)

    def ticks(self, energy_ratios: np.ndarray) -> None:
        """Atoms that left this frame, their energies over T0 (the loudest few heard)."""
        for ratio in sorted(energy_ratios.tolist(), reverse=True)[:TICKS_PER_FRAME]:
            pitch = tick_pitch(ratio)
            self._play("tick", pitch, lambda p=pitch: tick_wave(p))

    def approach(self, t_over_tc: float) -> None:
        pitch = approach_pitch(t_over_tc)
        self._play("approach", pitch, lambda: approach_wave(pitch))

    def condensed(self) -> None:
        self._play("chord", 0.0, chord_wave)

    def lost(self) -> None:
        self._play("falling", 0.0, falling_wave)

    def close(self) -> None:
        """Let what is playing end (a chord at the win, the ticks of a headless run), then
        stop the mixer."""
        if self.available:
            for _ in range(CLOSE_WAIT_STEPS):
                if not pygame.mixer.get_busy():
                    break
                pygame.time.wait(10)
            pygame.mixer.quit()
            self.available = False


def _start_mixer() -> bool:
    """Start the mixer as 16-bit mono at RATE; False where there is no audio device."""
    try:
        pygame.mixer.init(frequency=RATE, size=-16, channels=1, buffer=512)
    except pygame.error:
        return False
    init = pygame.mixer.get_init()
    if init is None:
        return False
    if init[0] != RATE or init[2] != 1:  # another program's mixer settings: ours
        pygame.mixer.quit()
        try:
            pygame.mixer.init(frequency=RATE, size=-16, channels=1, buffer=512, allowedchanges=0)
        except pygame.error:
            return False
    return True
