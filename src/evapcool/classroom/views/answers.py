"""What every answer carries and how refusals are answered: safe headers on every answer, a
refusal (or an unknown path or method, or the database away) in the reader's language, as
a page saying what to do for a browser reading a page, as JSON for API clients; /c/{code}
sent to its slash."""

from __future__ import annotations

from typing import Any
from urllib.parse import quote, urlencode

from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import RedirectResponse, Response

from evapcool.classroom.console_pages import refusal_page
from evapcool.classroom.errors import RefusedError, refused_response
from evapcool.classroom.hub import STORE_RETRY
from evapcool.classroom.views.common import hub_of
from evapcool.classroom.words import raw

#: Headers on every answer: no referrer (the lecturer's link holds the token), no sniffing.
SAFE_HEADERS = {
    "Referrer-Policy": "no-referrer",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
}
#: The policy of answers that are not pages (JSON, CSV, events): nothing may run or load.
DATA_POLICY = "default-src 'none'; frame-ancestors 'none'"


async def _to_class(request: Request) -> Response:
    """/c/{code} without its slash: the class's game page, in the language asked (`?lang=`)."""
    lang = request.query_params.get("lang")
    query = "?" + urlencode({"lang": lang[:35]}) if lang else ""
    return RedirectResponse(f"/c/{quote(request.path_params['code'])}/{query}", status_code=308)


def wants_page(request: Request) -> bool:
    """Whether a browser reads the answer as a page: asked for HTML, not at an API path
    (the API's clients, the page's own scripts and the desktop, get JSON)."""
    if "/api/" in request.url.path:
        return False
    return "text/html" in request.headers.get("accept", "")


def _answer(request: Request, refusal: RefusedError) -> Response:
    """A refusal as a page or as JSON (see wants_page), in the reader's language."""
    words = hub_of(request).words.of(request)
    if not wants_page(request):
        return refused_response(refusal, words)
    message = words.t(refusal.key, **refusal.args_)
    page = refusal_page(
        lambda k: raw(words, k),
        words.locale,
        words.meta["direction"],
        refusal.status,
        refusal.key,
        message,
    )
    if refusal.retry_after:
        page.headers["Retry-After"] = str(refusal.retry_after)
    return page


async def _refused(request: Request, exc: Exception) -> Response:
    """The answer of a RefusedError."""
    assert isinstance(exc, RefusedError)
    return _answer(request, exc)


async def _store_away(request: Request, exc: Exception) -> Response:
    """503 while the database does not answer (a department's PostgreSQL away)."""
    refusal = RefusedError(503, "store", "class.error.store_away", retry_after=STORE_RETRY)
    return _answer(request, refusal)


async def _cut_upload(request: Request, exc: Exception) -> Response:
    """A client that left mid-body (Starlette's ClientDisconnect): counted, no traceback;
    the answer goes nowhere."""
    hub_of(request).cut_uploads += 1
    return Response(status_code=400)


async def _no_route(request: Request, exc: Exception) -> Response:
    """The JSON answer of an unknown path (404) or method (405), as any refusal."""
    assert isinstance(exc, HTTPException)
    if exc.status_code == 405:
        refusal = RefusedError(405, "method", "class.error.method", method=request.method)
    else:
        refusal = RefusedError(404, "path", "class.error.not_found")
    answer = _answer(request, refusal)
    answer.headers.update(exc.headers or {})  # Allow, for a 405
    return answer


class _SafeHeaders:
    """ASGI middleware adding SAFE_HEADERS to every answer."""

    def __init__(self, app: Any) -> None:
        self.app = app

    async def __call__(self, scope: Any, receive: Any, send: Any) -> None:
        async def send_with(message: Any) -> None:
            if message["type"] == "http.response.start":
                headers = list(message.get("headers", []))
                have = {k.lower() for k, _ in headers}
                wanted = {**SAFE_HEADERS, "Content-Security-Policy": DATA_POLICY}
                # An answer's own header (the game page's framing, a page's policy) stays.
                extra = [
                    (k.lower().encode(), v.encode())
                    for k, v in wanted.items()
                    if k.lower().encode() not in have
                ]
                message["headers"] = headers + extra
            await send(message)

        if scope["type"] != "http":
            await self.app(scope, receive, send)
        else:
            await self.app(scope, receive, send_with)
