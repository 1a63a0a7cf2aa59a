"""The class server's HTML: the game page with the class marker, the projector, the lecturer.

Names never enter these templates: the pages' scripts put them in with textContent. The
words come from the message catalog, escaped here (html.escape, or JSON with < escaped).
Each page's Content-Security-Policy lets only its own script and style run (by their
SHA-256), and lets it talk to this server only.
"""

from __future__ import annotations

import base64
import functools
import hashlib
import html
import ipaddress
import json
import re
from collections.abc import Callable
from importlib import resources
from string import Template
from urllib.parse import urlsplit

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

STYLE_PROJECTOR = """
html,body{height:100%;margin:0}
body{background:#0b0f17;color:#f2f4f8;font:1.6vw/1.3 system-ui,sans-serif;overflow:hidden}
#page{display:grid;grid-template-columns:minmax(0,30vw) minmax(0,1fr);gap:2vw;height:100%;
box-sizing:border-box;padding:1.5vw 2vw}
#side,#main{display:flex;flex-direction:column;min-height:0;overflow:hidden}
h1{font-size:2.6vw;margin:0 0 .8vw}
#qr svg{display:block;width:min(26vw,44vh);height:auto;background:#fff;border-radius:1vw}
#join{font-size:2.4vw;font-weight:700;word-break:break-all;margin:.8vw 0}
#loopback{font-size:1.8vw;font-weight:700;background:#7a1010;color:#fff;padding:.8vw;
margin:0 0 .8vw}#loopback+#qr svg{width:min(20vw,28vh)}
.command{white-space:nowrap;font-family:ui-monospace,monospace}
#settings{font-size:1.5vw;color:#9fd3ff;margin:0 0 .6vw}#rejected{color:#ffb4a8;margin:.4vw 0}
#state{font-size:2.4vw;font-weight:700;margin:0 0 .6vw}#state.open{color:#8fe39a}
#state.closed{color:#ffd27a}
#board-box{flex:0 1 auto;min-height:0;overflow:hidden}
table{border-collapse:collapse;width:100%;table-layout:fixed;font-size:2.2vw}
td,th{padding:.2vw .8vw;text-align:start;white-space:nowrap;overflow:hidden;
text-overflow:ellipsis}tr:nth-child(even){background:#151c2a}
th{color:#9aa3b5;font-weight:400}col.rank{width:5em}col.score{width:5.5em}
col.frames{width:6.5em}
#replay{flex:1 1 0;min-height:0;display:flex;flex-direction:column;border-top:.3vw solid #9fd3ff;
margin-top:.6vw;padding-top:.4vw}#replay[hidden]{display:none}
#replay-head{font-size:1.4vw;white-space:nowrap;overflow:hidden;text-overflow:ellipsis}
#replay-code{font-size:.9vw;word-break:break-all;max-height:2.4vw;overflow:hidden}
#replay-frame{flex:1 1 0;min-height:0;width:100%;border:0;background:#000}a{color:#9fd3ff}
"""
STYLE_LECTURER = """
body{font:16px/1.4 system-ui,sans-serif;margin:1.5em;max-width:70em}
form{display:grid;grid-template-columns:max-content 14em;gap:.4em 1em;margin-bottom:1em}
table{border-collapse:collapse}td,th{border-bottom:1px solid #ccc;padding:.3em .8em;
text-align:start}tr.hidden{opacity:.45}tr.showing{background:#e4f1ff}#status{color:#a00}
button{margin-inline-end:.3em}#current{font-weight:700}
"""

