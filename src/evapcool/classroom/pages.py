"""The class server's HTML: the game page with the class marker, the projector, the lecturer.

Names never enter these templates: the pages' scripts put them in with textContent. The
words come from the message catalog, escaped here (html.escape, or JSON with < escaped).
Each page's Content-Security-Policy lets only its own script and style run (by their
SHA-256), and lets it talk to this server only.
"""

from __future__ import annotations

import base64
import hashlib
import html
import json
import re
from collections.abc import Callable
from importlib import resources
from string import Template

#: What the game page reads to enter class mode (the API's base path).
CLASS_MARKER = '<script type="application/json" id="evapcool-class">{"api":"/api"}</script>'
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
    "closed": "class.projector.closed",
    "closes": "class.projector.closes",
    "replay": "class.projector.replay",
    "summary": "class.projector.summary",
    "watch": "class.projector.watch",
    "hide": "class.lecturer.hide",
    "hidden": "class.lecturer.hidden",
    "show": "class.lecturer.show",
    "none": "class.lecturer.none",
    "open_now": "class.lecturer.open_now",
    "rename": "class.lecturer.rename",
    "rename_prompt": "class.lecturer.rename_prompt",
}

STYLE_PROJECTOR = """
html,body{height:100%;margin:0}
body{background:#0b0f17;color:#f2f4f8;font:1.6vw/1.3 system-ui,sans-serif;overflow:hidden}
#page{display:grid;grid-template-columns:minmax(0,34vw) minmax(0,1fr);gap:3vw;height:100%;
box-sizing:border-box;padding:2vw}
h1{font-size:3vw;margin:0 0 1vw}
#qr svg{display:block;width:min(28vw,48vh);height:auto;background:#fff;border-radius:1vw}
#join{font-size:1.8vw;word-break:break-all}#settings{font-size:1.6vw;color:#9fd3ff}
#rejected{color:#ffb4a8}#board-box{overflow:hidden;min-height:0}
table{border-collapse:collapse;width:100%;font-size:2.4vw}
td,th{padding:.3vw 1vw;text-align:start;white-space:nowrap;overflow:hidden;
text-overflow:ellipsis;max-width:30vw}tr:nth-child(even){background:#151c2a}
th{color:#9aa3b5;font-weight:400}
#replay{border:.3vw solid #9fd3ff;padding:1vw;margin-top:1vw}#replay code{font-size:1vw;
word-break:break-all;display:block;max-height:6vw;overflow:hidden}a{color:#9fd3ff}
"""
STYLE_LECTURER = """
body{font:16px/1.4 system-ui,sans-serif;margin:1.5em;max-width:70em}
form{display:grid;grid-template-columns:max-content 14em;gap:.4em 1em;margin-bottom:1em}
table{border-collapse:collapse}td,th{border-bottom:1px solid #ccc;padding:.3em .8em;
text-align:start}tr.hidden{opacity:.45}#status{color:#a00}button{margin-inline-end:.3em}
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
"""

SCRIPT_PROJECTOR = """
const key = new URLSearchParams(location.search).get("key");
let challenge = undefined;
async function loadChallenge() {
  const box = document.getElementById("settings");
  const r = await fetch("/api/challenge");
  if (!r.ok) { box.textContent = W.waiting; return; }
  const c = await r.json(), s = c.settings;
  let text = fill(W.settings, {n: s.n_atoms, radius: s.radius, escape: s.escape, seed: c.seed});
  if (c.closes_at) text += " · " + W.closes + " " + new Date(c.closes_at).toLocaleTimeString();
  box.textContent = text;
}
function showReplay(p) {
  const box = document.getElementById("replay");
  box.hidden = !p;
  if (!p) return;
  document.getElementById("replay-name").textContent = W.replay + ": " + p.name;
  document.getElementById("replay-summary").textContent = fill(W.summary, p.summary);
  // The code comes only with the projector's key while the challenge is open; it is
  // printed on the screen only once the challenge is closed.
  document.getElementById("replay-code").textContent = p.code && !open ? p.code : "";
  const a = document.getElementById("replay-link");
  a.hidden = !p.code;
  if (p.code) a.href = "/?replay=" + encodeURIComponent(p.code);
  a.textContent = W.watch;
}
let open = false;
function render(b) {
  open = b.open;
  if (b.challenge !== challenge || !b.open) { challenge = b.challenge; loadChallenge(); }
  const t = document.getElementById("board");
  t.replaceChildren();
  row(t, [W.rank, W.name, W.score, W.frames], "th");
  for (const e of b.entries) row(t, [e.rank, e.name, e.score, e.frames]);
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
    minutes: num("minutes"), attempts: num("attempts"),
    lost: document.getElementById("lost").checked});
};
document.getElementById("close").onclick = () => post("/api/challenge/close", {});
document.getElementById("export").href = "/api/export.csv?token=" + encodeURIComponent(token);
function button(text, action) {
  const b = document.createElement("button");
  b.textContent = text; b.onclick = action; return b;
}
async function refresh() {
  const r = await fetch("/api/entries", {headers: auth});
  if (!r.ok) return;
  const d = await r.json();
  const c = d.challenge;
  document.getElementById("current").textContent = c ? fill(W.open_now, {id: c.id, seed: c.seed})
    + (c.open ? "" : " (" + W.closed + ")") : W.none;
  document.getElementById("rejected").textContent = W.refused + ": " + d.rejected;
  const t = document.getElementById("entries");
  t.replaceChildren();
  row(t, ["#", W.name, W.score, W.frames, W.edition, ""], "th");
  for (const e of d.entries) {
    const acts = document.createElement("span");
    if (!e.hidden) acts.appendChild(button(W.hide, () => post("/api/hide", {entry: e.entry})));
    acts.appendChild(button(W.show, () => post("/api/show", {entry: e.entry})));
    acts.appendChild(button(W.rename, () => {
      const name = prompt(W.rename_prompt, e.name);
      if (name !== null) post("/api/rename", {entry: e.entry, name: name});
    }));
    const tr = row(t, [e.entry, e.name, e.score, e.frames, e.edition, acts]);
    if (e.hidden) { tr.className = "hidden"; tr.title = W.hidden; }
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
<div id="qr">$qr</div><p id="join">$join</p>
<p id="settings"></p><p id="rejected"></p>
<div id="replay" hidden><div id="replay-name"></div><div id="replay-summary"></div>
<code id="replay-code"></code><a id="replay-link"></a></div></div>
<div id="board-box"><table id="board"></table></div></div>""")

