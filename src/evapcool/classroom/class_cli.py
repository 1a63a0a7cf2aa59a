"""`evapcool class`: the class-competition server; prints the lecturer's and students' links
once it answers. `evapcool class --department`: a department's server of many classes
(the administrator's link instead); `evapcool class admin ...`: its lecturers and classes."""

from __future__ import annotations

import argparse
import os
import shlex
import socket
import sys
import urllib.parse
from pathlib import Path

from evapcool.about import APP_NAME, error_line
from evapcool.argtypes import OneLineParser
from evapcool.classroom.store import DEPARTMENT_MODULES, NEEDS_DEPARTMENT, is_url
from evapcool.extras import available, install_hint
from evapcool.i18n import Catalog, choose_locale

EXIT_USAGE = 2
DEFAULT_PORT = 8765
DEFAULT_STUDENTS = 2000
MAX_STUDENTS = 100_000
FILE_NAME = "class.sqlite"
#: Seconds an idle connection stays open: longer than clients' and proxies' own idle limits
#: (httpx 5 s, nginx's upstream 60 s), so the client closes it, never the server as a request
#: arrives on it (a reset connection, seen under load with uvicorn's 5 s).
KEEP_ALIVE_SECONDS = 75
#: The line printed when the class extra is not installed.
NEEDS_EXTRA = f"evapcool class needs the class extra: {install_hint('class')}"
EXTRA_MODULES = ("starlette", "uvicorn", "segno", "confusables")
#: The folder the applet keeps its files in when set (evapcool.app.storage.DATA_ENV).
DATA_ENV = "EVAPCOOL_DATA_DIR"


def port(text: str) -> int:
    """A TCP port 1..65535."""
    if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= 65535:
        raise argparse.ArgumentTypeError(f"must be a whole number 1..65535 (got {text!r})")
    return int(text)


def students(text: str) -> int:
    """A bound on the players of a class file, 1..100000."""
    if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= MAX_STUDENTS:
        raise argparse.ArgumentTypeError(f"must be a whole number 1..{MAX_STUDENTS} (got {text!r})")
    return int(text)


def workers(text: str) -> int:
    """A number of verifying processes 1..64."""
    if not (text.isascii() and text.isdigit()) or not 1 <= int(text) <= 64:
        raise argparse.ArgumentTypeError(f"must be a whole number 1..64 (got {text!r})")
    return int(text)


def public_url(text: str) -> str:
    """The students' address behind a reverse proxy: http:// or https://, a host, perhaps a
    port; no path (the pages' own links start at the root), query or fragment. Returned
    without a trailing /."""
    try:
        parts = urllib.parse.urlsplit(text)
        parts.port  # noqa: B018 (a bad port raises here)
    except ValueError:
        parts = None
    if (
        parts is None
        or parts.scheme not in ("http", "https")
        or not parts.hostname
        or parts.path not in ("", "/")
        or parts.query
        or parts.fragment
        or any(c.isspace() for c in text)
    ):
        raise argparse.ArgumentTypeError(
            "must be an http:// or https:// address with no path, e.g. https://class.example.edu "
            f"(got {text!r})"
        )
    return text.rstrip("/")


def default_data() -> Path:
    """The class file in $EVAPCOOL_DATA_DIR, else the per-user data folder (platformdirs),
    as evapcool's other files."""
    folder = os.environ.get(DATA_ENV)
    if folder:
        return Path(folder) / FILE_NAME
    from platformdirs import user_data_dir

    return Path(user_data_dir(APP_NAME, appauthor=False)) / FILE_NAME


def lan_address() -> str:
    """This computer's address on its network (the route out; no packet is sent)."""
    with socket.socket(socket.AF_INET, socket.SOCK_DGRAM) as probe:
        try:
            probe.connect(("192.0.2.1", 9))
            return str(probe.getsockname()[0])
        except OSError:
            return "127.0.0.1"


def build_parser() -> OneLineParser:
    """The options of `evapcool class`."""
    parser = OneLineParser(
        "class",
        prog="evapcool class",
        description="Run the class competition server (docs/class.md).",
        epilog="command: evapcool class admin ... (a department's administrator, lecturers "
        "and classes; evapcool class admin --help)",
    )
    parser.add_argument("--port", type=port, default=DEFAULT_PORT, help="TCP port (8765)")
    parser.add_argument(
        "--lan", action="store_true", help="listen on all addresses and print the network address"
    )
    parser.add_argument(
        "--public-url",
        type=public_url,
        default=None,
        metavar="URL",
        help="the address students open, behind a reverse proxy (https://...): shown on the "
        "projector and in the links",
    )
    parser.add_argument(
        "--data",
        type=Path,
        default=None,
        metavar="FILE",
        help="the SQLite file (default: class.sqlite in $EVAPCOOL_DATA_DIR, else the user data "
        "folder)",
    )
    parser.add_argument(
        "--db",
        default=None,
        metavar="FILE|URL",
        help="the store: a SQLite file, or a PostgreSQL database (postgresql://...)",
    )
    parser.add_argument(
        "--department",
        action="store_true",
        help="serve a department's classes: join by code at /, the administrator's page",
    )
    parser.add_argument(
        "--max-students",
        type=students,
        default=DEFAULT_STUDENTS,
        help=f"players a class takes at most ({DEFAULT_STUDENTS})",
    )
    parser.add_argument(
        "--new-link",
        action="store_true",
        help="make a new lecturer's (--department: administrator's) link; the last one stops "
        "working",
    )
    parser.add_argument(
        "--workers",
        type=workers,
        default=max(1, (os.cpu_count() or 2) - 1),
        help="processes verifying games (CPUs - 1)",
    )
    return parser


