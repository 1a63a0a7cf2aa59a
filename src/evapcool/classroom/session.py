"""Links that last: a lecturer's or the administrator's token, once opened from its link,
kept in a cookie (HttpOnly, SameSite=Strict, Secure over HTTPS) and taken out of the
address; every form and every call the page makes carries a CSRF token made from it.

The CSRF token is an HMAC of the secret token, so any server process can check it without
storing anything, and it tells nothing of the token itself.
"""

from __future__ import annotations

import hashlib
import hmac
import secrets
from urllib.parse import urlencode

from starlette.requests import Request
from starlette.responses import RedirectResponse, Response

from evapcool.classroom.errors import RefusedError

#: The cookies: a lecturer's token (every class page of theirs), the administrator's.
LECTURER_COOKIE = "evapcool_lecturer"
ADMIN_COOKIE = "evapcool_admin"
#: Where each cookie is sent: the lecturer's everywhere (/lecturer and /c/CODE/...), the
#: administrator's to the administrator's page only.
COOKIE_PATHS = {LECTURER_COOKIE: "/", ADMIN_COOKIE: "/admin"}
#: How long a link opened once lasts in that browser (a term's lectures: 120 days).
COOKIE_SECONDS = 120 * 24 * 3600
#: The form field and the header that carry the CSRF token.
CSRF_FIELD = "csrf"
CSRF_HEADER = "x-evapcool-csrf"
#: The one-time note cookie of the administrator's page (a new link, shown once).
NOTE_COOKIE = "evapcool_note"


def csrf_token(secret: str) -> str:
    """The CSRF token of a session: an HMAC of its secret token (hex, 32 digits)."""
    mac = hmac.new(secret.encode(), b"evapcool csrf", hashlib.sha256)
    return mac.hexdigest()[:32]


def csrf_ok(secret: str, given: str) -> bool:
    """Whether `given` is the session's CSRF token (constant time)."""
    return bool(secret) and secrets.compare_digest(csrf_token(secret), given)


def check_csrf(secret: str, given: str) -> None:
    """403 naming "csrf" unless `given` is the session's CSRF token."""
    if not csrf_ok(secret, given):
        raise RefusedError(403, "csrf", "console.error.csrf")


def secure(request: Request) -> bool:
    """Whether the page was read over HTTPS (the cookie is then Secure)."""
    return request.url.scheme == "https"


def set_cookie(response: Response, request: Request, name: str, value: str) -> None:
    """Keep `value` in the browser: HttpOnly, SameSite=Strict, Secure over HTTPS."""
    response.set_cookie(
        name,
        value,
        max_age=COOKIE_SECONDS if name != NOTE_COOKIE else 300,
        path=COOKIE_PATHS.get(name, "/admin"),
        secure=secure(request),
        httponly=True,
        samesite="strict",
    )


def drop_cookie(response: Response, request: Request, name: str) -> None:
    """Forget a cookie (the same attributes, expired)."""
    response.delete_cookie(
        name,
        path=COOKIE_PATHS.get(name, "/admin"),
        secure=secure(request),
        httponly=True,
        samesite="strict",
    )


def without_token(request: Request) -> str:
    """The page's own address with ?token= taken out (the other parameters kept)."""
    kept = [(k, v) for k, v in request.query_params.multi_items() if k != "token"]
    return request.url.path + ("?" + urlencode(kept) if kept else "")


def adopt(request: Request, name: str, token: str) -> Response:
    """A link's token taken into the cookie and the browser sent to the same page without
    it (303: a reload or a bookmark never holds the token, and never posts again)."""
    answer = RedirectResponse(without_token(request), status_code=303)
    set_cookie(answer, request, name, token)
    return answer


def back(request: Request, path: str) -> Response:
    """Post/redirect/get: after a form, the page again by GET (303), its language kept."""
    lang = request.query_params.get("lang")
    return RedirectResponse(path + (f"?{urlencode({'lang': lang})}" if lang else ""), 303)
