"""The class server's words in the language a browser asks for (`?lang=`, else
Accept-Language)."""

from __future__ import annotations

from starlette.requests import Request

from evapcool.i18n import FALLBACK, Catalog, best_match, shipped_locales

#: Languages read from one Accept-Language header at most.
MAX_LANGUAGES = 8
#: The longest `?lang=` tag read.
MAX_TAG = 35


def wanted_languages(header: str) -> list[str]:
    """The tags of an Accept-Language header, most wanted first."""
    ranked: list[tuple[float, int, str]] = []
    for i, part in enumerate(header.split(",")[:MAX_LANGUAGES]):
        tag, _, q = part.strip().partition(";q=")
        try:
            weight = float(q) if q else 1.0
        except ValueError:
            weight = 0.0
        if tag and tag != "*" and weight > 0:
            ranked.append((-weight, i, tag))
    return [tag for _, _, tag in sorted(ranked)]


class Words:
    """One Catalog per shipped locale, made when first asked for."""

    def __init__(self) -> None:
        self.catalogs: dict[str, Catalog] = {}
        self.tags = shipped_locales()

    def catalog(self, tag: str) -> Catalog:
        """The catalog of a shipped locale tag."""
        if tag not in self.catalogs:
            self.catalogs[tag] = Catalog(tag)
        return self.catalogs[tag]

    def of(self, request: Request) -> Catalog:
        """The catalog of the request's `?lang=` (a page's language carried from link to
        link), else best matching its Accept-Language (English if none)."""
        return self.catalog(self.tag_of(request))

    def tag_of(self, request: Request) -> str:
        """The shipped tag a request asks for: `?lang=` if shipped, else Accept-Language."""
        given = request.query_params.get("lang", "")[:MAX_TAG]
        chosen = best_match([given], self.tags) if given else None
        header = request.headers.get("accept-language", "")
        return chosen or best_match(wanted_languages(header), self.tags) or FALLBACK


def raw(catalog: Catalog, key: str) -> str:
    """A message's text unformatted (pages fill its {placeholders} themselves)."""
    return catalog.messages.get(key) or catalog.english[key]
