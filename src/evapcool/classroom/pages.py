"""The class server's HTML: the game page with the class marker, the projector, the lecturer.

Names never enter these templates: the pages' scripts put them in with textContent. The
words come from the message catalog, escaped here (html.escape, or JSON with < escaped).
The projector's and lecturer's scripts and styles are TypeScript and CSS in
web/src/classroom, built into web/class/ (package data) and inlined here. Each page's
Content-Security-Policy lets only its own script and style run (by their SHA-256), and lets
it talk to this server only.
"""

from __future__ import annotations

import functools
import html
import json
import re
from collections.abc import Callable
from importlib import resources
from string import Template

from evapcool.classroom.csp import page_policy as page_policy
from evapcool.classroom.csp import source_hash as source_hash
from evapcool.classroom.joinaddress import command_html, loopback
from evapcool.classroom.names import NAME_MAX

#: What the game page reads to enter class mode: the API's base path, and the longest
#: name the server keeps (the name box takes no more: one limit everywhere).
CLASS_MARKER = (
    '<script type="application/json" id="evapcool-class">'
    f'{{"api":"/api","name_max":{NAME_MAX}}}</script>'
)
#: The words each page's script needs: its key in the page -> the catalog key.
PAGE_WORDS = {
    "rank": "class.label.rank",
    "name": "class.label.name",
    "score": "class.label.score",
    "frames": "class.label.frames",
    "edition": "class.label.edition",
    "refused": "class.label.refused",
    "waiting": "class.projector.waiting",
    "settings": "class.projector.settings",
    "open": "class.state.open",
    "closes_in": "class.state.closes_in",
    "final": "class.state.final",
    "per_student": "class.state.attempts",
    "closed": "class.projector.closed",
    "replay": "class.projector.replay",
    "summary": "class.projector.summary",
    "hide": "class.lecturer.hide",
    "unhide": "class.lecturer.unhide",
    "hidden": "class.lecturer.hidden",
    "show": "class.lecturer.show",
    "on_projector": "class.lecturer.on_projector",
    "none": "class.lecturer.none",
    "open_now": "class.lecturer.open_now",
    "rename": "class.lecturer.rename",
    "rename_prompt": "class.lecturer.rename_prompt",
    "rim": "settings.escape_rim",
    "knife": "settings.escape_knife",
    "tc_law": "settings.tc_law",
}
#: The debrief's words (issue 36), under their catalog keys (web/src/view/debrief).
DEBRIEF_WORDS = (
    "debrief.title",
    "debrief.paths",
    "debrief.heights",
    "debrief.axis_time",
    "debrief.axis_height",
    "debrief.scale",
    "debrief.legend_end",
    "debrief.best",
    "debrief.fastest",
    "debrief.most_lost",
    "debrief.never_won",
    "debrief.anonymous_name",
    "debrief.picked",
    "debrief.describe",
    "debrief.describe_none",
    "debrief.side_by_side",
    "debrief.frame",
    "debrief.show",
    "debrief.early",
    "debrief.anonymous",
    "debrief.pair",
    "chart.axis.atoms",
    "chart.axis.temperature",
    "chart.legend.tc_line",
    "chart.legend.condensate",
    "chart.readout_path",
)
PAGE_WORDS.update({key: key for key in DEBRIEF_WORDS})


def built(name: str) -> str:
    """A class page's built script or stylesheet (web/src/classroom, built by `npm run
    build` into the package's web/class/), to be inlined whole."""
    text = (resources.files("evapcool") / "web" / "class" / name).read_text("utf-8").strip()
    if re.search(r"</(script|style)", text, re.I):
        raise ValueError(f"web/class/{name} holds a closing tag; it cannot be inlined")
    return text


STYLE_PROJECTOR = built("projector.css")
STYLE_LECTURER = built("lecturer.css")
SCRIPT_PROJECTOR = built("projector.js")
SCRIPT_LECTURER = built("lecturer.js")
#: The administrator's and lecturer's list pages and the refusal pages (web/src/classroom/
#: console.ts: copy buttons, confirmations; console.css: the console's design language).
STYLE_CONSOLE = built("console.css")
SCRIPT_CONSOLE = built("console.js")

