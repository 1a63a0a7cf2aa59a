"""Fuzzing every command's options and the Python API (issue 18).

Every case runs in a worker process (tests/fuzzworker.py) under a time limit and must
end in a clean refusal that names the parameter (exit 2 with one line; ValueError or
TypeError) or in a finite, bounded run whose peak memory stays under 1 GB. The options
are read from the commands' own parsers, so a new subcommand is fuzzed as it appears
(those without a known short run are fuzzed up to parsing: '--help' ends their argv).

CI runs a few derandomized cases per test; a long local run:
    nice python -m pytest tests/test_fuzz.py --hypothesis-profile=fuzz
(the 'fuzz' profile is registered in conftest.py).
"""

from __future__ import annotations

import argparse
import base64
import importlib
import json
import math
import os
import pickle
import queue
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, event, given, settings
from hypothesis import strategies as st

from evapcool import limits
from evapcool.cli import SUBCOMMANDS
from evapcool.lab.experiment import LabConfig, run_experiment
from evapcool.physics.room import Room
from evapcool.physics.state import room_of_window

#: A case whose worker spends more CPU time than this (s) is a hang; the worker is killed.
#: CPU time, not the clock's: on a loaded machine a niced worker may wait far longer.
CASE_SECONDS = 120.0
#: ...and a case still running after this long on the clock is one too.
CASE_WALL_SECONDS = 20 * CASE_SECONDS
#: Peak memory of the worker, MB: any accepted input below 100 000 atoms stays under it.
MEMORY_MB = 1000.0
#: Cases per test unless a profile asks for at least the 'fuzz' profile's number.
SMALL_BUDGET = 10
WORKER = Path(__file__).with_name("fuzzworker.py")


def _budget() -> int:
    """The loaded profile's cases if it is the 'fuzz' one, else SMALL_BUDGET."""
    current, fuzz = settings.default, settings.get_profile("fuzz")
    return current.max_examples if current == fuzz else SMALL_BUDGET


FUZZ = settings(
    max_examples=_budget(),
    deadline=None,
    suppress_health_check=list(HealthCheck),
)


# -- the worker ----------------------------------------------------------------------------
class Worker:
    """A long-lived python running cases; killed and restarted when one runs over time."""

    def __init__(self, workdir: Path) -> None:
        self.workdir = workdir
        self.proc: subprocess.Popen | None = None
        self.lines: queue.Queue[str] = queue.Queue()
        self.cases = 0

    def _start(self) -> None:
        env = dict(os.environ)
        env.update(
            SDL_VIDEODRIVER="dummy",
            SDL_AUDIODRIVER="dummy",
            PYGAME_HIDE_SUPPORT_PROMPT="1",
            EVAPCOOL_DATA_DIR=str(self.workdir / "home-data"),
            EVAPCOOL_CONFIG_DIR=str(self.workdir / "home-config"),
        )
        env.pop("DISPLAY", None)
        env.pop("WAYLAND_DISPLAY", None)
        self.proc = subprocess.Popen(
            [sys.executable, str(WORKER), str(self.workdir)],
            stdin=subprocess.PIPE,
            stdout=subprocess.PIPE,
            stderr=subprocess.DEVNULL,
            text=True,
            env=env,
        )
        self.lines = queue.Queue()
        threading.Thread(target=self._read, args=(self.proc, self.lines), daemon=True).start()
        ready = self.lines.get(timeout=600)  # imports, and the fast engine's compile
        assert json.loads(ready) == {"ready": True}

    @staticmethod
    def _read(proc: subprocess.Popen, lines: queue.Queue) -> None:
        for line in proc.stdout:
            lines.put(line)
        lines.put("")

    def run(self, case: dict) -> dict:
        if self.proc is None or self.proc.poll() is not None:
            self._start()
        self.proc.stdin.write(base64.b64encode(pickle.dumps(case)).decode() + "\n")
        self.proc.stdin.flush()
        line = self._answer(case)
        if not line:
            self.stop()
            raise AssertionError(f"the worker died (a crash or the memory killer): {case!r}")
        self.cases += 1
        answer = json.loads(line)
        assert "crash" not in answer, f"{case!r}\n{answer['crash']}"
        assert answer["rss_mb"] < MEMORY_MB, f"peak memory {answer['rss_mb']:.0f} MB: {case!r}"
        return answer

    def _answer(self, case: dict) -> str:
        """The worker's answer line; AssertionError if the case runs over its time."""
        start, cpu0 = time.monotonic(), _cpu_seconds(self.proc.pid)
        while True:
            try:
                return self.lines.get(timeout=2.0)
            except queue.Empty:
                wall = time.monotonic() - start
                cpu = _cpu_seconds(self.proc.pid)
                used = wall if cpu is None or cpu0 is None else cpu - cpu0
                if used > CASE_SECONDS or wall > CASE_WALL_SECONDS:
                    self.stop()
                    raise AssertionError(
                        f"case ran over {CASE_SECONDS:g} s ({used:.0f} s of CPU, "
                        f"{wall:.0f} s on the clock: a hang): {case!r}"
                    ) from None

    def stop(self) -> None:
        if self.proc is not None:
            self.proc.kill()
            self.proc.wait()
            self.proc = None


