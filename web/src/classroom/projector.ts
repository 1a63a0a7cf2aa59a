/**
 * The projector: the challenge's state, the live leaderboard and the replay playing, from
 * the server's event stream (the page's join address and QR code are the server's HTML).
 */
import "./projector.css";
import {
  BOARD_COLUMNS,
  ChallengeClock,
  boardCells,
  boardRows,
  rejectedText,
  replayHeading,
  row,
  settingsText,
  type Board,
  type Replay,
} from "./board";
import { byId, classBase, fill, listen, pageWords, queryParam } from "./common";
import { ProjectorDebrief } from "./debrief/projector";
import { gameOf } from "../view/debrief/model";

const words = pageWords();
const base = classBase();
const challenge = new ChallengeClock();
const key = queryParam("key");
let open = false;
let playing: string | null = null;
const query = key ? "?key=" + encodeURIComponent(key) : "";
// After the close: the class's paths (issue 36), in the main column above the replay.
const debrief = new ProjectorDebrief(
  byId("main"),
  (k, args = {}) => fill(words[k] ?? k, args),
  document.documentElement.lang,
  query,
);

function tick(): void {
  const [kind, text] = challenge.state(words);
  const box = byId("state");
  box.textContent = text;
  box.className = kind;
}

/** The game page replaying a code, in the projector's language. */
function replayAddress(code: string): string {
  const lang = encodeURIComponent(document.documentElement.lang);
  return base + "/?replay=" + encodeURIComponent(code) + "&lang=" + lang;
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
  byId("replay-head").textContent = replayHeading(words, replay, rank);
  // The code comes only with the projector's key while the challenge is open; it is
  // printed on the screen only once the challenge is closed.
  byId("replay-code").textContent = replay.code && !open ? replay.code : "";
}

function render(board: Board): void {
  open = board.open;
  challenge.take(board.info);
  tick();
  byId("settings").textContent = board.info ? settingsText(words, board.info) : "";
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
  for (const e of boardRows(board)) row(table, boardCells(e, words));
  byId("rejected").textContent = rejectedText(words, board.rejected);
  showReplay(board.replay);
  debrief.take(board);
}

setInterval(tick, 1000);
listen(base + "/api/stream" + query, (doc) => render(doc as Board));