PAGE = Template("""<!doctype html>
<html lang="$lang" dir="$dir"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>$title</title><style>$style</style></head>
<body$body_base>$body
<script type="application/json" id="words">$words</script>
<script>$script</script></body></html>
""")

PROJECTOR_BODY = Template("""<div id="page"><div id="side"><h1>$title</h1>
$loopback<div id="join-box"><div id="qr">$qr</div><div id="join-words">$code
<p id="join">$join</p></div></div>
<p id="rejected"></p></div>
<div id="main"><h2 id="round-head" hidden></h2><p id="state"></p><p id="settings"></p>
<p id="players"></p><ol id="podium" hidden></ol>
<div id="board-box"><table id="board"></table></div><p id="board-page"></p>
<div id="replay" hidden><h2 id="replay-head"></h2>
<div id="replay-stage"><iframe id="replay-frame" title="$replay" hidden></iframe></div></div>
<section id="rounds" hidden><h2 id="rounds-head">$history</h2><ol id="rounds-list"></ol>
</section></div></div>
<p id="tools"><button id="theme" type="button" aria-pressed="false">$theme</button>
<button id="history" type="button">$history</button></p>""")
#: The projector's own words (issue 45), beside PAGE_WORDS.
PROJECTOR_WORDS = (
    "console.projector.players",
    "console.projector.page",
    "console.projector.podium",
    "console.projector.atoms",
    "console.projector.round",
    "console.projector.round_line",
    "console.projector.live",
    "console.projector.history",
    "console.projector.none",
)

LECTURER_BODY = Template("""<header id="top"><div id="top-name">$classes
<h1 id="class-name">$name</h1></div>$code<nav id="top-links">
<a id="projector" class="button" href="$base/projector?key=$key" target="_blank">$projector</a>
<a id="export" class="button" download>$export</a>
<button id="print" type="button">$print</button></nav></header>
<main><section id="round" aria-labelledby="round-head"><h2 id="round-head">$round</h2>
<p id="current"></p><p id="countdown" aria-live="off"></p><p id="current-settings"></p>
<p class="actions"><button id="close" type="button">$close</button>
<button id="stop" type="button">$stop</button></p>
<p id="status" role="status"></p><p id="rejected"></p></section>
<div id="debrief-slot"></div>
<section id="table-box"><h2>$entries</h2><table id="entries" class="cards"></table></section>
<section id="rounds-box" hidden><h2>$history</h2><table id="rounds" class="cards"></table></section>
<section id="new-round"><h2>$heading</h2>
<form id="open">
<label for="n_atoms">$atoms</label><input id="n_atoms" type="number" min="2" max="400" value="49">
<label for="radius">$radius</label><input id="radius" type="number" min="1" max="40" step="any"
 value="12">
<label for="escape">$escape</label><select id="escape"><option value="rim">$rim</option>
<option value="knife">$knife</option></select>
<label for="tc_law">$tc_law</label><select id="tc_law">
<option value="0.6666666666666666">$law_seed</option><option value="0.4">$law_cup</option></select>
<label for="seed">$seed</label><input id="seed" type="number" min="0">
<label for="minutes">$minutes</label><input id="minutes" type="number" min="0.1" step="any">
<label for="attempts">$attempts</label><input id="attempts" type="number" min="1">
<label for="lost">$lost</label><input id="lost" type="checkbox">
<span></span><button class="primary">$open</button></form></section></main>""")


PROJECTOR_POLICY = page_policy(SCRIPT_PROJECTOR, STYLE_PROJECTOR, frames="'self'")
LECTURER_POLICY = page_policy(SCRIPT_LECTURER, STYLE_LECTURER)
CONSOLE_POLICY = page_policy(SCRIPT_CONSOLE, STYLE_CONSOLE).replace(
    "form-action 'none'", "form-action 'self'"
)
#: The built page's policy (a meta element) and its inline scripts.
META_POLICY = re.compile(r'(http-equiv="Content-Security-Policy"\s+content=")([^"]*)(")')
INLINE_SCRIPT = re.compile(r"<script(?![^>]*application/json)[^>]*>(.*?)</script>", re.S)


