"""The class server's words in the language a browser asks for (Accept-Language)."""

from __future__ import annotations

from starlette.requests import Request

from evapcool.i18n import FALLBACK, Catalog, best_match, shipped_locales

#: Languages read from one Accept-Language header at most.
MAX_LANGUAGES = 8


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
        """The catalog best matching the request's Accept-Language (English if none)."""
        header = request.headers.get("accept-language", "")
        tag = best_match(wanted_languages(header), self.tags) or FALLBACK
        return self.catalog(tag)


def raw(catalog: Catalog, key: str) -> str:
    """A message's text unformatted (pages fill its {placeholders} themselves)."""
    return catalog.messages.get(key) or catalog.english[key]
