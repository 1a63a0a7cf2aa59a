"""The shared start generator (issue 22.1): the same atoms from the same seed in every edition.

Random numbers come from a counter-based hash (MurmurHash3's 32-bit finalizer, applied to
the seed, a stream number and a counter), so the k-th number of a stream needs no state and
NumPy computes a million of them at once while the core computes them one by one, with
the same bits. Everything that turns them into a start uses only + - * / and sqrt, which
IEEE 754 rounds exactly in every language; `core/start.c` is the twin both editions run
(this module is its readable oracle and the fallback without the compiled core), and the
golden starts in `web/test/golden/starts.json` hold both to it.
"""

from __future__ import annotations

import secrets

import numpy as np

#: Which generator built a start from a seed (recorded in replays): this module's.
START_GENERATOR = 1
#: Largest seed: the largest whole number a double (the page's number) holds exactly;
#: limits.SEED is this range.
SEED_PORTABLE_MAX = 2**53 - 1
#: Streams: each use of random numbers has its own, so changing one never shifts another.
STREAM_JITTER = 1
STREAM_SPEED = 2
STREAM_DIRECTION = 3
#: Candidates drawn per atom for a point in the unit disk (accepted with chance pi/4 or
#: 15 pi/64); the rare atom whose candidates all miss goes on in its own fallback stream.
CANDIDATES = 8
FALLBACK = 16
_CHUNK = 1 << 15  # atoms per NumPy block (memory: about 1 MB a block)
_M32 = np.uint64(0xFFFFFFFF)


def _fmix32(h: np.ndarray) -> np.ndarray:
    """MurmurHash3's finalizer: a bijection of 32-bit words that mixes every bit (uint64 in)."""
    h = h ^ (h >> np.uint64(16))
    h = (h * np.uint64(0x85EBCA6B)) & _M32
    h = h ^ (h >> np.uint64(13))
    h = (h * np.uint64(0xC2B2AE35)) & _M32
    mixed: np.ndarray = h ^ (h >> np.uint64(16))
    return mixed


def stream_keys(seed: int, stream: int) -> tuple[int, int]:
    """The two 32-bit keys of a (seed, stream) pair; a seed has 64 bits (low, high word)."""
    lo, hi = seed & 0xFFFFFFFF, (seed >> 32) & 0xFFFFFFFF
    salt = (0x9E3779B9 * stream) & 0xFFFFFFFF
    key_a = int(_fmix32(np.array([lo ^ salt], dtype=np.uint64))[0])
    key_b = int(_fmix32(np.array([hi ^ key_a ^ 0x5BD1E995], dtype=np.uint64))[0])
    return key_a, key_b


def words(seed: int, stream: int, counters: np.ndarray) -> np.ndarray:
    """The 32-bit words at these counters (each below 2^32) of a stream, as uint64."""
    key_a, key_b = stream_keys(seed, stream)
    c = counters.astype(np.uint64)
    return _fmix32(_fmix32(c ^ np.uint64(key_a)) ^ np.uint64(key_b))


def uniforms(seed: int, stream: int, indices: np.ndarray) -> np.ndarray:
    """Doubles in [0, 1), the k-th from words 2k and 2k + 1 (27 + 26 bits)."""
    k = indices.astype(np.uint64) * np.uint64(2)
    hi = words(seed, stream, k) >> np.uint64(5)
    lo = words(seed, stream, k + np.uint64(1)) >> np.uint64(6)
    out: np.ndarray = (hi.astype(np.float64) * 67108864.0 + lo.astype(np.float64)) / (
        9007199254740992.0
    )
    return out


def _candidates(seed: int, stream: int, first: int, count: int, per: int) -> np.ndarray:
    """Points in the square [-1, 1)^2: `per` candidates for each of `count` atoms from `first`."""
    base = np.arange(first * per, (first + count) * per, dtype=np.uint64) * np.uint64(2)
    x = 2.0 * uniforms(seed, stream, base) - 1.0
    y = 2.0 * uniforms(seed, stream, base + np.uint64(1)) - 1.0
    return np.stack((x.reshape(count, per), y.reshape(count, per)), axis=-1)


def disk_points(seed: int, stream: int, n: int, inner: float = 0.0) -> np.ndarray:
    """For each of n atoms, its first candidate (x, y) with inner <= x^2 + y^2 < 1."""
    out = np.empty((n, 2))
    for first in range(0, n, _CHUNK):
        count = min(_CHUNK, n - first)
        cand = _candidates(seed, stream, first, count, CANDIDATES)
        s = cand[..., 0] * cand[..., 0] + cand[..., 1] * cand[..., 1]
        ok = (s >= inner) & (s < 1.0)
        pick = np.argmax(ok, axis=1)
        out[first : first + count] = cand[np.arange(count), pick]
        for i in np.flatnonzero(~ok.any(axis=1)):
            out[first + i] = _fallback_point(seed, stream, first + int(i), inner)
    return out


def _fallback_point(seed: int, stream: int, atom: int, inner: float) -> tuple[float, float]:
    """The atom's first accepted candidate of its fallback stream (chance < 1e-5 an atom)."""
    cand = _candidates(seed, stream + 16 * FALLBACK, atom, 1, FALLBACK)[0]
    for x, y in cand:
        s = x * x + y * y
        if inner <= s < 1.0:
            return float(x), float(y)
    raise RuntimeError(f"no point in the disk for atom {atom} (seed {seed}): impossible odds")


def random_seed() -> int:
    """A fresh seed a browser can replay too (at most SEED_PORTABLE_MAX)."""
    return secrets.randbelow(SEED_PORTABLE_MAX + 1)