LECTURER_BODY = Template("""<h1>$title</h1>
<p><a id="projector" href="/projector?key=$key" target="_blank">$projector</a> ·
<a id="export" download>$export</a></p>
<h2>$open</h2>
<form id="open">
<label for="n_atoms">$atoms</label><input id="n_atoms" type="number" min="2" max="400" value="49">
<label for="radius">$radius</label><input id="radius" type="number" min="1" max="40" step="any"
 value="12">
<label for="escape">$escape</label><select id="escape"><option>rim</option><option>knife</option>
</select>
<label for="seed">$seed</label><input id="seed" type="number" min="0">
<label for="minutes">$minutes</label><input id="minutes" type="number" min="1" step="any">
<label for="attempts">$attempts</label><input id="attempts" type="number" min="1">
<label for="lost">$lost</label><input id="lost" type="checkbox">
<span></span><button>$open</button></form>
<p><button id="close">$close</button></p>
<p id="status" role="status"></p><p id="current"></p><p id="rejected"></p>
<h2>$entries</h2><table id="entries"></table>""")


def source_hash(text: str) -> str:
    """A script's or style's CSP source: 'sha256-<base64 of its SHA-256>'."""
    return "'sha256-" + base64.b64encode(hashlib.sha256(text.encode()).digest()).decode() + "'"


def page_policy(script: str, style: str) -> str:
    """The policy of a page: its one script and one style, talking to this server only."""
    return (
        f"default-src 'none'; script-src {source_hash(SCRIPT_COMMON + script)}; "
        f"style-src {source_hash(style)}; connect-src 'self'; base-uri 'none'; "
        "form-action 'none'; frame-ancestors 'none'"
    )


PROJECTOR_POLICY = page_policy(SCRIPT_PROJECTOR, STYLE_PROJECTOR)
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


def game_page() -> tuple[str, str]:
    """The browser edition with the class marker before </head>, and its policy: the
    built page's, talking to this server only (from a file it talks to nothing), its
    inline scripts allowed by their hashes instead of 'unsafe-inline'."""
    text = (resources.files("evapcool") / "web" / "evapcool.html").read_text("utf-8")
    at = text.find("</head>")
    meta = META_POLICY.search(text)
    if at < 0 or meta is None or "connect-src 'none'" not in meta.group(2):
        raise ValueError("evapcool.html has no </head> or no connect-src 'none' policy")
    hashes = " ".join(source_hash(body) for body in INLINE_SCRIPT.findall(text))
    policy = meta.group(2).replace("connect-src 'none'", "connect-src 'self'")
    policy = policy.replace("script-src 'unsafe-inline'", f"script-src {hashes}")
    text = text[: meta.start(2)] + policy + text[meta.end(2) : at] + CLASS_MARKER + text[at:]
    return text, f"{policy}; base-uri 'none'; frame-ancestors 'none'"


def projector_page(
    raw: Callable[[str], str], lang: str, direction: str, join_url: str, qr_svg: str
) -> str:
    """The projector: join address and QR code, the challenge, the live leaderboard."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    join = raw("class.projector.join").replace("{url}", join_url)
    body = PROJECTOR_BODY.substitute(
        title=html.escape(raw("class.projector.title")), qr=qr_svg, join=html.escape(join)
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


def lecturer_page(raw: Callable[[str], str], lang: str, direction: str, key: str) -> str:
    """The lecturer's page: open and close a challenge, the entries, hide, rename, replay,
    export, and the projector's link with its key."""
    words = {k: raw(v) for k, v in PAGE_WORDS.items()}
    labels = {k: html.escape(raw(f"class.lecturer.{k}")) for k in LECTURER_LABELS}
    body = LECTURER_BODY.substitute(labels, key=html.escape(key))
    return page(
        lang,
        direction,
        raw("class.lecturer.title"),
        body,
        words_json(words),
        STYLE_LECTURER,
        SCRIPT_LECTURER,
    )
