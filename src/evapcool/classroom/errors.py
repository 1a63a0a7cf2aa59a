"""Refusals as JSON {"error": {"field", "message"}}, and request bodies read within a limit."""

from __future__ import annotations

import json
from typing import Any

from starlette.requests import Request
from starlette.responses import JSONResponse

from evapcool.classroom.depth import MAX_DEPTH, too_deep
from evapcool.i18n import Catalog


class RefusedError(Exception):
    """A request refused: HTTP status, the field at fault, a catalog key and its arguments."""

    def __init__(
        self, status: int, field: str, key: str, retry_after: int | None = None, **args: Any
    ) -> None:
        super().__init__(f"{status} {field}: {key}")
        self.status = status
        self.field = field
        self.key = key
        self.args_ = args
        self.retry_after = retry_after


def refused_response(exc: RefusedError, words: Catalog) -> JSONResponse:
    """The JSON answer of a refusal, in the request's language."""
    message = words.t(exc.key, **exc.args_)
    headers = {"Retry-After": str(exc.retry_after)} if exc.retry_after else None
    body = {"error": {"field": exc.field, "message": message}}
    return JSONResponse(body, status_code=exc.status, headers=headers)


def is_json(request: Request) -> bool:
    """Whether the request says its body is JSON: a web page elsewhere cannot send that
    without the browser asking this server first (a CORS preflight, never granted)."""
    kind = request.headers.get("content-type", "").split(";")[0].strip().lower()
    return kind == "application/json"


async def read_json(request: Request, limit: int) -> dict[str, Any]:
    """The request's JSON object; RefusedError 415 if not said to be JSON, 413 past `limit`
    bytes, 400 if not an object or nested deeper than MAX_DEPTH."""
    if not is_json(request):
        raise RefusedError(415, "content-type", "class.error.content_type")
    length = request.headers.get("content-length", "")
    if length.isascii() and length.isdigit() and int(length) > limit:
        raise RefusedError(413, "body", "class.error.too_large", n=limit)
    chunks: list[bytes] = []
    size = 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise RefusedError(413, "body", "class.error.too_large", n=limit)
        chunks.append(chunk)
    try:
        doc = json.loads(b"".join(chunks))
    except RecursionError:  # the parser's own bound, about a thousand levels
        raise RefusedError(400, "body", "class.error.too_deep", n=MAX_DEPTH) from None
    except ValueError:
        doc = None
    if too_deep(doc):
        raise RefusedError(400, "body", "class.error.too_deep", n=MAX_DEPTH)
    if not isinstance(doc, dict):
        raise RefusedError(400, "body", "class.error.body")
    return doc