def _cpu_seconds(pid: int) -> float | None:
    """CPU time (user + system) of a running process on Linux, else None."""
    try:
        fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    except (OSError, IndexError):
        return None
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


DEEP = "[" * 100_000 + "]" * 100_000


def _workdir(root: Path) -> Path:
    """Files and folders the cases may name: good, damaged and strange ones."""
    good = run_experiment(n_atoms=5, frames=2, seed=1)
    good.save(root / "good.json")
    good.save(root / "good.csv")
    doc = json.loads((root / "good.json").read_text())
    doc["metadata"]["parameters"]["gravity"] = 1e300
    (root / "badparams.json").write_text(json.dumps(doc))
    texts = {
        "list.json": "[]",
        "deep.json": DEEP,
        "short.csv": "# evapcool lab results\n" + ",".join(doc["columns"]) + "\n1,2\n",
        "empty.csv": "",
        "binary.json": "\udcff",
        "afile": "not a folder",
    }
    for name, text in texts.items():
        (root / name).write_bytes(text.encode("utf-8", "surrogateescape"))
    for folder in ("outdir", "taken.csv", "dirx.json", "cfg-good", "cfg-deep", "cfg-fifo"):
        (root / folder).mkdir()
    (root / "cfg-good" / "settings.json").write_text('{"n_atoms": 30, "radius": 5}')
    (root / "data-deep").mkdir()
    (root / "data-deep" / "highscores.json").write_text(DEEP)
    (root / "cfg-deep" / "settings.json").write_text(DEEP)
    if hasattr(os, "mkfifo"):
        os.mkfifo(root / "fifo.json")
        os.mkfifo(root / "fifo.csv")
        os.mkfifo(root / "cfg-fifo" / "settings.json")
    return root


@pytest.fixture(scope="module")
def worker(tmp_path_factory):
    w = Worker(_workdir(tmp_path_factory.mktemp("fuzz")))
    yield w
    w.stop()
    print(f"\nfuzz: {w.cases} cases run")


# -- values ----------------------------------------------------------------------------------
JUNK = st.one_of(
    st.sampled_from(
        [
            *("", "-", "--", "nan", "NaN", "inf", "-inf", "1e309", "0x10", " 7", "7 ", "1_0"),
            *("3.", "٣", "None", "[]", "{}", "-0", "+5", "1" * 5000, "9" * 30, "1e-400", "é"),
        ]
    ),
    st.text(max_size=8),
)
EDGES = [0, -1, 1, 2.5, 1e308, -1e308, 5e-324, 1e-300, 1e300, 2**63, 2**64, 10**12, 10**30]
SPECIAL = [math.nan, math.inf, -math.inf]
#: Work sizes: valid values are drawn small (the run must be short); large ones come
#: only beyond the range (they must be refused at once).
WORK = {"n_atoms": 60, "frames": 8, "every": 20}


def _edges(rng: limits.Range, cap: float | None) -> list[float]:
    out = [*EDGES, *SPECIAL, rng.low, math.nextafter(rng.low, -math.inf)]
    if math.isfinite(rng.high):
        out.append(math.nextafter(rng.high, math.inf) if not rng.integer else rng.high + 1)
        if cap is None:
            out.append(rng.high)
    return [v for v in out if cap is None or not rng.contains(v) or v <= cap]


def inside(rng: limits.Range, cap: float | None = None) -> st.SearchStrategy:
    """Accepted values, spread over the decades of the range (at most cap)."""
    top = rng.high if cap is None else min(rng.high, cap)
    if rng.integer:
        return st.integers(int(rng.low), int(top))
    lo = max(rng.low, 1e-6) * (1 + 1e-12 if rng.low_open else 1)
    hi = min(top, 1e9)
    spread = st.floats(math.log10(lo), math.log10(hi)).map(lambda e: min(max(10**e, lo), hi))
    ends = [lo, hi, *([math.inf] if rng.inf_ok else [])]
    return st.one_of(spread, st.sampled_from(ends))


