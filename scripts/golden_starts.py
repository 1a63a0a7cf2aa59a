"""Golden starts and golden wins: what the shared start generator and the game's rules must
give in every edition (issue 22.1). The web edition's tests read them (web/test/start.test.ts).

    python scripts/golden_starts.py write    # web/test/golden/starts.json, wins.json, paths.json
    python scripts/golden_starts.py check    # the committed files still match (exit 1 if not)
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

from evapcool.fileio import atomic_write_text
from evapcool.game.path import game_path
from evapcool.game.replay import Recording, Settings, record_autopilot
from evapcool.physics.simulation import Simulation
from evapcool.physics.start import SEED_PORTABLE_MAX

GOLDEN_DIR = Path(__file__).resolve().parents[1] / "web" / "test" / "golden"
#: (atoms, radius, seed): the classic game, the seed's extremes, small and many atoms; seed 10
#: sends atom 1932's jitter and seed 7 atom 1927's direction to their fallback streams.
START_CASES = [
    (49, 12.0, 0),
    (49, 12.0, 1),
    (49, 12.0, 123456789),
    (49, 12.0, 2**32 + 5),
    (49, 12.0, SEED_PORTABLE_MAX),
    (1, 12.0, 9),
    (400, 4.0, 7),
    (2000, 2.0, 7),
    (2000, 2.0, 10),
]
#: (strategy, atoms, radius, escape, tc exponent, seed): games the autopilot won, replayed by
#: the page: the classic game, the knife, and the cup's Tc law (exponent 2/5).
WIN_CASES = [
    ("demo", 49, 12.0, "rim", 2.0 / 3.0, 1),
    ("demo", 49, 12.0, "knife", 2.0 / 3.0, 5),
    ("demo", 49, 12.0, "rim", 2.0 / 5.0, 99),
]


def starts() -> dict:
    cases = []
    for atoms, radius, seed in START_CASES:
        sim = Simulation(n_atoms=atoms, radius=radius, seed=seed, engine="reference")
        cases.append(
            {
                "atoms": atoms,
                "radius": radius,
                "seed": seed,
                "positions": sim.positions.ravel().tolist(),
                "velocities": sim.velocities.ravel().tolist(),
                "initial_temperature": sim.initial_temperature,
                "critical_temperature": sim.critical_temperature,
            }
        )
    return {"format": "evapcool-starts", "generator": 1, "cases": cases}


def wins() -> dict:
    cases = []
    for strategy, atoms, radius, escape, tc_exponent, seed in WIN_CASES:
        settings = Settings(n_atoms=atoms, radius=radius, escape=escape, tc_exponent=tc_exponent)
        rec = record_autopilot(strategy, settings, seed, engine="reference")
        cases.append(rec.to_json())
    return {"format": "evapcool-wins", "generator": 1, "recordings": cases}


def paths() -> dict:
    """The debrief's paths (issue 36) of the won games and of a lost one (a slow ramp)."""
    recordings = [Recording.from_json(doc) for doc in wins()["recordings"]]
    lost = Recording(Settings(n_atoms=49), 3, ((400.0, 30), (300.0, 500)), False, 0, 530)
    out = []
    for rec in [*recordings, lost]:
        out.append({"recording": rec.to_json(), "path": game_path(rec).to_json()})
    return {"format": "evapcool-paths", "generator": 1, "cases": out}


def texts() -> dict[str, str]:
    return {
        "starts.json": json.dumps(starts()) + "\n",
        "wins.json": json.dumps(wins()) + "\n",
        "paths.json": json.dumps(paths()) + "\n",
    }


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("action", choices=["write", "check"])
    args = parser.parse_args(argv)
    stale = []
    for name, text in texts().items():
        path = GOLDEN_DIR / name
        if args.action == "write":
            atomic_write_text(path, text)
            print(f"wrote {path}")
        elif not path.exists() or path.read_text(encoding="utf-8") != text:
            stale.append(name)
    if stale:
        names = ", ".join(stale)
        print(f"stale: {names} (run python scripts/golden_starts.py write)", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
