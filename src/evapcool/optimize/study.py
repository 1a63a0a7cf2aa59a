"""The search: an Optuna study of strategies, its trials played as Dask tasks.

The study lives in storage (a SQLite file or any URL Optuna takes) with the problem it
solves in its user attributes, so a later `--resume` needs nothing else and several
processes can ask and tell on one study. Trials are asked in batches of fixed size and
each trial's seeds are split into chunks of fixed size, so the same sampler seed gives
the same trials whatever the number of workers and wherever the games run.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, fields
from pathlib import Path

from evapcool.game.autopilot import GameSetup
from evapcool.lab.cluster import Engine, StopRequest, TaskError, run_tasks
from evapcool.optimize.evaluate import Summary, chunks, play_seeds
from evapcool.optimize.families import DEFAULT_KNOTS, FAMILIES, build, params_of, suggest
from evapcool.physics.simulation import ATOM_RADIUS, N_ATOMS, TC_LAWS
from evapcool.physics.world import ESCAPE_RULES as ESCAPES

SAMPLERS = ("tpe", "cmaes", "nsga2")
OBJECTIVES = ("score", "time")
DEFAULT_SEEDS = 100
DEFAULT_BUDGET = 1800
DEFAULT_BATCH = 8
DEFAULT_CHUNK = 20
STUDY_NAME = "evapcool"
PROBLEM_ATTR = "evapcool_problem"
#: A finished trial's scores, seeds, strategy... (one user attribute).
RESULT_ATTR = "evapcool"


@dataclass(frozen=True)
class Problem:
    """What a study optimizes; stored in the study, so `--resume` repeats it exactly."""

    budget: int = DEFAULT_BUDGET
    seeds: int = DEFAULT_SEEDS
    seed_start: int = 0
    families: tuple[str, ...] = tuple(FAMILIES)
    knots: int = DEFAULT_KNOTS
    objectives: tuple[str, ...] = ("score",)
    n_atoms: int = N_ATOMS
    radius: float = ATOM_RADIUS
    escape: str = "rim"
    tc_law: str = "seed"
    sampler: str = "tpe"
    sampler_seed: int | None = None
    batch: int = DEFAULT_BATCH
    chunk: int = DEFAULT_CHUNK

    def __post_init__(self) -> None:
        for name, low in (("budget", 1), ("seeds", 2), ("seed_start", 0), ("knots", 1),
                          ("n_atoms", 2), ("batch", 1), ("chunk", 1)):  # fmt: skip
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < low:
                raise ValueError(f"{name} must be a whole number >= {low} (got {v!r})")
        if not (isinstance(self.radius, (int, float)) and math.isfinite(self.radius)
                and self.radius > 0):  # fmt: skip
            raise ValueError(f"radius must be a positive finite number (got {self.radius!r})")
        if self.escape not in ESCAPES:
            raise ValueError(f"escape must be rim or knife (got {self.escape!r})")
        if self.tc_law not in TC_LAWS:
            raise ValueError(f"tc-law must be seed or cup (got {self.tc_law!r})")
        if self.sampler not in SAMPLERS:
            raise ValueError(f"sampler must be one of {', '.join(SAMPLERS)} (got {self.sampler!r})")
        objs = self.objectives
        if (
            not objs
            or objs[0] != "score"
            or len(set(objs)) != len(objs)
            or any(o not in OBJECTIVES for o in objs)
        ):
            raise ValueError(f"objectives must be score or score,time (got {','.join(objs)!r})")
        if self.sampler == "cmaes" and (len(self.families) != 1 or len(objs) != 1):
            raise ValueError(
                "sampler cmaes searches one family for the score alone: give --family NAME "
                "and --objectives score"
            )
        if self.sampler_seed is not None and (
            isinstance(self.sampler_seed, bool)
            or not isinstance(self.sampler_seed, int)
            or self.sampler_seed < 0
        ):
            raise ValueError(
                f"sampler-seed must be a whole number >= 0 (got {self.sampler_seed!r})"
            )

    @property
    def search_seeds(self) -> list[int]:
        return list(range(self.seed_start, self.seed_start + self.seeds))

    @property
    def setup(self) -> dict:
        return asdict(
            GameSetup(
                n_atoms=self.n_atoms,
                radius=float(self.radius),
                escape=self.escape,
                tc_exponent=TC_LAWS[self.tc_law],
            )
        )

    def to_attr(self) -> dict:
        d = asdict(self)
        d["families"] = list(self.families)
        d["objectives"] = list(self.objectives)
        return d

    @classmethod
    def from_attr(cls, d: dict) -> Problem:
        known = {f.name for f in fields(cls)}
        d = {"n_atoms" if k == "atoms" else k: v for k, v in d.items()}  # older studies
        kw = {k: v for k, v in d.items() if k in known}
        kw["families"] = tuple(kw.get("families", FAMILIES))
        kw["objectives"] = tuple(kw.get("objectives", ("score",)))
        return cls(**kw)


def storage_url(text: str) -> str:
    """A storage URL for Optuna: 'sqlite:///abs/path' for a plain file name."""
    if "://" in text:
        return text
    return "sqlite:///" + str(Path(text).resolve())


def make_storage(url: str):
    import optuna

    if url.startswith("sqlite"):
        # Several processes on one SQLite file: wait for the lock rather than fail.
        return optuna.storages.RDBStorage(url, engine_kwargs={"connect_args": {"timeout": 120}})
    return optuna.storages.RDBStorage(url)


def make_sampler(problem: Problem):
    import optuna

    seed = problem.sampler_seed
    if problem.sampler == "cmaes":
        return optuna.samplers.CmaEsSampler(seed=seed, warn_independent_sampling=False)
    if problem.sampler == "nsga2":
        return optuna.samplers.NSGAIISampler(seed=seed)
    return optuna.samplers.TPESampler(
        seed=seed,
        multivariate=True,
        group=len(problem.families) > 1,
        constant_liar=problem.batch > 1,
        n_startup_trials=max(10, 2 * problem.batch),
    )


def directions(problem: Problem) -> list[str]:
    return ["maximize" if o == "score" else "minimize" for o in problem.objectives]


def quiet_optuna() -> None:
    import warnings

    import optuna

    optuna.logging.set_verbosity(optuna.logging.WARNING)
    warnings.filterwarnings("ignore", category=optuna.exceptions.ExperimentalWarning)


def create_study(problem: Problem, storage: str, name: str = STUDY_NAME):
    """A new study in storage (ValueError if one of that name is already there)."""
    import optuna

    quiet_optuna()
    store = make_storage(storage)
    if name in [s.study_name for s in optuna.get_all_study_summaries(store)]:
        raise ValueError(f"study {name!r} already exists in {storage}; continue it with --resume")
    study = optuna.create_study(
        storage=store,
        study_name=name,
        sampler=make_sampler(problem),
        directions=directions(problem),
    )
    study.set_user_attr(PROBLEM_ATTR, problem.to_attr())
    return study


def load_study(storage: str, name: str = STUDY_NAME):
    """The study and its Problem; ValueError if storage holds no evapcool study of that name."""
    import optuna

    quiet_optuna()
    store = make_storage(storage)
    names = [s.study_name for s in optuna.get_all_study_summaries(store)]
    if name not in names:
        raise ValueError(f"resume: no study {name!r} in {storage}")
    study = optuna.load_study(study_name=name, storage=store)
    attr = study.user_attrs.get(PROBLEM_ATTR)
    if not isinstance(attr, dict):
        raise ValueError(f"resume: study {name!r} in {storage} is not an evapcool study")
    problem = Problem.from_attr(attr)
    study.sampler = make_sampler(problem)
    return study, problem


@dataclass
class _Pending:
    trial: object
    family: str
    strategy: str
    rows: list
    chunks_left: int
    cpu: float = 0.0
    error: str | None = None
    told: bool = False


class Search:
    """Runs trials of a study on an Engine, telling each as soon as its games are in."""

    def __init__(self, study, problem: Problem, engine: Engine) -> None:
        self.study = study
        self.problem = problem
        self.engine = engine
        self.games = 0
        self.cpu_seconds = 0.0
        self.told = 0

    def _ask(self, k: int) -> list[_Pending]:
        import optuna

        p = self.problem
        out = []
        for _ in range(k):
            trial = self.study.ask()
            family, params = suggest(trial, p.families, p.budget, p.knots)
            try:
                text = build(family, params, p.budget, p.knots).text
            except ValueError as exc:
                trial.set_user_attr(RESULT_ATTR, {"family": family, "error": str(exc)})
                self.study.tell(trial, state=optuna.trial.TrialState.FAIL)
                continue
            n_chunks = len(chunks(p.search_seeds, p.chunk))
            out.append(_Pending(trial, family, text, [], n_chunks))
        return out

    def _tell(self, pend: _Pending) -> None:
        import optuna

        t = pend.trial
        result: dict = {"family": pend.family, "strategy": pend.strategy}
        if pend.error is not None:
            result["error"] = pend.error
            t.set_user_attr(RESULT_ATTR, result)
            self.study.tell(t, state=optuna.trial.TrialState.FAIL)
            return
        s = Summary.of(pend.rows, self.problem.budget)
        result.update(score_mean=s.mean, score_se=s.se, time_mean=s.time_mean, time_se=s.time_se,
                      no_wins=s.no_wins, n=s.n, scores=list(s.scores),
                      won_frames=list(s.won_frames), cpu_seconds=pend.cpu)  # fmt: skip
        t.set_user_attr(RESULT_ATTR, result)  # one attribute: one write to the storage
        values = [s.mean if o == "score" else s.time_mean for o in self.problem.objectives]
        self.study.tell(t, values if len(values) > 1 else values[0])
        self.told += 1

    def run(
        self,
        n_trials: int,
        timeout: float | None = None,
        on_trial: Callable[[Search], None] | None = None,
    ) -> None:
        """Run up to n_trials trials (fewer if timeout seconds pass); Ctrl-C keeps all told.

        Ctrl-C (or SIGTERM) stops at a safe point: trials asked but unfinished are failed
        and queued again, so a later `--resume` plays them first; KeyboardInterrupt follows.
        """
        p = self.problem
        start = time.monotonic()
        seed_chunks = chunks(p.search_seeds, p.chunk)
        done = 0
        pending: list[_Pending] = []
        with StopRequest() as stop:
            try:
                while done < n_trials and (timeout is None or time.monotonic() - start < timeout):
                    if stop():
                        raise KeyboardInterrupt
                    k = min(p.batch, n_trials - done)
                    pending = self._ask(k)
                    done += k
                    if not pending:
                        continue
                    args = [
                        (b.strategy, c, p.budget, p.setup) for b in pending for c in seed_chunks
                    ]
                    owner = [b for b in pending for _ in seed_chunks]

                    def got(i: int, value: object, owner=owner) -> None:
                        self._collect(owner[i], value, on_trial)

                    run_tasks(self.engine, play_seeds, args, got, stop=stop)
            except KeyboardInterrupt:
                self._requeue([b for b in pending if not b.told])
                raise

    def _collect(self, pend: _Pending, value: object, on_trial) -> None:
        if isinstance(value, TaskError):
            pend.error = value.message
        else:
            rows, cpu = value
            pend.rows.extend(rows)
            pend.cpu += cpu
            self.games += len(rows)
            self.cpu_seconds += cpu
        pend.chunks_left -= 1
        if pend.chunks_left == 0:
            self._tell(pend)
            pend.told = True
            if on_trial is not None:
                on_trial(self)

    def _requeue(self, unfinished: list[_Pending]) -> None:
        import optuna

        for pend in unfinished:
            self.study.tell(pend.trial, state=optuna.trial.TrialState.FAIL)
            self.study.enqueue_trial(dict(pend.trial.params), skip_if_exists=False)


def completed_trials(study) -> list:
    """Finished trials that carry scores, in trial order."""
    import optuna

    return [
        t
        for t in study.get_trials(deepcopy=False, states=(optuna.trial.TrialState.COMPLETE,))
        if "score_mean" in result_of(t)
    ]


def result_of(trial) -> dict:
    """What `Search` stored about a trial (older studies kept each item apart)."""
    return trial.user_attrs.get(RESULT_ATTR) or trial.user_attrs


def best_so_far(study) -> float:
    trials = completed_trials(study)
    return max((result_of(t)["score_mean"] for t in trials), default=math.nan)


def trial_strategy(trial, problem: Problem):
    """The strategy of a stored trial (rebuilt from its parameters, checked against its text)."""
    family, params = params_of(trial.params)
    strategy = build(family or problem.families[0], params, problem.budget, problem.knots)
    stored = result_of(trial).get("strategy")
    if stored is not None and stored != strategy.text:
        print(f"evapcool optimize: trial {trial.number} rebuilt differently", file=sys.stderr)
    return family, strategy
