/**
 * The lecturer's page: open and close a challenge, the entries (hide, rename, put on the
 * projector), the export link; refreshed on every message of the event stream.
 */
import "./lecturer.css";
import {
  ChallengeClock,
  entryCells,
  entryClass,
  rejectedText,
  row,
  settingsText,
  type ChallengeInfo,
  type LecturerEntry,
} from "./board";
import {
  byId,
  classBase,
  fill,
  getJson,
  listen,
  pageWords,
  postJson,
  queryParam,
  refusalText,
  type Refusal,
} from "./common";
import { LecturerDebrief } from "./debrief/lecturer";

/** The lecturer's list as /api/entries sends it. */
interface Entries {
  challenge: ChallengeInfo | null;
  entries: LecturerEntry[];
  rejected: number;
  /** The entry on the projector (absent before any challenge). */
  showing?: number | null;
}

const words = pageWords();
const base = classBase();
const challenge = new ChallengeClock();
const token = queryParam("token") || "";
const auth = { Authorization: "Bearer " + token, "Content-Type": "application/json" };

function say(text: string): void {
  byId("status").textContent = text;
}

async function post(path: string, body: unknown): Promise<void> {
  const answer = await postJson<Refusal>(base + path, body, auth);
  say(answer.ok ? "" : refusalText(answer.body));
  await refresh();
}

/** A number box's value, or null when empty. */
function num(id: string): number | null {
  const v = byId<HTMLInputElement>(id).value.trim();
  return v === "" ? null : Number(v);
}

function button(text: string, action: () => void): HTMLButtonElement {
  const b = document.createElement("button");
  b.textContent = text;
  b.onclick = action;
  return b;
}

function tick(): void {
  const c = challenge.info;
  const [kind, text] = challenge.state(words);
  const state = kind === "open" ? " · " + text : " (" + words.closed + ")";
  byId("current").textContent = c
    ? fill(words.open_now, { id: c.id, seed: c.seed }) + state
    : words.none;
  byId("current-settings").textContent = c ? settingsText(words, c) : "";
}

/** An entry's buttons: hide or unhide, show or take off the projector, rename. */
function actions(e: LecturerEntry, showing: number | null | undefined): HTMLElement {
  const acts = document.createElement("span");
  acts.appendChild(
    e.hidden
      ? button(words.unhide, () => post("/api/hide", { entry: e.entry, hidden: false }))
      : button(words.hide, () => post("/api/hide", { entry: e.entry })),
  );
  acts.appendChild(
    e.entry === showing
      ? button(words.on_projector, () => post("/api/show", { entry: null }))
      : button(words.show, () => post("/api/show", { entry: e.entry })),
  );
  acts.appendChild(
    button(words.rename, () => {
      const name = prompt(words.rename_prompt, e.name);
      if (name !== null) void post("/api/rename", { entry: e.entry, name });
    }),
  );
  return acts;
}

async function refresh(): Promise<void> {
  const answer = await getJson<Entries>(base + "/api/entries", auth);
  if (!answer.ok) return;
  const d = answer.body;
  challenge.take(d.challenge);
  tick();
  byId<HTMLButtonElement>("close").disabled = !(challenge.info && challenge.info.open);
  byId<HTMLButtonElement>("stop").disabled = d.showing === null;
  byId("rejected").textContent = rejectedText(words, d.rejected);
  const table = byId("entries");
  table.replaceChildren();
  const head = ["rank", "name", "score", "frames", "edition"].map((k) => words[k]);
  row(table, [...head, ""], "th");
  for (const e of d.entries) {
    const tr = row(table, [...entryCells(e), actions(e, d.showing)]);
    tr.dataset.entry = String(e.entry);
    tr.className = entryClass(e, d.showing);
    if (e.hidden) tr.title = words.hidden;
  }
}

byId<HTMLFormElement>("open").onsubmit = (ev) => {
  ev.preventDefault();
  void post("/api/challenge", {
    n_atoms: num("n_atoms"),
    radius: num("radius"),
    escape: byId<HTMLSelectElement>("escape").value,
    seed: num("seed"),
    tc_exponent: Number(byId<HTMLSelectElement>("tc_law").value),
    minutes: num("minutes"),
    attempts: num("attempts"),
    lost: byId<HTMLInputElement>("lost").checked,
  });
};
// The debrief's controls (issue 36), under the entries.
const debriefBox = document.createElement("div");
byId("entries").after(debriefBox);
const debrief = new LecturerDebrief(
  debriefBox,
  (k, args = {}) => fill(words[k] ?? k, args),
  document.documentElement.lang,
  auth,
  post,
);

byId("close").onclick = () => post("/api/challenge/close", {});
byId("stop").onclick = () => post("/api/show", { entry: null });
byId<HTMLAnchorElement>("export").href =
  base + "/api/export.csv?token=" + encodeURIComponent(token);
setInterval(tick, 1000);
// The projector's key (in its link) lets this page's stream past the students' streams.
const projectorLink = byId<HTMLAnchorElement>("projector");
listen(base + "/api/stream" + new URL(projectorLink.href).search, () => {
  // Once closed, or once the lecturer has looked early: the debrief kept current.
  void refresh().then(() => {
    if (debrief.doc || (challenge.info && !challenge.info.open)) void debrief.refresh();
  });
});
