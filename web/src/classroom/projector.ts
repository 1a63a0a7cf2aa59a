/**
 * The projector: the challenge's state, how many played, the live leaderboard a page at a
 * time, the replay playing, and on the close the podium and the debrief, from the server's
 * event stream; or a past round (?round=), reopened from the history (issue 45). The join
 * code, address and QR code are the server's HTML.
 */
import "./projector.css";
import "./projector-debrief.css";
import {
  BOARD_COLUMNS,
  ChallengeClock,
  rejectedText,
  replayHeading,
  row,
  settingsText,
  type Board,
  type Replay,
} from "./board";
import { byId, classBase, fill, getJson, listen, pageWords, queryParam } from "./common";
import { ProjectorDebrief } from "./debrief/projector";
import { present } from "./debrief/replays";
import { BoardPager, drawPodium } from "./podium";
import { readerTime } from "./times";
import { gameOf } from "../view/debrief/model";

/** Seconds each page of a long board stays up. */
const PAGE_SECONDS = 6;

const words = pageWords();
const base = classBase();
const challenge = new ChallengeClock();
const key = queryParam("key");
/** A past round reopened (its id: ?round=, or ?challenge= as the API names it), or null
 * for the live board. */
const asked = queryParam("round") ?? queryParam("challenge");
const round = asked !== null && /^\d+$/.test(asked) ? asked : null;
let playing: string | null = null;
const keyQuery = key ? "?key=" + encodeURIComponent(key) : "";
const roundQuery = round ? (keyQuery ? "&" : "?") + "challenge=" + round : "";
// After the close: the class's paths (issue 36), in the main column under the podium.
const debrief = new ProjectorDebrief(
  byId("main"),
  (k, args = {}) => fill(words[k] ?? k, args),
  document.documentElement.lang,
  keyQuery + roundQuery,
);
const pager = new BoardPager(
  byId("board-box"),
  byId<HTMLTableElement>("board"),
  byId("board-page"),
  words,
);

function tick(): void {
  const [kind, text] = challenge.state(words);
  const box = byId("state");
  box.textContent = text;
  box.className = kind;
}

/** The game page replaying a code, in the projector's language, as a presentation (no
 * buttons, no keys: "#present"). */
function replayAddress(code: string): string {
  const lang = encodeURIComponent(document.documentElement.lang);
  return base + "/?replay=" + encodeURIComponent(code) + "&lang=" + lang + "#present";
}

function showReplay(replay: Replay | null): void {
  const frame = byId<HTMLIFrameElement>("replay-frame");
  byId("replay").hidden = !replay;
  const src = replay && replay.code ? replayAddress(replay.code) : null;
  if (src !== playing) {
    playing = src;
    frame.src = src || "about:blank";
  }
  frame.hidden = !src;
  if (!replay) return;
  const rank = debrief.doc ? (gameOf(debrief.doc, replay.entry)?.rank ?? null) : null;
  // The code itself is never printed on the projector (the lecturer's page exports it).
  byId("replay-head").textContent = replayHeading(words, replay, rank);
}

function drawBoard(board: Board): void {
  const table = byId("board");
  table.replaceChildren();
  const cols = document.createElement("colgroup");
  for (const c of BOARD_COLUMNS) {
    const col = document.createElement("col");
    col.className = c;
    cols.appendChild(col);
  }
  table.appendChild(cols);
  row(
    table,
    BOARD_COLUMNS.map((c) => words[c]),
    "th",
  );
  pager.take(board.entries, (cells) => row(table, cells));
}

function render(board: Board): void {
  challenge.take(board.info);
  tick();
  const head = byId("round-head");
  head.hidden = !round;
  head.textContent = round ? fill(words["console.projector.round"], { n: round }) : "";
  byId("settings").textContent = board.info ? settingsText(words, board.info) : "";
  const n = board.players ?? board.entries.length;
  byId("players").textContent = fill(words["console.projector.players"], { n });
  const closed = board.challenge != null && !board.open;
  const podium = byId("podium");
  podium.hidden = !closed || board.entries.length === 0;
  drawPodium(podium, closed ? board.entries : [], words);
  byId("rejected").textContent = rejectedText(words, board.rejected);
  debrief.take(board);
  drawBoard(board);
  showReplay(board.replay);
}

