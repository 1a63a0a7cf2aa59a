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
import { byId, listen, pageWords, queryParam } from "./common";

const words = pageWords();
const challenge = new ChallengeClock();
const key = queryParam("key");
let open = false;
let playing: string | null = null;

function tick(): void {
  const [kind, text] = challenge.state(words);
  const box = byId("state");
  box.textContent = text;
  box.className = kind;
}

/** The game page replaying a code, in the projector's language. */
function replayAddress(code: string): string {
  const lang = encodeURIComponent(document.documentElement.lang);
  return "/?replay=" + encodeURIComponent(code) + "&lang=" + lang;
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
  byId("replay-head").textContent = replayHeading(words, replay);
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
  for (const e of boardRows(board)) row(table, boardCells(e));
  byId("rejected").textContent = rejectedText(words, board.rejected);
  showReplay(board.replay);
}

setInterval(tick, 1000);
const query = key ? "?key=" + encodeURIComponent(key) : "";
listen("/api/stream" + query, (doc) => render(doc as Board));