def numbers(rng: limits.Range, cap: float | None = None) -> st.SearchStrategy:
    """Mostly accepted values; the range's edges and beyond; specials."""
    good = inside(rng, cap)
    return st.one_of(good, good, good, st.sampled_from(_edges(rng, cap)))


def _text(value: object) -> str:
    if isinstance(value, float) and value.is_integer() and abs(value) < 1e16:
        return repr(int(value)) if value % 3 else repr(value)
    return str(value)


PATHS = [
    "out.csv", "out.json", "plot.png", "shot.png", "out.txt", "", "outdir", "taken.csv",
    "fifo.csv", "/dev/null", "/proc/version.csv", "/proc/x.png", "x" * 300 + ".csv",
    "y" * 300 + ".png", "missing/r.csv", "outdir/r.json", "outdir/p.png", ".csv", "-",
    "été.csv", "outdir/../r.csv", "z" * 300 + "/r.csv", "afile/r.csv", "afile/r.png",
]  # fmt: skip
FROMS = [
    "good.json", "good.csv", "list.json", "deep.json", "short.csv", "binary.json",
    "fifo.json", "dirx.json", "missing.json", "empty.csv", "badparams.json", "afile",
    "v" * 300 + "/r.json", "afile/r.json", "/dev/null.json",
]  # fmt: skip
DIRS = [
    *("cfg-good", "cfg-deep", "cfg-fifo", "data-deep", "afile", "missing-dir", "/proc"),
    *("outdir", "w" * 300, "afile/sub", "/dev/null"),
]
LONG_RAMP = ",".join(f"{400 - i * 0.1:g}@{i}" for i in range(60))  # longer than a file name
SCHEDULES = st.one_of(
    st.sampled_from(
        [
            *("400", "inf", "0", "-5", "nan", "eta=6", "eta=0", "eta=1e308", "eta=5e-324"),
            *("1e308", "400@0,60@1800", "400@0,60@0", "5e-324", "400@0,", "eta=", "@"),
            *("400@nan", "60@2", ",".join(f"{400 - i}@{i}" for i in range(1500))),
            *("eta=1e-100", "eta=1000", "demo", "fifo.json", "deep.json", "x" * 1500, LONG_RAMP),
        ]
    ),
    st.lists(
        st.tuples(
            st.one_of(st.floats(-10, 1e6), st.sampled_from(SPECIAL)),
            st.one_of(st.floats(-5, 1e9), st.sampled_from(SPECIAL)),
        ),
        min_size=1,
        max_size=4,
    ).map(lambda pts: ",".join(f"{h!r}@{f!r}" for h, f in pts)),
)
STARTS = st.one_of(
    st.sampled_from(["cup", "thermal=20", "thermal", "thermal=", "Thermal=2", "cup "]),
    numbers(limits.START_KT).map(lambda v: f"thermal={_text(v)}"),
)


def _option_values(action: argparse.Action) -> st.SearchStrategy:
    """Texts to put after an option: its own kind of values, edges, and junk."""
    kind = getattr(action.type, "range", None)
    if kind is not None:
        own = numbers(kind, WORK.get(action.dest)).map(_text)
    elif getattr(action.type, "suffixes", None) is not None:
        own = st.sampled_from(PATHS)
    elif action.choices:
        own = st.sampled_from(sorted(map(str, action.choices)))
    elif action.dest == "from_file":
        own = st.sampled_from(FROMS)
    elif action.dest in ("autopilot", "baseline"):
        own = st.sampled_from([*FROMS, "demo", "1" * 1500, "linear:h0=400,h1=60", LONG_RAMP])
    elif action.dest == "schedule":
        own = SCHEDULES
    elif action.dest == "start":
        own = STARTS
    elif action.dest.endswith("_dir"):
        own = st.sampled_from(DIRS)
    else:
        own = JUNK
    return st.one_of(own, own, own, JUNK)


class _CapturedError(Exception):
    pass


def parser_of(command: str) -> argparse.ArgumentParser:
    """The parser of a command (its build_parser, else caught from its main)."""
    module = importlib.import_module(SUBCOMMANDS[command][0] if command else "evapcool.app.cli")
    if hasattr(module, "build_parser"):
        return module.build_parser()
    caught: list[argparse.ArgumentParser] = []
    original = argparse.ArgumentParser.parse_args

    def capture(self, *args, **kwargs):
        caught.append(self)
        raise _CapturedError

    argparse.ArgumentParser.parse_args = capture
    try:
        module.main([])
    except _CapturedError:
        pass
    finally:
        argparse.ArgumentParser.parse_args = original
    return caught[0]