SCRIPT_COMMON = """
const W = JSON.parse(document.getElementById("words").textContent);
const fill = (t, a) => t.replace(/\\{(\\w+)\\}/g, (m, k) => (k in a ? String(a[k]) : m));
function row(table, cells, tag = "td") {
  const tr = document.createElement("tr");
  for (const c of cells) {
    const td = document.createElement(tag);
    if (c instanceof Node) td.appendChild(c); else td.textContent = String(c);
    tr.appendChild(td);
  }
  table.appendChild(tr);
  return tr;
}
// The challenge's state as every page says it; its window counted down from the server's
// own "seconds left" (no clocks compared), ticking once a second.
let info = null, infoAt = 0;
const laws = {"0.6666666666666666": "2/3", "0.4": "2/5"};
function settingsText(c) {
  const s = c.settings, p = String(s.tc_exponent);
  let text = fill(W.settings, {n: s.n_atoms, radius: s.radius,
    escape: W[s.escape] || s.escape, seed: c.seed});
  text += " · " + W.tc_law + " " + (laws[p] || Number(s.tc_exponent).toFixed(3));
  if (c.attempts) text += " · " + fill(W.per_student, {n: c.attempts});
  return text;
}
function clock(seconds) {
  const s = Math.max(0, Math.ceil(seconds));
  return Math.floor(s / 60) + ":" + String(s % 60).padStart(2, "0");
}
function stateText() {
  if (!info) return ["", W.waiting];
  const left = info.closes_in === null ? null : info.closes_in - (Date.now() - infoAt) / 1000;
  if (!info.open || (left !== null && left <= 0)) return ["closed", W.final];
  return ["open", W.open + (left === null ? "" : " · " + fill(W.closes_in, {time: clock(left)}))];
}
function takeInfo(b) { info = b.info; infoAt = Date.now(); }
"""

SCRIPT_PROJECTOR = """
const key = new URLSearchParams(location.search).get("key");
let open = false, playing = null;
function tick() {
  const [kind, text] = stateText(), box = document.getElementById("state");
  box.textContent = text; box.className = kind;
}
setInterval(tick, 1000);
function showReplay(p) {
  const box = document.getElementById("replay"), frame = document.getElementById("replay-frame");
  box.hidden = !p;
  const src = p && p.code ? "/?replay=" + encodeURIComponent(p.code) + "&lang=" +
    encodeURIComponent(document.documentElement.lang) : null;
  if (src !== playing) { playing = src; frame.src = src || "about:blank"; }
  frame.hidden = !src;
  if (!p) return;
  document.getElementById("replay-head").textContent =
    W.replay + ": " + p.name + " · " + fill(W.summary, p.summary);
  // The code comes only with the projector's key while the challenge is open; it is
  // printed on the screen only once the challenge is closed.
  document.getElementById("replay-code").textContent = p.code && !open ? p.code : "";
}
function render(b) {
  open = b.open;
  takeInfo(b); tick();
  document.getElementById("settings").textContent = info ? settingsText(info) : "";
  const t = document.getElementById("board");
  t.replaceChildren();
  const cols = document.createElement("colgroup");
  for (const c of ["rank", "name", "score", "frames"]) {
    const col = document.createElement("col"); col.className = c; cols.appendChild(col);
  }
  t.appendChild(cols);
  row(t, [W.rank, W.name, W.score, W.frames], "th");
  // With a replay playing, the board keeps its top rows and the replay fills the rest.
  const rows = b.replay && b.replay.code ? b.entries.slice(0, 5) : b.entries;
  for (const e of rows) row(t, [e.rank, e.name, e.score, e.frames]);
  document.getElementById("rejected").textContent = W.refused + ": " + b.rejected;
  showReplay(b.replay);
}
const query = key ? "?key=" + encodeURIComponent(key) : "";
new EventSource("/api/stream" + query).onmessage = (e) => render(JSON.parse(e.data));
"""