/** The past rounds, each a link reopening it here; the live board's link first. */
async function showRounds(): Promise<void> {
  const box = byId("rounds");
  if (!box.hidden) {
    box.hidden = true;
    return;
  }
  type Round = { id: number; students: number; games: number; closes_at: number | null };
  const got = await getJson<{ rounds: Round[] }>(base + "/api/rounds" + keyQuery);
  const list = byId("rounds-list");
  list.replaceChildren();
  const link = (text: string, href: string) => {
    const li = document.createElement("li");
    const a = document.createElement("a");
    a.textContent = text;
    a.href = href;
    li.append(a);
    list.append(li);
    return a;
  };
  link(words["console.projector.live"], base + "/projector" + keyQuery).id = "round-live";
  const rounds = got.ok ? got.body.rounds : [];
  for (const r of rounds) {
    const text = fill(words["console.projector.round_line"], { n: r.id, ...r });
    const sep = keyQuery ? "&" : "?";
    const a = link(text, base + "/projector" + keyQuery + sep + "round=" + r.id);
    a.dataset.round = String(r.id);
    // When it ended, in the room's language and the projector's time zone.
    if (r.closes_at !== null) a.append(" · ", readerTime(r.closes_at));
  }
  if (!rounds.length) {
    const li = document.createElement("li");
    li.textContent = words["console.projector.none"];
    list.append(li);
  }
  box.hidden = false;
}

/** The light high-contrast theme (a bright room), remembered on this computer. */
function setTheme(light: boolean): void {
  document.body.classList.toggle("light", light);
  byId("theme").setAttribute("aria-pressed", String(light));
  try {
    localStorage.setItem("evapcool-projector-theme", light ? "light" : "dark");
  } catch {
    /* no storage: this visit only */
  }
}

function savedLight(): boolean {
  try {
    return localStorage.getItem("evapcool-projector-theme") === "light";
  } catch {
    return false;
  }
}

present(byId<HTMLIFrameElement>("replay-frame"));
setTheme(savedLight());
byId("theme").addEventListener("click", () => setTheme(!document.body.classList.contains("light")));
byId("history").addEventListener("click", () => void showRounds());
/** The join address on one line: its type shrinks to fit (down to the projector's least
 * size, 24 px at 1080p), and only an address longer than that still breaks. */
function fitAddress(): void {
  const address = document.querySelector<HTMLElement>("#join .address");
  const line = address?.parentElement;
  if (!address || !line) return;
  address.style.fontSize = "";
  address.classList.remove("wraps");
  const small = getComputedStyle(document.documentElement).getPropertyValue("--small").trim();
  const least = parseFloat(small) * (small.endsWith("vh") ? innerHeight / 100 : 1) || 0;
  let size = parseFloat(getComputedStyle(address).fontSize);
  while (address.offsetWidth > line.clientWidth && size * 0.95 >= least) {
    size *= 0.95;
    address.style.fontSize = `${size}px`;
  }
  if (address.offsetWidth > line.clientWidth) address.classList.add("wraps");
}
fitAddress();
window.addEventListener("resize", () => {
  pager.layout();
  fitAddress();
});
setInterval(() => pager.next(), PAGE_SECONDS * 1000);
if (round) {
  document.body.classList.add("past");
  void getJson<Board>(base + "/api/leaderboard" + keyQuery + roundQuery).then((got) => {
    if (got.ok) render(got.body);
  });
} else {
  setInterval(tick, 1000);
  listen(base + "/api/stream" + keyQuery, (doc) => render(doc as Board));
}