def argv_for(parser: argparse.ArgumentParser) -> st.SearchStrategy:
    options = [a for a in parser._actions if a.option_strings and a.dest != "help"]

    def one(action: argparse.Action) -> st.SearchStrategy:
        flag = st.sampled_from(action.option_strings)
        if action.nargs == 0:
            return flag.map(lambda f: [f])
        return st.tuples(flag, _option_values(action)).map(list)

    pieces = st.one_of(*(one(a) for a in options), JUNK.map(lambda j: [j]))
    return st.lists(pieces, max_size=6).map(lambda ps: [t for p in ps for t in p])


#: The tail that keeps a valid run short; commands not named here stop at --help.
TAILS = {"": ["--frames", "2"], "lab": ["--frames", "3"], "bench": []}
COMMANDS = ["", *sorted(SUBCOMMANDS)]


def _check_exit(argv: list[str], answer: dict, command: str = "") -> None:
    code, err = answer["code"], answer["stderr"]
    event(f"exit {code}")
    # Exit 1: a run too short for --theory's model (documented), known only after it;
    # `evapcool verify` when a code was rejected (documented: the rejections are its output).
    theory = code == 1 and "--theory" in argv and "error: --theory: theory needs" in err
    rejected = code == 1 and command == "verify" and "Traceback" not in err
    assert code in (0, 2) or theory or rejected, f"exit {code}: {argv!r}\n{err}"
    if code == 2:
        assert err.count("\n") == 1 and "Traceback" not in err, f"{argv!r}\n{err}"
        named = [t for t in argv if t.startswith("-") and t.split("=")[0] in err]
        assert named or "unrecognized" in err or "argument" in err, f"{argv!r}: {err}"


@pytest.mark.parametrize("command", COMMANDS, ids=lambda c: c or "play")
def test_fuzz_command_line(command: str, worker: Worker) -> None:
    prefix = [command] if command else []
    tail = TAILS.get(command, ["--help"])

    @FUZZ
    @given(argv_for(parser_of(command)))
    def run(argv: list[str]) -> None:
        full = [*prefix, *argv, *tail]
        _check_exit(argv, worker.run({"kind": "cli", "argv": full}), command)

    run()


# -- the Python API ----------------------------------------------------------------------------
ANY = st.one_of(
    st.none(),
    st.booleans(),
    st.integers(-3, 3),
    st.floats(),
    st.text(max_size=4),
    st.sampled_from(
        [
            *([], {}, (1, 2), b"x", [1.0, 2.0], np.array([1.0]), np.float32(2.0), np.int64(3)),
            *(np.bool_(True), 2**64, 10**12, 1e308, 5e-324, "12", "no", "yes", math.nan),
        ]
    ),
)


def _param(rng: limits.Range, cap: float | None = None) -> st.SearchStrategy:
    return st.one_of(numbers(rng, cap), ANY)


def _valid(rng: limits.Range, cap: float | None = None) -> st.SearchStrategy:
    return inside(rng, cap)


def kwargs_of(valid: dict, anything: dict) -> st.SearchStrategy:
    """Keyword sets: all accepted, all accepted but one, or anything at all."""
    all_valid = st.fixed_dictionaries({}, optional=valid)
    bad_one = st.sampled_from(sorted(anything)).flatmap(
        lambda k: st.tuples(st.just(k), anything[k])
    )
    one_bad = st.tuples(all_valid, bad_one).map(lambda t: {**t[0], t[1][0]: t[1][1]})
    return st.one_of(all_valid, one_bad, st.fixed_dictionaries({}, optional=anything))


A = 0.01


