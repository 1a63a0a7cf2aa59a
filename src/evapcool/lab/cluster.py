"""One distributed engine for `evapcool sweep` and `evapcool optimize`: Dask.

Runs are Dask tasks. By default a LocalCluster with one single-threaded worker process per
core; `scheduler="tcp://host:8786"` attaches to a running cluster instead (docs/cluster.md).
Results come back as tasks finish, so a worker that dies
loses only what it was running: Dask runs that again elsewhere.

dask, distributed, pandas and pyarrow are the optional extra `cluster`; they are imported
only here, inside functions, so `import evapcool` never pulls them in.
"""

from __future__ import annotations

import argparse
import contextlib
import importlib.util
import logging
import os
import platform
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass

from evapcool.about import error_line
from evapcool.argtypes import UsageError, whole
from evapcool.extras import install_hint

INSTALL_HINT = install_hint("cluster")
#: What each command needs from the extra (import names).
NEEDS = {
    "sweep": ("dask", "distributed", "pandas", "pyarrow", "tqdm"),
    "optimize": ("optuna", "dask", "distributed", "pandas", "tqdm"),
}
if sys.version_info < (3, 11):
    NEEDS["sweep"] = (*NEEDS["sweep"], "tomli")


class MissingExtraError(RuntimeError):
    """The optional cluster dependencies are not installed."""


def require_extra(command: str) -> None:
    """MissingExtraError (one line: what to install) if a module of the extra is absent."""
    missing = [m for m in NEEDS[command] if importlib.util.find_spec(m) is None]
    if missing:
        raise MissingExtraError(f"evapcool {command} needs {', '.join(missing)}: {INSTALL_HINT}")


#: Exit status of a command given bad arguments (or without the extra it needs).
EXIT_USAGE = 2


def open_command(
    command: str, parser: argparse.ArgumentParser, argv: list[str] | None
) -> argparse.Namespace | int:
    """The opening of `evapcool sweep` and `evapcool optimize`: the parsed arguments, or
    EXIT_USAGE after one line on stderr (bad arguments, the cluster extra missing)."""
    try:
        args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    except UsageError as exc:
        print(error_line(command, str(exc)), file=sys.stderr)
        return EXIT_USAGE
    try:
        require_extra(command)
    except MissingExtraError as exc:
        print(exc, file=sys.stderr)
        return EXIT_USAGE
    return args


def check_scheduler(address: str | None) -> str | None:
    """A scheduler address like tcp://host:8786; ValueError naming --scheduler otherwise."""
    if address is None:
        return None
    scheme, sep, rest = str(address).partition("://")
    host, colon, port = rest.rpartition(":")
    if not (sep and scheme in ("tcp", "tls", "ws", "wss", "inproc") and colon and host
            and port.isdigit()):  # fmt: skip
        raise ValueError(f"scheduler must be an address like tcp://host:8786 (got {address!r})")
    return str(address)


def scheduler_option(text: str) -> str:
    """--scheduler on the command line: check_scheduler, as argparse's error."""
    try:
        return str(check_scheduler(text))
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"must be an address like tcp://host:8786 (got {text!r})"
        ) from None


#: The help of the options where games run, shared by `evapcool sweep` and `evapcool optimize`.
SCHEDULER_HELP = "a running Dask scheduler (default: a local cluster)"
WORKERS_HELP = "local worker processes (default: one per core)"


def add_cluster_options(parser: argparse.ArgumentParser | argparse._ArgumentGroup) -> None:
    """--scheduler and --workers: where the games run (one definition for every command)."""
    parser.add_argument(
        "--scheduler", type=scheduler_option, metavar="tcp://HOST:8786", help=SCHEDULER_HELP
    )
    parser.add_argument("--workers", type=whole(1), help=WORKERS_HELP)


def check_workers(workers: object) -> int | None:
    if workers is None:
        return None
    if isinstance(workers, bool) or not isinstance(workers, int) or workers < 1:
        raise ValueError(f"workers must be a whole number >= 1 (got {workers!r})")
    return workers


# -- what runs on the workers ------------------------------------------------------------------


def worker_environment() -> dict[str, str]:
    """Versions and host of the process a run executes in (stored with every run)."""
    import numpy

    from evapcool import __version__

    env = {
        "evapcool_version": __version__,
        "python_version": platform.python_version(),
        "numpy_version": numpy.__version__,
        "host": platform.node(),
        "platform": platform.platform(terse=True),
    }
    with contextlib.suppress(ImportError):
        from evapcool.physics import _core

        env["core_compiler"] = _core.COMPILER
    return env


