"""The console's HTML shells: the administrator's page, a department lecturer's list of
classes and the refusal pages a browser gets, in the console's design (web/src/classroom/
console.css) with its small script (console.ts: copy buttons, confirmations).

Every argument that is text is escaped here or by the caller (html.escape); names enter
only escaped.
"""

from __future__ import annotations

import html
from collections.abc import Callable

from starlette.responses import HTMLResponse

from evapcool.classroom import pages

#: What a refused browser is told to do, by the refusal's catalog key.
TODO = {
    "class.error.lecturer": "console.todo.lecturer",
    "class.error.admin": "console.todo.admin",
    "class.error.no_class": "console.todo.no_class",
    "console.error.csrf": "console.todo.csrf",
    "class.error.not_found": "console.todo.not_found",
    "class.error.store_away": "console.todo.store_away",
    "class.error.slow_down": "console.todo.slow_down",
}
#: The command that makes a new administrator's link (said on the administrator's refusal).
ADMIN_COMMAND = "evapcool class admin --db … token"
#: The words console.ts needs (copy buttons, confirmations).
SCRIPT_WORDS = ("console.copy", "console.copied", "console.sure")


def console_page(
    raw: Callable[[str], str],
    lang: str,
    direction: str,
    title: str,
    body: str,
    status: int = 200,
) -> HTMLResponse:
    """A console page (body already escaped HTML); never cached, its own policy."""
    words = pages.words_json({k: raw(k) for k in SCRIPT_WORDS})
    text = (
        f'<!doctype html><html lang="{html.escape(lang)}" dir="{html.escape(direction)}">'
        '<head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{html.escape(title)}</title><style>{pages.STYLE_CONSOLE}</style></head>"
        f'<body class="console">{body}'
        f'<script type="application/json" id="words">{words}</script>'
        f"<script>{pages.SCRIPT_CONSOLE}</script></body></html>"
    )
    headers = {"Content-Security-Policy": pages.CONSOLE_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, status_code=status, headers=headers)


def refusal_page(
    raw: Callable[[str], str],
    lang: str,
    direction: str,
    status: int,
    key: str,
    message: str,
) -> HTMLResponse:
    """A refusal as a page: what happened (the refusal's own words) and what to do."""
    todo = html.escape(raw(TODO.get(key, "console.todo.other")))
    todo = todo.replace("{command}", f"<code>{html.escape(ADMIN_COMMAND)}</code>")
    title = raw("console.refused.title")
    body = (
        f'<main class="refusal"><h1>{html.escape(title)}</h1>'
        f'<p id="refusal" role="alert">{html.escape(message)}</p>'
        f'<p id="todo">{todo}</p>'
        f'<p><a class="button" href="/">{html.escape(raw("console.home"))}</a></p>'
        f'<p class="status">HTTP {status}</p></main>'
    )
    return console_page(raw, lang, direction, title, body, status)
