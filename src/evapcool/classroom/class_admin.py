"""`evapcool class admin`: a department server's administrator's commands, everything the
administrator's page does: a new administrator's link; a new lecturer, their new link
(relink), rename, retire; a new class, rename, archive and bring back; the list. A
lecturer is named by their number, a class by its join code or number (as `list` shows
them)."""

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


def ident(text: str) -> int:
    """A lecturer's number: ASCII digits 1..ID_MAX (as the page's forms take it)."""
    from evapcool.classroom.numbers import ID_MAX, digits_value

    value = digits_value(text, 1, ID_MAX)
    if value is None:
        raise argparse.ArgumentTypeError(f"must be a whole number >= 1 (got {text!r})")
    return value


def class_ref(text: str) -> str:
    """A class: its join code as typed (any case, spaces or dashes), or its number (as
    `list` shows it)."""
    from evapcool.classroom.numbers import ID_MAX, digits_value
    from evapcool.classroom.rooms import normal_code

    if normal_code(text) is None and digits_value(text, 1, ID_MAX) is None:
        raise argparse.ArgumentTypeError(
            f"must be a class's join code or its number from list (got {text!r})"
        )
    return text


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
    for name, helps in (
        ("relink", "a lecturer's new link (the last one stops; a retired lecturer is back)"),
        ("retire", "a lecturer's link stops; their classes and results stay"),
        ("rename-lecturer", "a lecturer's new name"),
    ):
        one = commands.add_parser(name, command=COMMAND, help=helps)
        one.add_argument("lecturer", type=ident, metavar="ID")
        if name == "rename-lecturer":
            one.add_argument("name", type=title)
    made = commands.add_parser(
        "class", command=COMMAND, help="a new class of a lecturer: prints its code"
    )
    made.add_argument("name", type=title)
    made.add_argument("--lecturer", type=ident, required=True, metavar="ID")
    for name, helps in (
        ("rename-class", "a class's new name"),
        ("archive", "no new round in a class; its results stay"),
        ("unarchive", "an archived class brought back"),
    ):
        one = commands.add_parser(name, command=COMMAND, help=helps)
        one.add_argument("room", type=class_ref, metavar="CLASS")
        if name == "rename-class":
            one.add_argument("name", type=title)
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


def _refuse(parameter: str, what: str) -> int:
    print(error_line(COMMAND, f"argument {parameter}: {what}"), file=sys.stderr)
    return EXIT_USAGE


def run(store: Any, args: argparse.Namespace, words: Catalog) -> int:
    """One command on an open store; prints its lines (bad input: one line, 2)."""
    from evapcool.classroom.tokens import digest
    from evapcool.classroom.views.department import new_admin_token, new_token

    if args.command == "token":
        print(words.t("class.cli.admin", url=f"{args.url}/admin?token={new_admin_token(store)}"))
        return 0
    if args.command == "lecturer":
        token = new_token()
        made = store.add_lecturer(args.name, digest(token))
        link = f"{args.url}/lecturer?token={token}"
        print(words.t("class.cli.new_lecturer", id=made, name=args.name, url=link))
        return 0
    if args.command == "list":
        return _list(store, words)
    if args.command in ("relink", "retire", "rename-lecturer", "class"):
        names = {row["id"]: row["name"] for row in store.lecturers()}
        if args.lecturer not in names:
            parameter = "--lecturer" if args.command == "class" else "ID"
            return _refuse(parameter, f"no lecturer {args.lecturer}")
        return _lecturer_command(store, args, words, names[args.lecturer])
    room = _room_of(store, args.room)
    if room is None:
        return _refuse("CLASS", f"no class {args.room}")
    return _class_command(store, args, words, room)


def _room_of(store: Any, ref: str) -> dict[str, Any] | None:
    """The class a join code names, else the one of that number (a code of digits alone,
    such as 346779, is a code first)."""
    from evapcool.classroom.rooms import normal_code

    code = normal_code(ref)
    found = store.room_by_code(code) if code else None
    if found is None and ref.isascii() and ref.isdigit():
        found = store.room(int(ref))
    return found


def _lecturer_command(store: Any, args: argparse.Namespace, words: Catalog, name: str) -> int:
    """relink, retire, rename-lecturer or class, for a lecturer who exists."""
    from evapcool.classroom.tokens import digest
    from evapcool.classroom.views.department import new_token

    who = args.lecturer
    if args.command == "relink":
        token = new_token()
        store.set_lecturer_digest(who, digest(token))
        link = f"{args.url}/lecturer?token={token}"
        print(words.t("class.cli.new_lecturer", id=who, name=name, url=link))
    elif args.command == "retire":
        store.retire_lecturer(who)
        print(words.t("class.cli.retired", id=who, name=name))
    elif args.command == "rename-lecturer":
        store.rename_lecturer(who, args.name)
        print(words.t("class.cli.renamed_lecturer", id=who, name=args.name))
    else:
        room = store.add_room(args.name, who)
        join = f"{args.url}/c/{room['code']}/"
        print(words.t("class.cli.new_class", name=room["name"], code=room["code"], url=join))
    return 0


def _class_command(
    store: Any, args: argparse.Namespace, words: Catalog, room: dict[str, Any]
) -> int:
    """rename-class, archive or unarchive, for a class that exists."""
    code = room["code"]
    if args.command == "rename-class":
        store.rename_room(room["id"], args.name)
        print(words.t("class.cli.renamed_class", code=code, name=args.name))
    else:
        archive = args.command == "archive"
        store.set_archived(room["id"], archive)
        key = "class.cli.archived" if archive else "class.cli.unarchived"
        print(words.t(key, code=code, name=room["name"]))
    return 0


def _list(store: Any, words: Catalog) -> int:
    """The lecturers (retired ones marked), then the classes (archived ones marked)."""
    from evapcool.classroom.rooms import DEFAULT_ROOM

    for row in store.lecturers():
        line = words.t("class.cli.list_lecturer", id=row["id"], name=row["name"])
        print(f"{line} ({words.t('console.admin.retired')})" if row["retired"] else line)
    archived = store.archived_rooms()
    for room in store.rooms():
        if room["id"] == DEFAULT_ROOM and store.latest(DEFAULT_ROOM) is None:
            continue  # the single class's room, empty: not a class of the department
        line = f"{room['id']}  {room['code']}  {room['name']}  ({room['lecturer_name'] or '-'})"
        mark = f"  [{words.t('console.admin.archived')}]" if room["id"] in archived else ""
        print(line + mark)
    return 0