@st.composite
def states(draw) -> dict:
    """Given positions and velocities: in the cup, on the wall grazing, overlapping, or junk."""
    n = draw(st.integers(1, 3))
    xs = draw(st.lists(st.floats(-150, 150), min_size=n, max_size=n))
    lift = draw(st.sampled_from([0.0, 1e-9, 0.5, 30.0, 300.0, -1e-3]))
    pos = [(x, A * x * x + lift + 40.0 * i * (lift > 1)) for i, x in enumerate(xs)]
    speed = st.one_of(st.floats(-limits.VELOCITY_MAX, limits.VELOCITY_MAX), st.sampled_from(EDGES))
    vel = draw(st.lists(st.tuples(speed, speed), min_size=n, max_size=n))
    if draw(st.booleans()):  # tangent to the wall: the grazing states of issue 13
        vel = [(v, 2 * A * x * v) for (x, _), (v, _) in zip(pos, vel, strict=True)]
    out = {"n_atoms": n, "positions": pos, "velocities": vel}
    if draw(st.integers(0, 5)) == 0:
        out[draw(st.sampled_from(["positions", "velocities"]))] = draw(ANY)
    return out


SIM_VALID = {
    "n_atoms": _valid(limits.N_ATOMS, WORK["n_atoms"]),
    "radius": _valid(limits.RADIUS),
    "mass": _valid(limits.MASS),
    "curvature": _valid(limits.CURVATURE),
    "gravity": _valid(limits.GRAVITY),
    "trap_height": _valid(limits.TRAP_HEIGHT),
    "tc_exponent": _valid(limits.TC_EXPONENT),
    "seed": _valid(limits.SEED),
    "room": st.tuples(_valid(limits.WINDOW_SIDE), _valid(limits.WINDOW_SIDE)).map(room_of_window),
    "engine": st.sampled_from(["auto", "reference", "fast"]),
    "escape": st.sampled_from(["rim", "knife"]),
    "record_events": st.booleans(),
    "win": st.booleans(),
}
SIM_ANY = {
    **{k: st.one_of(v, ANY) for k, v in SIM_VALID.items()},
    **{k: _param(getattr(limits, k.upper())) for k in ("radius", "mass", "curvature", "gravity")},
    "n_atoms": _param(limits.N_ATOMS, WORK["n_atoms"]),
    "trap_height": _param(limits.TRAP_HEIGHT),
    "tc_exponent": _param(limits.TC_EXPONENT),
    "seed": _param(limits.SEED),
    "room": st.one_of(st.builds(Room, *[st.floats(-10.0, 10_000.0)] * 4), ANY),
}


def _short(dt: object) -> bool:
    """dt is not an accepted long advance: those are bounded work, but minutes of it."""
    return not (isinstance(dt, (int, float)) and limits.DT.contains(float(dt)) and dt > 100)


DT = st.one_of(st.floats(0, 1), st.sampled_from([0.0, 1.0, *EDGES, *SPECIAL]), ANY.filter(_short))


def _named(message: str, names) -> bool:
    head = message.split(" ", 1)[0].rstrip(":")
    return head in names or any(f"'{n}'" in message for n in names)


def _check_api(kwargs: dict, answer: dict, names) -> None:
    event("refused" if "error" in answer else "ran")
    if "error" in answer:
        assert answer["error"] in ("ValueError", "ParameterError", "TypeError"), answer
        assert _named(answer["message"], names), f"{kwargs!r}: {answer['message']}"
    else:
        assert answer["finite"], f"non-finite result: {kwargs!r}"


@FUZZ
@given(kwargs_of(SIM_VALID, SIM_ANY), st.one_of(st.just({}), states()), DT)
def test_fuzz_simulation(worker: Worker, kwargs: dict, state: dict, dt: object) -> None:
    kwargs = {**kwargs, **state}
    answer = worker.run({"kind": "sim", "kwargs": kwargs, "dt": dt})
    _check_api(kwargs, answer, [*SIM_ANY, "positions", "velocities", "dt"])


LAB_VALID = {
    "n_atoms": _valid(limits.N_ATOMS, WORK["n_atoms"]),
    "radius": _valid(limits.RADIUS),
    "curvature": _valid(limits.CURVATURE),
    "gravity": _valid(limits.GRAVITY),
    "seed": _valid(limits.SEED),
    "engine": st.sampled_from(["auto", "reference", "fast"]),
    "frames": st.integers(1, WORK["frames"]),
    "every": _valid(limits.EVERY, WORK["every"]),
    "escape": st.sampled_from(["rim", "knife"]),
    "schedule": SCHEDULES,
    "tc_law": st.sampled_from(["seed", "cup"]),
    "start": STARTS,
    "stop_at_win": st.booleans(),
    "out": st.sampled_from(["out.csv", "out.json", "outdir/r.json"]),
    "plot": st.just("outdir/p.png"),
    "progress": st.sampled_from([True, False, None]),
    "checkpoint_seconds": _valid(limits.CHECKPOINT_SECONDS),
    "on_record": st.sampled_from([len, id, None]),
}
LAB_ANY = {
    **{k: st.one_of(v, ANY) for k, v in LAB_VALID.items()},
    **{k: _param(getattr(limits, k.upper())) for k in ("radius", "curvature", "gravity", "seed")},
    "n_atoms": _param(limits.N_ATOMS, WORK["n_atoms"]),
    "every": _param(limits.EVERY),
    "out": st.one_of(st.sampled_from(PATHS), ANY),
    "plot": st.one_of(st.sampled_from(PATHS), ANY),
    "checkpoint_seconds": _param(limits.CHECKPOINT_SECONDS),
}


