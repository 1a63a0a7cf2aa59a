"""Write web/test/cases/refusals.json: out-of-range states and parameters with the exact
refusal of the Python edition, which the web edition must give word for word (issue 25.1).

    python scripts/refusals.py           # (re)write the fixture
    python scripts/refusals.py --check   # exit 1 if it is stale

tests/web/test_refusals.py checks the fixture against Python; web/test/refusals.test.ts
feeds every case to the TypeScript Simulation and demands a RangeError with that message.
Values are not whole numbers where Python would print an int and JavaScript cannot tell.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path
from typing import Any

from fixture_cli import fixture_main

from evapcool import Simulation
from evapcool.physics.state import to_state

FIXTURE = Path(__file__).resolve().parents[1] / "web" / "test" / "cases" / "refusals.json"


def _atoms(positions: list[list[float]], velocities: list[list[float]]) -> dict[str, Any]:
    """A valid state of these atoms (radius 12, H = 400), without its optional energy sum."""
    sim = Simulation(
        n_atoms=len(positions), positions=positions, velocities=velocities, engine="reference"
    )
    state = to_state(sim)
    del state["energy_sum"], state["initial_temperature"]
    return state


def _with(state: dict[str, Any], **fields: Any) -> dict[str, Any]:
    out = json.loads(json.dumps(state))
    for key, value in fields.items():
        if key.startswith("atom_"):
            field, index = key[5:].rsplit("_", 1)
            out["atoms"][field][int(index)] = value
        else:
            out[key] = value
    return out


def state_cases() -> list[tuple[str, dict[str, Any]]]:
    one = _atoms([[0.0, 50.0]], [[1.0, 0.5]])
    two = _atoms([[-30.0, 60.0], [30.0, 60.0]], [[1.0, 0.0], [-1.0, 0.0]])
    classic = to_state(Simulation.classic(seed=3, engine="reference"))
    del classic["energy_sum"], classic["initial_temperature"]
    return [
        ("an atom at 120.5 px/frame", _with(one, atom_vx_0=120.5)),
        ("a hot atom among 49", _with(classic, atom_vy_17=-101.25)),
        ("an atom 2e8 px above the cup", _with(one, atom_y_0=2.5e8)),
        ("curvature above its range", _with(one, curvature=20.5)),
        ("gravity above its range", _with(one, gravity=50.5)),
        ("gravity below its range", _with(one, gravity=0.00025)),
        ("tc exponent above its range", _with(one, tc_exponent=11.5)),
        ("a radius above its range", _with(one, atoms={**one["atoms"], "radius": [2000.5]})),
        ("a mass above its range", _with(one, atoms={**one["atoms"], "mass": [1000.5]})),
        ("a mass below its range", _with(one, atoms={**one["atoms"], "mass": [0.0005]})),
        ("an atom outside the cup", _with(one, atom_x_0=100.5, atom_y_0=10.5)),
        ("two atoms overlapping", _with(two, atom_x_1=-25.5)),
    ]


#: (case, Python keyword, TypeScript option, value)
PARAMETER_CASES: list[tuple[str, str, str, Any]] = [
    ("no atoms", "n_atoms", "nAtoms", 0),
    ("two million atoms", "n_atoms", "nAtoms", 2_000_000),
    ("a radius too small", "radius", "radius", 0.005),
    ("a radius too large", "radius", "radius", 1000.5),
    ("a mass too large", "mass", "mass", 2000.5),
    ("a curvature too small", "curvature", "curvature", 0.0000015),
    ("gravity too strong", "gravity", "gravity", 10.5),
    ("a tc exponent too large", "tc_exponent", "tcExponent", 10.5),
    ("a negative trap height", "trap_height", "trapHeight", -3.5),
]


def _refusal(make: Any) -> str:
    try:
        make()
    except ValueError as e:
        return str(e)
    raise AssertionError("the Python edition accepted a case meant to be refused")


def fixture() -> dict[str, Any]:
    states = [
        {
            "case": name,
            "state": state,
            "message": _refusal(lambda s=state: Simulation.from_state(s)),
        }
        for name, state in state_cases()
    ]
    parameters = []
    for name, python, web, value in PARAMETER_CASES:
        message = _refusal(lambda p=python, v=value: Simulation(**{p: v}, engine="reference"))
        assert message.startswith(python + " "), message
        parameters.append(
            {
                "case": name,
                "python": python,
                "web": web,
                "value": value,
                "refusal": message[len(python) :],
            }
        )
    return {
        "generated_by": "scripts/refusals.py from the Python edition: do not edit",
        "states": states,
        "parameters": parameters,
    }


def fixture_text() -> str:
    return json.dumps(fixture(), indent=1) + "\n"


def main(argv: list[str] | None = None) -> int:
    return fixture_main(__doc__, __file__, FIXTURE, fixture_text, argv)


if __name__ == "__main__":
    sys.exit(main())
