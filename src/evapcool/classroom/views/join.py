"""A department's root: the students' page joining a class by its code, in the language the
link asks for (`?lang=`, kept into the class's page), sized for a phone's thumb."""

from __future__ import annotations

import html
from urllib.parse import urlencode

from starlette.requests import Request
from starlette.responses import HTMLResponse, RedirectResponse, Response

from evapcool.classroom import pages
from evapcool.classroom.guessing import room_for
from evapcool.classroom.views.common import guard
from evapcool.i18n import Catalog

#: The game page's name box (web/src/app/page.css #join): a white card on black; every
#: control at least 44 x 44 CSS px (WCAG 2.5.5), the code in large type.
JOIN_STYLE = """
body{margin:0;min-height:100vh;background:#000;color:#111;display:flex;align-items:center;
justify-content:center;font:700 18px/1.4 "Liberation Sans",Arial,Helvetica,sans-serif}
main{box-sizing:border-box;width:min(92vw,26em);padding:1em 1.2em;background:#fff;
border-radius:8px}h1{font-size:1.3em;margin:0 0 .6em}label{display:block}
input{display:block;box-sizing:border-box;width:100%;min-height:52px;margin:.4em 0 .8em;
padding:.2em .4em;font:700 1.6em ui-monospace,monospace;letter-spacing:.2em;
text-transform:uppercase}button{font:inherit;min-height:48px;min-width:100%;
padding:.3em 1em;border:0;border-radius:6px;background:#1a56c4;color:#fff}
button:focus-visible,input:focus-visible{outline:3px solid #f5a300;outline-offset:2px}
#error{color:#a00;margin:0 0 .6em}
"""
JOIN_POLICY = (
    f"default-src 'none'; style-src {pages.source_hash(JOIN_STYLE)}; base-uri 'none'; "
    "form-action 'self'; frame-ancestors 'none'"
)


def _lang_query(request: Request, words: Catalog) -> str:
    """`?lang=TAG` when the link asked for a language (carried to the next page), else ''."""
    return "?" + urlencode({"lang": words.locale}) if request.query_params.get("lang") else ""


async def join_page(request: Request) -> Response:
    """The department's root: a box for the join code; a known code goes to its class (in
    the language the link asked for)."""
    hub = guard(request)
    words = hub.words.of(request)
    given = request.query_params.get("code")
    lang = _lang_query(request, words)
    error = ""
    if given is not None:
        room = await room_for(request, hub, given)  # wrong codes limited (issue 46)
        if room is not None:
            return RedirectResponse(f"/c/{room['code']}/{lang}", status_code=303)
        error = f'<p id="error" role="alert">{_e(words, "class.join.unknown")}</p>'
    keep = f'<input type="hidden" name="lang" value="{html.escape(words.locale)}">' if lang else ""
    title = _e(words, "class.join.title")
    body = (
        f"<main><h1>{title}</h1>{error}"
        f'<form method="get" action="/"><label for="code">{_e(words, "class.join.code")}'
        '</label><input id="code" name="code" dir="ltr" size="8" maxlength="12" autocomplete="off" '
        'autocapitalize="characters" spellcheck="false" required autofocus>'
        f"{keep}<button>{_e(words, 'class.join.go')}</button></form></main>"
    )
    text = (
        f'<!doctype html><html lang="{html.escape(words.locale)}" '
        f'dir="{html.escape(words.meta["direction"])}"><head><meta charset="utf-8">'
        '<meta name="viewport" content="width=device-width, initial-scale=1">'
        f"<title>{title}</title><style>{JOIN_STYLE}</style></head><body>{body}</body></html>"
    )
    headers = {"Content-Security-Policy": JOIN_POLICY, "Cache-Control": "no-store"}
    return HTMLResponse(text, headers=headers)


def _e(words: Catalog, key: str) -> str:
    """A catalog message, escaped for HTML."""
    return html.escape(words.t(key))