@FUZZ
@given(kwargs_of(LAB_VALID, LAB_ANY))
def test_fuzz_run_experiment(worker: Worker, kwargs: dict) -> None:
    kwargs.setdefault("frames", 3)  # not the default 1800: keep valid runs short
    answer = worker.run({"kind": "lab", "kwargs": kwargs})
    _check_api(kwargs, answer, [*LAB_ANY, *LabConfig.__dataclass_fields__, "n_atoms"])


# -- states read from files (Simulation.from_state) ---------------------------------------------
def _saved_state() -> dict:
    from evapcool import Simulation

    sim = Simulation(6, radius=10.0, seed=3, trap_height=math.inf)
    sim.advance(40.0)  # mid-run: atoms at their own times, some touching after collisions
    return sim.to_state()


SAVED = _saved_state()
STATE_FIELDS = {
    "time": _param(limits.DT),
    "trap_height": _param(limits.TRAP_HEIGHT),
    "curvature": _param(limits.CURVATURE),
    "gravity": _param(limits.GRAVITY),
    "tc_exponent": _param(limits.TC_EXPONENT),
    "window": st.one_of(st.lists(numbers(limits.WINDOW_SIDE), min_size=2, max_size=2), ANY),
    "escape": st.one_of(st.sampled_from(["rim", "knife"]), ANY),
    "win": st.one_of(st.booleans(), ANY),
    "won": st.one_of(st.booleans(), ANY),
}
ATOM_FIELDS = {
    "x": st.floats(-300, 300),
    "y": st.floats(-1, 600),
    "vx": numbers(limits.Range(-limits.VELOCITY_MAX, limits.VELOCITY_MAX)),
    "vy": numbers(limits.Range(-limits.VELOCITY_MAX, limits.VELOCITY_MAX)),
    "radius": numbers(limits.RADIUS),
    "mass": numbers(limits.MASS),
    "t": st.floats(-1e3, 40.0),
}


@st.composite
def states_json(draw) -> object:
    """A saved state with some fields or one atom's values changed, or garbage."""
    state = json.loads(json.dumps(SAVED))
    few = st.integers(0, 3).flatmap(lambda k: st.just(k) if k < 2 else st.integers(0, k))
    for key in draw(st.lists(st.sampled_from(sorted(STATE_FIELDS)), max_size=draw(few))):
        state[key] = draw(STATE_FIELDS[key])
    for key in draw(st.lists(st.sampled_from(sorted(ATOM_FIELDS)), max_size=draw(few))):
        i = draw(st.integers(0, len(state["atoms"]["x"]) - 1))
        state["atoms"][key][i] = draw(st.one_of(ATOM_FIELDS[key], ATOM_FIELDS[key], ANY))
    sums = draw(st.sampled_from(["keep", "drop", "drop", "junk"]))  # dropped: recomputed
    if sums != "keep":
        for key in ("energy_sum", "initial_temperature"):
            if sums == "drop":
                state.pop(key, None)
            else:
                state[key] = draw(ANY)
    if draw(st.integers(0, 9)) == 0:
        cut = json.dumps(state, default=str)[: draw(st.integers(0, 200))]
        return draw(st.one_of(ANY, st.just(cut)))
    return state


@FUZZ
@given(states_json(), DT)
def test_fuzz_state_from_a_file(worker: Worker, state: object, dt: object) -> None:
    answer = worker.run({"kind": "state", "state": state, "dt": dt})
    event("refused" if "error" in answer else "ran")
    if "error" in answer:
        assert answer["error"] in ("ValueError", "ParameterError", "TypeError"), answer
        message = answer["message"]
        known = [*STATE_FIELDS, *ATOM_FIELDS, "state", "positions", "velocities", "dt", "n_atoms"]
        assert _named(message, known) or message.startswith("state"), f"{state!r}: {message}"
    else:
        assert answer["finite"], f"non-finite result: {state!r}"
