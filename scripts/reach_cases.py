"""Write web/test/cases/reach.json: states near the reach rule's thresholds, each with the
rim asked for and the answer of the reference engine's readable rule (issue 47), which the
page's core (core_out_of_reach in WebAssembly) must give.

    python scripts/reach_cases.py           # (re)write the fixture
    python scripts/reach_cases.py --check   # exit 1 if it is stale

tests/physics/test_core_reach.py builds its random states with `reach_state` and checks the
fixture fresh; web/test/reach.test.ts feeds every case to the TypeScript Simulation.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path
from typing import Any

import numpy as np
from fixture_cli import fixture_main

from evapcool import Simulation
from evapcool.game.rules import HEIGHT_MIN
from evapcool.physics.model import REACH_NAMES
from evapcool.physics.portable import power

FIXTURE = Path(__file__).resolve().parents[1] / "web" / "test" / "cases" / "reach.json"
#: The threshold a state's energy is put near: m g H_min, m g H, or (any energy) T near Tc.
AIMS = ("escape", "trap", "tc")
#: How near: ties to the last bit, a hair either side, well either side.
SCALES = (1.0, 1.0 - 1e-12, 1.0 + 1e-12, 1.0 - 1e-6, 1.0 + 1e-6, 0.9, 1.1, 0.5, 2.0)
#: Small atoms, so that a few lie below m g H_min together.
GRAVITY, CURVATURE, RADIUS, TC_EXPONENT = 10.0 / 30.0, 0.01, 3.0, 2.0 / 3.0


def reach_state(
    masses: list[float],
    n_gone: int,
    aim: str,
    scale: float,
    tc_scale: float,
    height: float,
    win: bool = True,
    won: bool = False,
    radius: float = RADIUS,
) -> dict[str, Any]:
    """A state of len(masses) trapped atoms in a row at the cup's bottom (and n_gone gone),
    their energy E put at scale x the aim's threshold for the rim `height` asked for (at rest
    if it is lower than where they sit), and T0 so that T = E / N is tc_scale x Tc(N)."""
    n = len(masses)
    x = (np.arange(n) - (n - 1) / 2.0) * 2.2 * radius
    y = CURVATURE * x * x + 0.05
    m = np.array(masses)
    lightest = float(m.min()) if n else 1.0
    potential = float(np.sum(m * GRAVITY * y))
    target = {"escape": HEIGHT_MIN, "trap": height, "tc": 3.0 * HEIGHT_MIN}[aim]
    kinetic = lightest * GRAVITY * target * scale - potential
    v = math.sqrt(2.0 * kinetic / float(np.sum(m))) if kinetic > 0.0 and n else 0.0
    angle = np.linspace(0.3, 2.8, n) if n > 1 else np.full(n, 1.0)
    vx, vy = v * np.cos(angle), v * np.sin(angle)
    energy = potential + float(np.sum(0.5 * m * v * v))
    n0 = n + n_gone
    # Tc(N) = 0.75 T0 (N / N0)^p: T0 for T = tc_scale Tc(N) (and T0 = 1 for an empty cup).
    t0 = energy / n / (0.75 * power(n / n0, TC_EXPONENT)) / tc_scale if n else 1.0
    gone = n_gone * [0.0]
    return {
        "format": "evapcool-state",
        "version": 1,
        "trap_height": 450.0,
        "win": win,
        "won": won,
        "initial_temperature": t0,
        "atoms": {
            "x": [*x.tolist(), *gone],
            "y": [*y.tolist(), *(n_gone * [-600.0])],
            "vx": [*vx.tolist(), *gone],
            "vy": [*vy.tolist(), *gone],
            "radius": radius,
            "mass": [*masses, *(n_gone * [1.0])],
            "status": [*(n * ["trapped"]), *(n_gone * ["gone"])],
        },
    }


def tie(energy: float, m: float, g: float) -> float | None:
    """A rim H with m g H == E to the last bit, if one lies within a few ulps of E / (m g)."""
    h = energy / (m * g)
    for _ in range(8):
        if m * g * h == energy:
            return h
        h = math.nextafter(h, math.inf if m * g * h < energy else -math.inf)
    return None


def tie_case(masses: list[float]) -> dict[str, Any]:
    """Atoms above Tc whose E is m g H to the last bit for the rim H asked for: stuck here."""
    state = reach_state(masses, 10, "trap", 1.0, 1.5, 80.0)
    sim = Simulation.from_state(state, engine="reference")
    h = tie(sim.total_energy(), float(sim.masses.min()), sim.gravity)
    assert h is not None, masses
    return {"case": f"E = m g H to the last bit, {len(masses)} atoms", "state": state, "height": h}


def answer(state: dict[str, Any], height: float) -> int:
    """The reference engine's readable rule (the oracle) on that state."""
    sim = Simulation.from_state(state, engine="reference")
    return sim.out_of_reach(HEIGHT_MIN, height)


def cases() -> list[dict[str, Any]]:
    """Every aim at every scale, the Tc tie near or far, from a seeded generator; then the
    games won or without the win rule, and an empty cup."""
    rng = np.random.default_rng(47)
    out = []
    for aim in AIMS:
        for scale in SCALES:
            n = int(rng.integers(1, 7)) if aim != "tc" else int(rng.integers(2, 7))
            masses = rng.uniform(0.8, 1.6, n).round(3).tolist()
            tc_scale = float(rng.choice([1.0, 1.0 - 1e-12, 1.0 + 1e-12, 1.1, 1.5]))
            if aim == "tc":
                tc_scale = scale
            height = round(float(rng.uniform(HEIGHT_MIN, 120.0)), 2)
            state = reach_state(masses, int(rng.integers(0, 40)), aim, scale, tc_scale, height)
            out.append({"case": f"{aim} x {scale!r}", "state": state, "height": height})
    hot = reach_state([1.0, 2.0], 20, "escape", 0.5, 1.5, 100.0)
    many = [(n, rng.uniform(0.8, 1.6, n).round(3).tolist()) for n in (12, 40, 200)]
    out += [
        {"case": "won", "state": {**hot, "won": True}, "height": 100.0},
        {"case": "no win rule", "state": {**hot, "win": False}, "height": 100.0},
        {"case": "stuck", "state": hot, "height": 100.0},
        {"case": "empty cup", "state": reach_state([], 49, "tc", 1.0, 1.0, 60.0), "height": 60.0},
        *(
            {
                "case": f"{n} atoms, T at Tc x {tc!r}",
                "state": reach_state(masses, 9, "tc", 1.0, tc, 450.0, radius=0.5),
                "height": 450.0,
            }
            for n, masses in many
            for tc in (1.0, 1.0 - 1e-15, 1.0 + 1e-15)
        ),
    ]
    out += [tie_case([1.0, 1.25]), tie_case([1.5, 1.1, 1.3])]
    for c in out:
        c["code"] = answer(c["state"], c["height"])
        c["reason"] = REACH_NAMES[c["code"]]
    return out


def fixture_text() -> str:
    head = "scripts/reach_cases.py from the reference engine's readable rule: do not edit"
    lines = ",\n".join(json.dumps(c) for c in cases())  # a case a line
    return f'{{"generated_by": "{head}", "lowest": {HEIGHT_MIN!r}, "cases": [\n{lines}\n]}}\n'


def main(argv: list[str] | None = None) -> int:
    return fixture_main(__doc__, __file__, FIXTURE, fixture_text, argv)


if __name__ == "__main__":
    sys.exit(main())