SCRIPT_LECTURER = """
const token = new URLSearchParams(location.search).get("token") || "";
const auth = {"Authorization": "Bearer " + token, "Content-Type": "application/json"};
const say = (text) => { document.getElementById("status").textContent = text; };
async function post(path, body) {
  const r = await fetch(path, {method: "POST", headers: auth, body: JSON.stringify(body)});
  const d = await r.json();
  say(r.ok ? "" : d.error.field + ": " + d.error.message);
  await refresh();
}
const num = (id) => {
  const v = document.getElementById(id).value.trim();
  return v === "" ? null : Number(v);
};
document.getElementById("open").onsubmit = (ev) => {
  ev.preventDefault();
  post("/api/challenge", {n_atoms: num("n_atoms"), radius: num("radius"),
    escape: document.getElementById("escape").value, seed: num("seed"),
    tc_exponent: Number(document.getElementById("tc_law").value),
    minutes: num("minutes"), attempts: num("attempts"),
    lost: document.getElementById("lost").checked});
};
document.getElementById("close").onclick = () => post("/api/challenge/close", {});
document.getElementById("stop").onclick = () => post("/api/show", {entry: null});
document.getElementById("export").href = "/api/export.csv?token=" + encodeURIComponent(token);
function button(text, action) {
  const b = document.createElement("button");
  b.textContent = text; b.onclick = action; return b;
}
function tick() {
  const c = info;
  const [kind, text] = stateText();
  document.getElementById("current").textContent = c ? fill(W.open_now, {id: c.id, seed: c.seed})
    + (kind === "open" ? " · " + text : " (" + W.closed + ")") : W.none;
  document.getElementById("current-settings").textContent = c ? settingsText(c) : "";
}
setInterval(tick, 1000);
async function refresh() {
  const r = await fetch("/api/entries", {headers: auth});
  if (!r.ok) return;
  const d = await r.json();
  takeInfo({info: d.challenge}); tick();
  document.getElementById("close").disabled = !(info && info.open);
  document.getElementById("stop").disabled = d.showing === null;
  document.getElementById("rejected").textContent = W.refused + ": " + d.rejected;
  const t = document.getElementById("entries");
  t.replaceChildren();
  row(t, [W.rank, W.name, W.score, W.frames, W.edition, ""], "th");
  for (const e of d.entries) {
    const acts = document.createElement("span");
    acts.appendChild(e.hidden
      ? button(W.unhide, () => post("/api/hide", {entry: e.entry, hidden: false}))
      : button(W.hide, () => post("/api/hide", {entry: e.entry})));
    acts.appendChild(e.entry === d.showing
      ? button(W.on_projector, () => post("/api/show", {entry: null}))
      : button(W.show, () => post("/api/show", {entry: e.entry})));
    acts.appendChild(button(W.rename, () => {
      const name = prompt(W.rename_prompt, e.name);
      if (name !== null) post("/api/rename", {entry: e.entry, name: name});
    }));
    const tr = row(t, [e.rank === null ? "" : e.rank, e.name, e.score, e.frames, e.edition, acts]);
    tr.dataset.entry = e.entry;
    if (e.hidden) { tr.className = "hidden"; tr.title = W.hidden; }
    if (e.entry === d.showing) tr.className += " showing";
  }
}
// The projector's key (in its link) lets this page's stream past the students' streams.
const projectorLink = document.getElementById("projector");
new EventSource("/api/stream" + new URL(projectorLink.href).search).onmessage = () => refresh();
"""

PAGE = Template("""<!doctype html>
<html lang="$lang" dir="$dir"><head><meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>$title</title><style>$style</style></head>
<body>$body
<script type="application/json" id="words">$words</script>
<script>$script</script></body></html>
""")

PROJECTOR_BODY = Template("""<div id="page"><div id="side"><h1>$title</h1>
$loopback<div id="qr">$qr</div><p id="join">$join</p>
<p id="rejected"></p></div>
<div id="main"><p id="state"></p><p id="settings"></p>
<div id="board-box"><table id="board"></table></div>
<div id="replay" hidden><div id="replay-head"></div><code id="replay-code"></code>
<iframe id="replay-frame" title="$replay" hidden></iframe></div></div></div>""")

LECTURER_BODY = Template("""<h1>$title</h1>
<p><a id="projector" href="/projector?key=$key" target="_blank">$projector</a> ·
<a id="export" download>$export</a></p>
<p id="current"></p><p id="current-settings"></p>
<p><button id="close">$close</button> <button id="stop">$stop</button></p>
<p id="status" role="status"></p><p id="rejected"></p>
<h2>$entries</h2><table id="entries"></table>
<h2>$heading</h2>
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
<span></span><button>$open</button></form>""")


def source_hash(text: str) -> str:
    """A script's or style's CSP source: 'sha256-<base64 of its SHA-256>'."""
    return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() + "'"