def _listen(host: str, number: int) -> socket.socket:
    """A listening socket on host:number (OSError if taken)."""
    sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
    sock.bind((host, number))
    sock.listen(2048)
    return sock


def store_of(args: argparse.Namespace) -> tuple[Path | str | None, str]:
    """(the store: a SQLite file or a PostgreSQL URL, or None after printing why not; the
    option that named it)."""
    option = "--db" if args.db is not None else "--data"
    if args.db is not None and is_url(args.db):
        if not all(available(m) for m in DEPARTMENT_MODULES):
            print(NEEDS_DEPARTMENT, file=sys.stderr)
            return None, option
        return str(args.db), option
    data = Path(args.db) if args.db is not None else (args.data or default_data())
    if data.is_dir():
        print(error_line("class", f"argument {option}: {data} is a folder"), file=sys.stderr)
        return None, option
    return data, option


def main(argv: list[str] | None = None) -> int:
    """Parse, bind, print the links, serve until Ctrl+C (`admin ...`: class_admin)."""
    argv = sys.argv[1:] if argv is None else argv
    if argv[:1] == ["admin"]:
        from evapcool.classroom.class_admin import main as admin_main

        return admin_main(argv[1:])
    args = build_parser().parse_args(argv)
    if not all(available(m) for m in EXTRA_MODULES):
        print(NEEDS_EXTRA, file=sys.stderr)
        return EXIT_USAGE
    data, option = store_of(args)
    if data is None:
        return EXIT_USAGE
    host = "0.0.0.0" if args.lan else "127.0.0.1"
    try:
        sock = _listen(host, args.port)
    except OSError as exc:
        print(error_line("class", f"argument --port: {args.port}: {exc.strerror}"), file=sys.stderr)
        return EXIT_USAGE
    try:
        token = first_token(data, args.new_link, args.department)
    except Exception as exc:  # the store's own errors (sqlite3, psycopg)
        sock.close()
        print(error_line("class", f"argument {option}: {data}: {exc}"), file=sys.stderr)
        return EXIT_USAGE
    base = args.public_url or f"http://{lan_address() if args.lan else host}:{args.port}"
    return serve(
        sock, data, args.workers, base, token, args.max_students, args.department, lan_command(argv)
    )


def lan_command(argv: list[str]) -> str:
    """This very command with --lan added (the projector's fix for a loopback address):
    the same port, store and mode; only --new-link dropped, so the lecturer's link holds."""
    kept = [_shown_store(a) for a in argv if a not in ("--new-link", "--lan")]  # no password
    return shlex.join(["evapcool", "class", *kept, "--lan"])


def first_token(data: Path | str, new: bool, department: bool = False) -> str | None:
    """A new lecturer's (department: administrator's) token if asked for or the store has
    none yet, else None (the one made before still works: only its digest is kept)."""
    from evapcool.classroom.hub import open_store
    from evapcool.classroom.tokens import ADMIN_SECRET, LECTURER_SECRET, new_lecturer_token
    from evapcool.classroom.views.department import new_admin_token

    store = open_store(data, connections=1)
    name, make = (
        (ADMIN_SECRET, new_admin_token) if department else (LECTURER_SECRET, new_lecturer_token)
    )
    try:
        if new or store.secret(name) is None:
            return make(store)
        return None
    finally:
        store.close()


def links(
    words: Catalog, base: str, token: str | None, data: Path | str, department: bool = False
) -> list[str]:
    """What is printed once the server answers: the lecturer's (department: the
    administrator's) link, or that the last one still works, the students' link, the
    store, how to stop."""
    if department:
        first = (
            words.t("class.cli.admin", url=f"{base}/admin?token={token}")
            if token
            else words.t("class.cli.admin_kept")
        )
    else:
        first = (
            words.t("class.cli.lecturer", url=f"{base}/lecturer?token={token}")
            if token
            else words.t("class.cli.lecturer_kept")
        )
    return [
        first,
        words.t("class.cli.students", url=f"{base}/"),
        words.t("class.cli.data", path=_shown_store(data)),
        words.t("class.cli.stop"),
    ]


def _shown_store(data: Path | str) -> str:
    """The store as printed: a file's path, a database URL without its password."""
    text = str(data)
    if is_url(text) and "@" in text.split("//", 1)[1].split("/", 1)[0]:
        scheme, rest = text.split("//", 1)
        user, host = rest.split("@", 1)
        return f"{scheme}//{user.split(':', 1)[0]}@{host}"
    return text


def serve(
    sock: socket.socket,
    data: Path | str,
    pool_workers: int,
    base: str,
    token: str | None,
    max_students: int = DEFAULT_STUDENTS,
    department: bool = False,
    relaunch: str | None = None,
) -> int:
    """Run the server on a bound socket; print the links (on `base`, the students' address
    without the trailing /) once it answers."""
    import uvicorn

    from evapcool.classroom.app import create_app
    from evapcool.classroom.hub import Limits

    lines = links(Catalog(choose_locale()), base, token, data, department)

    class Announcing(uvicorn.Server):
        """uvicorn's server, printing the links once it has started (workers warm)."""

        async def startup(self, sockets: list[socket.socket] | None = None) -> None:
            await super().startup(sockets=sockets)
            if self.started:
                print("\n".join(lines), flush=True)

    limits = Limits(students=max_students)
    app = create_app(data, pool_workers, limits, join_url=f"{base}/", department=department)
    app.state.lan_command = relaunch  # the projector's words for a loopback address
    config = uvicorn.Config(
        app, log_level="warning", timeout_graceful_shutdown=2, timeout_keep_alive=KEEP_ALIVE_SECONDS
    )
    Announcing(config).run(sockets=[sock])
    return 0
