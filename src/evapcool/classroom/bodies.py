"""Request bodies read as they arrive within a limit (413 at the first byte past it, never
after the whole upload), and uploads cut mid-body ended quietly."""

from __future__ import annotations

from urllib.parse import parse_qs

from starlette.requests import Request

from evapcool.classroom.errors import RefusedError
from evapcool.classroom.numbers import digits_value


def _too_large(limit: int) -> RefusedError:
    return RefusedError(413, "body", "class.error.too_large", n=limit)


async def read_bounded(request: Request, limit: int) -> bytes:
    """The request's body, refused 413 by its Content-Length or as soon as more than
    `limit` bytes arrived (a client that leaves mid-body: Starlette's ClientDisconnect)."""
    length = request.headers.get("content-length")
    if length is not None and digits_value(length, 0, limit) is None:
        raise _too_large(limit)
    chunks: list[bytes] = []
    size = 0
    async for chunk in request.stream():
        size += len(chunk)
        if size > limit:
            raise _too_large(limit)
        chunks.append(chunk)
    return b"".join(chunks)


async def read_form(request: Request, limit: int) -> dict[str, str]:
    """A posted urlencoded form's fields within `limit` bytes (the last of a repeated one)."""
    body = await read_bounded(request, limit)
    fields = parse_qs(body.decode("utf-8", "replace"), keep_blank_values=True)
    return {k: v[-1] for k, v in fields.items()}