def page_policy(script: str, style: str, frames: str = "'none'") -> str:
    """The policy of a page: its one script and one style, talking to this server only
    (frames: what it may show in a frame; the projector, this server's game page)."""
    return (
        f"default-src 'none'; script-src {source_hash(SCRIPT_COMMON + script)}; "
        f"style-src {source_hash(style)}; connect-src 'self'; frame-src {frames}; "
        "base-uri 'none'; form-action 'none'; frame-ancestors 'none'"
    )


PROJECTOR_POLICY = page_policy(SCRIPT_PROJECTOR, STYLE_PROJECTOR, frames="'self'")
LECTURER_POLICY = page_policy(SCRIPT_LECTURER, STYLE_LECTURER)
#: The built page's policy (a meta element) and its inline scripts.
META_POLICY = re.compile(r'(http-equiv="Content-Security-Policy"\s+content=")([^"]*)(")')
INLINE_SCRIPT = re.compile(r"<script(?![^>]*application/json)[^>]*>(.*?)</script>", re.S)


def words_json(t: dict[str, str]) -> str:
    """The page's words as JSON safe inside a script element."""
    text = json.dumps(t, ensure_ascii=False)
    return text.replace("<", "\\u003c").replace(">", "\\u003e").replace("&", "\\u0026")


def page(
    lang: str, direction: str, title: str, body: str, words: str, style: str, script: str
) -> str:
    """A whole page; every argument already escaped (body HTML, words JSON)."""
    return PAGE.substitute(
        lang=html.escape(lang),
        dir=html.escape(direction),
        title=html.escape(title),
        style=style,
        body=body,
        words=words,
        script=SCRIPT_COMMON + script,
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


def loopback(url: str) -> bool:
    """Whether a join address is this computer's own (127.x, ::1, localhost): no phone
    reaches it."""
    host = (urlsplit(url).hostname or "").lower()
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return host == "localhost" or host.endswith(".localhost")


def projector_page(
    raw: Callable[[str], str], lang: str, direction: str, join_url: str, qr_svg: str
) -> str:
    """The projector: join address and QR code (a warning in large type if phones cannot
    reach it), the challenge's state, the live leaderboard and the replay playing."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    join = raw("class.projector.join").replace("{url}", join_url)
    warning = ""
    if loopback(join_url):
        # The command on one line (a break inside "--lan" would mislead).
        command = '<span class="command">evapcool class --lan</span>'
        fix = html.escape(raw("class.projector.loopback_fix")).replace("{command}", command)
        said = html.escape(raw("class.projector.loopback"))
        warning = f'<p id="loopback" role="alert">{said}<br>{fix}</p>'
    body = PROJECTOR_BODY.substitute(
        title=html.escape(raw("class.projector.title")),
        qr=qr_svg,
        join=html.escape(join),
        loopback=warning,
        replay=html.escape(raw("class.projector.replay")),
    )
    return page(
        lang,
        direction,
        raw("class.projector.title"),
        body,
        words_json(words),
        STYLE_PROJECTOR,
        SCRIPT_PROJECTOR,
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


#: The lecturer's form's words shared with the game's settings panel (one translation).
GAME_LABELS = {
    "rim": "escape_rim",
    "knife": "escape_knife",
    "tc_law": "tc_law",
    "law_seed": "law_seed",
    "law_cup": "law_cup",
}


def lecturer_page(raw: Callable[[str], str], lang: str, direction: str, key: str) -> str:
    """The lecturer's page: open and close a challenge, the entries, hide, rename, replay,
    export, and the projector's link with its key."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    labels = {k: html.escape(raw(f"class.lecturer.{k}")) for k in LECTURER_LABELS}
    shared = {k: html.escape(raw(f"settings.{v}")) for k, v in GAME_LABELS.items()}
    body = LECTURER_BODY.substitute(labels, **shared, key=html.escape(key))
    return page(
        lang,
        direction,
        raw("class.lecturer.title"),
        body,
        words_json(words),
        STYLE_LECTURER,
        SCRIPT_LECTURER,
    )