# -- the client --------------------------------------------------------------------------------


@dataclass
class Engine:
    """A connected Dask client plus what the progress lines say about it."""

    client: object
    description: str

    @property
    def n_workers(self) -> int:
        return len(self.client.scheduler_info().get("workers", {}))

    def versions(self) -> set[str]:
        """evapcool versions on the workers (one, for runs to be repeatable anywhere)."""
        found = self.client.run(lambda: worker_environment()["evapcool_version"])
        return set(found.values())


@contextlib.contextmanager
def connect(
    scheduler: str | None = None, workers: int | None = None, quiet: bool = True
) -> Iterator[Engine]:
    """A Dask client: on the scheduler given, else on a new LocalCluster (one worker per core)."""
    from dask.distributed import Client, LocalCluster

    level = logging.ERROR if quiet else logging.WARNING
    for name in ("distributed", "distributed.nanny", "distributed.scheduler",
                 "distributed.worker", "distributed.core"):  # fmt: skip
        logging.getLogger(name).setLevel(level)
    cluster = None
    if scheduler is None:
        n = workers or os.cpu_count() or 1
        cluster = LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            dashboard_address=":0",  # a free port: never a clash with another cluster
            silence_logs=level,
        )
        client = Client(cluster)
        description = f"local cluster, {n} worker{'s' if n != 1 else ''}"
    else:
        client = Client(scheduler, timeout="10s")
        description = f"scheduler {scheduler}"
    try:
        engine = Engine(client, description)
        if scheduler is not None:
            _check_versions(engine)
        yield engine
    finally:
        client.close()
        if cluster is not None:
            cluster.close()


class VersionMismatchError(RuntimeError):
    """Workers run another evapcool than this process: results would not be repeatable."""


def _check_versions(engine: Engine) -> None:
    from evapcool import __version__

    found = engine.versions()
    if found - {__version__}:
        raise VersionMismatchError(
            f"workers run evapcool {', '.join(sorted(found))} and this is {__version__}: "
            "install the same version everywhere"
        )


@dataclass(frozen=True)
class TaskError:
    """A task that could not be run (its worker kept dying, or it raised outside the run)."""

    message: str


class StopRequest:
    """Ctrl-C and SIGTERM ask for a stop, checked between safe points (never mid-write).

    The first signal only sets the flag; run_tasks then cancels what is left and raises
    KeyboardInterrupt from a safe point. A second Ctrl-C raises at once.
    """

    def __init__(self) -> None:
        self.requested = False
        self._old: dict = {}

    def __call__(self) -> bool:
        return self.requested

    def _handle(self, signum, frame) -> None:
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True

    def __enter__(self) -> StopRequest:
        if threading.current_thread() is threading.main_thread():
            for sig in (signal.SIGINT, signal.SIGTERM):
                self._old[sig] = signal.getsignal(sig)
                signal.signal(sig, self._handle)
        return self

    def __exit__(self, *exc: object) -> None:
        for sig, handler in self._old.items():
            signal.signal(sig, handler)
        self._old.clear()


def run_tasks(
    engine: Engine,
    function: Callable,
    arguments: Sequence[tuple],
    on_result: Callable[[int, object], None],
    stop: Callable[[], bool] | None = None,
) -> None:
    """Run function(*arguments[i]) for every i as Dask tasks; on_result(i, value) as each ends.

    A task whose worker is lost is re-run by Dask on another worker; one that still cannot
    run (or raises) reports a TaskError instead of a value. When stop() turns true (or on
    Ctrl-C), what is left is cancelled and KeyboardInterrupt raised.
    """
    from dask.distributed import as_completed

    client = engine.client
    futures = [client.submit(function, *args, pure=False) for args in arguments]
    index = {f.key: i for i, f in enumerate(futures)}
    done = as_completed(futures)
    try:
        while not done.is_empty():
            if stop is not None and stop():
                raise KeyboardInterrupt
            if not done.has_ready():
                time.sleep(0.05)
                continue
            for future in done.next_batch(block=False):
                try:
                    value = future.result()
                except Exception as exc:  # the worker died too often, or the task raised
                    value = TaskError(f"{type(exc).__name__}: {exc}".strip())
                on_result(index[future.key], value)
                future.release()
    except BaseException:
        client.cancel(futures)
        raise
