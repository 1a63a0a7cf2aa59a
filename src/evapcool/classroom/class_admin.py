"""`evapcool class admin`: a department server's administrator's commands (the same as the
administrator's page): a new administrator's link, lecturers, classes, the list."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from evapcool.about import error_line
from evapcool.argtypes import OneLineParser
from evapcool.i18n import Catalog, choose_locale

EXIT_USAGE = 2
COMMAND = "class admin"


def title(text: str) -> str:
    """A lecturer's or class's name: 1..80 visible characters."""
    from evapcool.classroom.views.department import TITLE_MAX

    cleaned = " ".join(text.split())
    if not cleaned or len(cleaned) > TITLE_MAX or not cleaned.isprintable():
        raise argparse.ArgumentTypeError(f"must be 1..{TITLE_MAX} visible characters")
    return cleaned


def url(text: str) -> str:
    """The server's public address (http:// or https://)."""
    if not text.startswith(("http://", "https://")) or len(text) < 9:
        raise argparse.ArgumentTypeError(f"must start with http:// or https:// (got {text!r})")
    return text.rstrip("/")


def build_parser() -> OneLineParser:
    """The options and commands of `evapcool class admin`."""
    parser = OneLineParser(
        COMMAND,
        prog="evapcool class admin",
        description="A department's class server: administrator, lecturers, classes.",
    )
    parser.add_argument(
        "--db", required=True, metavar="FILE|URL", help="the store (as evapcool class --db)"
    )
    parser.add_argument(
        "--url",
        type=url,
        default="http://127.0.0.1:8765",
        help="the server's address as students reach it (for the links printed)",
    )
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")
    commands.add_parser(
        "token", command=COMMAND, help="a new administrator's link (the last one stops working)"
    )
    lecturer = commands.add_parser(
        "lecturer", command=COMMAND, help="a new lecturer: prints their link"
    )
    lecturer.add_argument("name", type=title)
    relink = commands.add_parser(
        "relink", command=COMMAND, help="a lecturer's new link (the last one stops)"
    )
    relink.add_argument("lecturer", type=int, metavar="ID")
    made = commands.add_parser(
        "class", command=COMMAND, help="a new class of a lecturer: prints its code"
    )
    made.add_argument("name", type=title)
    made.add_argument("--lecturer", type=int, required=True, metavar="ID")
    commands.add_parser("list", command=COMMAND, help="the lecturers and classes")
    return parser


def main(argv: list[str]) -> int:
    """Run one administrator's command; one line naming the parameter on bad input."""
    args = build_parser().parse_args(argv)
    from evapcool.classroom.store import DEPARTMENT_MODULES, NEEDS_DEPARTMENT, is_url
    from evapcool.extras import available

    if is_url(args.db) and not all(available(m) for m in DEPARTMENT_MODULES):
        print(NEEDS_DEPARTMENT, file=sys.stderr)
        return EXIT_USAGE
    if not is_url(args.db) and Path(args.db).is_dir():
        print(error_line(COMMAND, f"argument --db: {args.db} is a folder"), file=sys.stderr)
        return EXIT_USAGE
    from evapcool.classroom.hub import open_store

    try:
        store = open_store(args.db, connections=1)
    except Exception as exc:  # the store's own errors (sqlite3, psycopg)
        print(error_line(COMMAND, f"argument --db: {exc}"), file=sys.stderr)
        return EXIT_USAGE
    try:
        return run(store, args, Catalog(choose_locale()))
    finally:
        store.close()


def run(store: Any, args: argparse.Namespace, words: Catalog) -> int:
    """One command on an open store; prints its lines."""
    from evapcool.classroom.tokens import digest
    from evapcool.classroom.views.department import new_admin_token, new_token

    if args.command == "token":
        print(words.t("class.cli.admin", url=f"{args.url}/admin?token={new_admin_token(store)}"))
    elif args.command == "lecturer":
        token = new_token()
        made = store.add_lecturer(args.name, digest(token))
        link = f"{args.url}/lecturer?token={token}"
        print(words.t("class.cli.new_lecturer", id=made, name=args.name, url=link))
    elif args.command == "relink":
        token = new_token()
        if not store.set_lecturer_digest(args.lecturer, digest(token)):
            print(error_line(COMMAND, f"argument ID: no lecturer {args.lecturer}"), file=sys.stderr)
            return EXIT_USAGE
        link = f"{args.url}/lecturer?token={token}"
        print(words.t("class.cli.new_lecturer", id=args.lecturer, name="", url=link))
    elif args.command == "class":
        if args.lecturer not in {row["id"] for row in store.lecturers()}:
            message = f"argument --lecturer: no lecturer {args.lecturer}"
            print(error_line(COMMAND, message), file=sys.stderr)
            return EXIT_USAGE
        room = store.add_room(args.name, args.lecturer)
        join = f"{args.url}/c/{room['code']}/"
        print(words.t("class.cli.new_class", name=room["name"], code=room["code"], url=join))
    else:
        for row in store.lecturers():
            print(words.t("class.cli.list_lecturer", id=row["id"], name=row["name"]))
        from evapcool.classroom.rooms import DEFAULT_ROOM

        for room in store.rooms():
            if room["id"] == DEFAULT_ROOM and store.latest(DEFAULT_ROOM) is None:
                continue  # the single class's room, empty: not a class of the department
            print(f"{room['code']}  {room['name']}  ({room['lecturer_name'] or '-'})")
    return 0