def words_json(t: dict[str, str]) -> str:
    """The page's words as JSON safe inside a script element."""
    text = json.dumps(t, ensure_ascii=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def page(
    lang: str,
    direction: str,
    title: str,
    body: str,
    words: str,
    style: str,
    script: str,
    base: str = "",
) -> str:
    """A whole page; every argument already escaped (body HTML, words JSON). base: the
    class's path on a department's server ("/c/CODE"; the scripts read it)."""
    return PAGE.substitute(
        body_base=f' data-base="{html.escape(base)}"' if base else "",
        lang=html.escape(lang),
        dir=html.escape(direction),
        title=html.escape(title),
        style=style,
        body=body,
        words=words,
        script=script,
    )


def class_marker(api: str) -> str:
    """The class marker of a class whose API is at `api` (a path on this server)."""
    return CLASS_MARKER.replace(
        '"api":"/api"', json.dumps({"api": api}, separators=(",", ":"))[1:-1]
    )


@functools.lru_cache(maxsize=256)
def game_page(api: str = "/api") -> tuple[str, str]:
    """The browser edition with the class marker (its API at `api`) before </head>, and
    its policy: the built page's, talking to this server only (from a file it talks to
    nothing), its inline scripts allowed by their hashes instead of 'unsafe-inline'."""
    text = (resources.files("evapcool") / "web" / "evapcool.html").read_text("utf-8")
    at = text.find("</head>")
    meta = META_POLICY.search(text)
    if at < 0 or meta is None or "connect-src 'none'" not in meta.group(2):
        raise ValueError("evapcool.html has no </head> or no connect-src 'none' policy")
    hashes = " ".join(source_hash(body) for body in INLINE_SCRIPT.findall(text))
    policy = meta.group(2).replace("connect-src 'none'", "connect-src 'self'")
    policy = policy.replace("script-src 'unsafe-inline'", f"script-src {hashes}")
    text = text[: meta.start(2)] + policy + text[meta.end(2) : at] + class_marker(api) + text[at:]
    # Framed by this server's projector only (it plays replays in the game page).
    return text, f"{policy}; base-uri 'none'; frame-ancestors 'self'"


def projector_page(
    raw: Callable[[str], str],
    lang: str,
    direction: str,
    join_url: str,
    qr_svg: str,
    base: str = "",
    lan_command: str | None = None,
    join: tuple[str | None, str] | None = None,
) -> str:
    """The projector: join code in the largest type beside the QR code and the short
    address (a warning in large type if phones cannot reach it, with lan_command, the
    command that started the server with --lan added), the challenge's state, the live
    leaderboard and the replay playing, the podium, the past rounds (base: the class's
    path, "" for the single class; join: (the class's code or None, the short address))."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    words.update({k: raw(k) for k in PROJECTOR_WORDS})
    code, short = join or (None, join_url)
    # The address is one piece: it shrinks to fit its line (projector.ts), never breaks inside.
    said = html.escape(raw("class.projector.join")).replace(
        "{url}", f'<span class="address">{html.escape(short)}</span>'
    )
    code_html = ""
    if code:
        label = html.escape(raw("class.join.code"))
        code_html = f'<p id="join-label">{label}</p><p id="join-code">{html.escape(code)}</p>'
    # Without a code the address is what students type: it takes the largest type.
    join_class = "" if code else ' class="alone"'
    warning = ""
    if loopback(join_url):
        command = command_html(lan_command or "evapcool class --lan")
        fix = html.escape(raw("class.projector.loopback_fix")).replace("{command}", command)
        alert = html.escape(raw("class.projector.loopback"))
        warning = f'<p id="loopback" role="alert">{alert}<br>{fix}</p>'
    body = PROJECTOR_BODY.substitute(
        title=html.escape(raw("class.projector.title")),
        qr=qr_svg,
        code=code_html,
        join=said,
        loopback=warning,
        replay=html.escape(raw("class.projector.replay")),
        theme=html.escape(raw("console.projector.theme")),
        history=html.escape(raw("console.projector.history")),
    ).replace('<p id="join">', f'<p id="join"{join_class}>')
    return page(
        lang,
        direction,
        raw("class.projector.title"),
        body,
        words_json(words),
        STYLE_PROJECTOR,
        SCRIPT_PROJECTOR,
        base,
    )


LECTURER_LABELS = (
    "title",
    "projector",
    "export",
    "open",
    "heading",
    "stop",
    "atoms",
    "radius",
    "escape",
    "seed",
    "minutes",
    "attempts",
    "close",
    "entries",
    "lost",
)
#: The console's own words on the lecturer's page (issue 45).
CONSOLE_LABELS = {
    "print": "console.lecturer.print",
    "round": "console.lecturer.round",
    "history": "console.projector.history",
}


#: The lecturer's form's words shared with the game's settings panel (one translation).
GAME_LABELS = {
    "rim": "escape_rim",
    "knife": "escape_knife",
    "tc_law": "tc_law",
    "law_seed": "law_seed",
    "law_cup": "law_cup",
}
#: The words of the lecturer's script added by the console (issue 45).
CONSOLE_WORDS = (
    "console.lecturer.attempts",
    "console.lecturer.save",
    "console.lecturer.cancel",
    "console.lecturer.confirm_title",
    "console.lecturer.confirm_text",
    "console.lecturer.confirm_go",
    "console.lecturer.pick_named",
    "console.lecturer.no_games",
    "console.lecturer.debrief_head",
    "console.lecturer.pair_left",
    "console.lecturer.pair_right",
    "console.lecturer.pair_option",
    *("console.lecturer.round_projector", "console.projector.round_line"),
)


def lecturer_page(
    raw: Callable[[str], str],
    lang: str,
    direction: str,
    key: str,
    base: str = "",
    classes: str = "",
    name: str = "",
    code: str = "",
    csrf: str = "",
) -> str:
    """The lecturer's page: the class's name and join code at the top, open and close a
    challenge, the debrief's controls, the entries (hide, rename, replay), export and
    print, and the projector's link with its key (base: the class's path, "" for the
    single class; classes: the address of the department lecturer's list of classes, ""
    for none; csrf: the token its calls carry)."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    words.update({k: raw(k) for k in CONSOLE_WORDS})
    labels = {k: html.escape(raw(f"class.lecturer.{k}")) for k in LECTURER_LABELS}
    labels.update({k: html.escape(raw(v)) for k, v in CONSOLE_LABELS.items()})
    shared = {k: html.escape(raw(f"settings.{v}")) for k, v in GAME_LABELS.items()}
    back = ""
    if classes:
        said = html.escape(raw("class.lecturer.classes"))
        back = f'<p id="crumbs"><a id="classes" href="{html.escape(classes)}">{said}</a></p>\n'
    code_box = ""
    if code:
        label = html.escape(raw("console.lecturer.join_code"))
        code_box = (
            f'<p id="code-box"><span class="label">{label}</span> '
            f'<span id="join-code" class="code">{html.escape(code)}</span></p>'
        )
    body = LECTURER_BODY.substitute(
        labels,
        **shared,
        key=html.escape(key),
        base=html.escape(base),
        classes=back,
        name=html.escape(name or raw("class.lecturer.title")),
        code=code_box,
    )
    text = page(
        lang,
        direction,
        f"{name} · {raw('class.lecturer.title')}" if name else raw("class.lecturer.title"),
        body,
        words_json(words),
        STYLE_LECTURER,
        SCRIPT_LECTURER,
        base,
    )
    return text.replace("<body", f'<body data-csrf="{html.escape(csrf)}"', 1)
