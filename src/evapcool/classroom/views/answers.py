"""What every answer carries and how refusals are answered: safe headers on every answer, a
refusal (or an unknown path or method, or the database away) as JSON in the reader's
language, /c/{code} sent to its slash."""

from __future__ import annotations

from typing import Any

from starlette.exceptions import HTTPException
from starlette.requests import Request
from starlette.responses import RedirectResponse, Response

from evapcool.classroom.errors import RefusedError, refused_response
from evapcool.classroom.hub import STORE_RETRY
from evapcool.classroom.views.common import hub_of

#: Headers on every answer: no referrer (the lecturer's link holds the token), no sniffing.
SAFE_HEADERS = {
    "Referrer-Policy": "no-referrer",
    "X-Content-Type-Options": "nosniff",
    "X-Frame-Options": "DENY",
}
#: The policy of answers that are not pages (JSON, CSV, events): nothing may run or load.
DATA_POLICY = "default-src 'none'; frame-ancestors 'none'"


async def _to_class(request: Request) -> Response:
    """/c/{code} without its slash: the class's game page."""
    return RedirectResponse(f"/c/{request.path_params['code']}/", status_code=308)


async def _refused(request: Request, exc: Exception) -> Response:
    """The JSON answer of a RefusedError."""
    assert isinstance(exc, RefusedError)
    return refused_response(exc, hub_of(request).words.of(request))


async def _store_away(request: Request, exc: Exception) -> Response:
    """503 while the database does not answer (a department's PostgreSQL away)."""
    refusal = RefusedError(503, "store", "class.error.store_away", retry_after=STORE_RETRY)
    return refused_response(refusal, hub_of(request).words.of(request))


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
    answer = refused_response(refusal, hub_of(request).words.of(request))
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
