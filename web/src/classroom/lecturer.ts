/**
 * The lecturer's page: the round (open, its countdown, close), the debrief's controls,
 * the students as a live ranked table (attempts, best, hide and undo, rename inline, put
 * on the projector), a new round (confirmed when it would close an open one), export and
 * print; refreshed on every message of the event stream.
 *
 * The page signs its calls with the session's cookie and the CSRF token the server wrote in
 * the page (data-csrf); the token itself never appears in the page or its address.
 */
import "./lecturer.css";
import {
  ChallengeClock,
  clock,
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
  refusalText,
  type Refusal,
} from "./common";
import { LecturerDebrief } from "./debrief/lecturer";
import { showRounds } from "./pastrounds";
import { studentRows, type StudentRow } from "./students";

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
const csrf = document.body.dataset["csrf"] ?? "";
const auth = { "Content-Type": "application/json", "X-Evapcool-CSRF": csrf };
/** The entry whose name is being edited (the table is not redrawn under the lecturer). */
let renaming: number | null = null;

function say(text: string): void {
  byId("status").textContent = text;
}

async function post(path: string, body: unknown): Promise<boolean> {
  const answer = await postJson<Refusal>(base + path, body, auth);
  say(answer.ok ? "" : refusalText(answer.body));
  await refresh();
  return answer.ok;
}

/** A number box's value, or null when empty. */
function num(id: string): number | null {
  const v = byId<HTMLInputElement>(id).value.trim();
  return v === "" ? null : Number(v);
}

function button(text: string, action: () => void, cls = ""): HTMLButtonElement {
  const b = document.createElement("button");
  b.type = "button";
  b.textContent = text;
  if (cls) b.className = cls;
  b.onclick = action;
  return b;
}

function tick(): void {
  const c = challenge.info;
  const [kind] = challenge.state(words);
  // The round's line with its state; below it, large, only what the line does not say:
  // the time left, or the final results.
  const state = kind === "open" ? " · " + words.open : " (" + words.closed + ")";
  byId("current").textContent = c
    ? fill(words.open_now, { id: c.id, seed: c.seed }) + state
    : words.none;
  const countdown = byId("countdown");
  const left = challenge.secondsLeft();
  const time = left === null ? "" : fill(words.closes_in, { time: clock(Math.max(0, left)) });
  countdown.textContent = c ? (kind === "open" ? time : words.final) : "";
  countdown.className = kind;
  byId("current-settings").textContent = c ? settingsText(words, c) : "";
}

/** A student's buttons: hide or undo, show on or take off the projector, rename. */
function actions(r: StudentRow, showing: number | null | undefined): HTMLElement {
  const e = r.best;
  const acts = document.createElement("span");
  acts.className = "row-actions";
  acts.appendChild(
    e.hidden
      ? button(words.unhide, () => void post("/api/hide", { entry: e.entry, hidden: false }))
      : button(words.hide, () => void post("/api/hide", { entry: e.entry })),
  );
  acts.appendChild(
    e.entry === showing
      ? button(words.on_projector, () => void post("/api/show", { entry: null }), "on")
      : button(words.show, () => void post("/api/show", { entry: e.entry })),
  );
  acts.appendChild(
    button(words.rename, () => {
      renaming = e.entry;
      void refresh();
    }),
  );
  return acts;
}

/** The name cell: the name, or while renaming a box with Save and Cancel (Enter, Escape). */
function nameCell(e: LecturerEntry): HTMLElement {
  const box = document.createElement("span");
  if (renaming !== e.entry) {
    box.textContent = e.name;
    return box;
  }
  // One box per rename, moved into each redrawn table (two refreshes may overlap):
  // what the lecturer typed, and the focus, survive the redraw.
  const fresh = renameBox?.entry !== e.entry;
  if (fresh) renameBox = renameForm(e);
  const { form, input } = renameBox as RenameBox;
  const focused = document.activeElement === input;
  const [from, to] = [input.selectionStart, input.selectionEnd];
  box.append(form);
  queueMicrotask(() => {
    if (!fresh && !focused) return;
    input.focus();
    if (!fresh) input.setSelectionRange(from, to);
  });
  return box;
}

interface RenameBox {
  readonly entry: number;
  readonly form: HTMLFormElement;
  readonly input: HTMLInputElement;
}
let renameBox: RenameBox | null = null;

function renameForm(e: LecturerEntry): RenameBox {
  const form = document.createElement("form");
  form.className = "rename";
  const input = document.createElement("input");
  input.value = e.name;
  input.setAttribute("aria-label", words.rename_prompt);
  const done = (): void => {
    renaming = renameBox = null;
    void refresh();
  };
  form.onsubmit = (ev) => {
    ev.preventDefault();
    renaming = renameBox = null;
    void post("/api/rename", { entry: e.entry, name: input.value });
  };
  input.onkeydown = (ev) => {
    if (ev.key === "Escape") done();
  };
  // A submit button alone: Enter and a click each submit once (no second post).
  const save = button(words["console.lecturer.save"], () => undefined, "primary");
  save.type = "submit";
  form.append(input, save, button(words["console.lecturer.cancel"], done));
  return { entry: e.entry, form, input };
}

async function refresh(): Promise<void> {
  const answer = await getJson<Entries>(base + "/api/entries", auth);
  if (!answer.ok) return;
  const d = answer.body;
  challenge.take(d.challenge);
  tick();
  byId<HTMLButtonElement>("close").disabled = !(challenge.info && challenge.info.open);
  byId<HTMLButtonElement>("stop").disabled = d.showing === null || d.showing === undefined;
  byId("rejected").textContent = rejectedText(words, d.rejected);
  const table = byId("entries");
  table.replaceChildren();
  const heads = ["rank", "name", "score", "console.lecturer.attempts", "frames", "edition"];
  const head = document.createElement("thead");
  table.append(head);
  const labels = [...heads.map((k) => words[k]), ""];
  row(head, labels, "th");
  const body = document.createElement("tbody");
  table.append(body);
  for (const r of studentRows(d.entries)) {
    const e = r.best;
    const cells = [e.rank ?? "", nameCell(e), e.score, r.attempts, e.frames, e.edition];
    const tr = row(body, [...cells, actions(r, d.showing)]);
    tr.dataset.entry = String(e.entry);
    // Each cell names its column: a phone shows the row as a card (console.css).
    [...tr.cells].forEach((td, i) => (td.dataset.label = labels[i] ?? ""));
    tr.className = [e.hidden ? "hidden" : "", e.entry === d.showing ? "showing" : ""].join(" ");
    if (e.hidden) tr.title = words.hidden;
  }
  if (d.entries.length === 0) {
    const td = row(body, [words["console.lecturer.no_games"]]).firstElementChild;
    td?.setAttribute("colspan", "7");
  }
}

/** The new round's settings from the form. */
function newRound(): unknown {
  return {
    n_atoms: num("n_atoms"),
    radius: num("radius"),
    escape: byId<HTMLSelectElement>("escape").value,
    seed: num("seed"),
    tc_exponent: Number(byId<HTMLSelectElement>("tc_law").value),
    minutes: num("minutes"),
    attempts: num("attempts"),
    lost: byId<HTMLInputElement>("lost").checked,
  };
}

/** The confirmation asked before a new round closes the open one. */
function confirmDialog(): HTMLDialogElement {
  const dialog = document.createElement("dialog");
  dialog.id = "confirm";
  const title = document.createElement("h2");
  title.textContent = words["console.lecturer.confirm_title"];
  const text = document.createElement("p");
  text.textContent = words["console.lecturer.confirm_text"];
  const form = document.createElement("form");
  form.method = "dialog";
  const go = document.createElement("button");
  go.value = "go";
  go.className = "primary danger";
  go.id = "confirm-go";
  go.textContent = words["console.lecturer.confirm_go"];
  const cancel = document.createElement("button");
  cancel.value = "cancel";
  cancel.id = "confirm-cancel";
  cancel.textContent = words["console.lecturer.cancel"];
  form.append(cancel, go);
  dialog.append(title, text, form);
  dialog.setAttribute("aria-labelledby", "confirm-title");
  title.id = "confirm-title";
  document.body.append(dialog);
  return dialog;
}

const confirm = confirmDialog();
byId<HTMLFormElement>("open").onsubmit = (ev) => {
  ev.preventDefault();
  const body = newRound();
  if (!(challenge.info && challenge.info.open)) {
    void post("/api/challenge", body);
    return;
  }
  confirm.returnValue = "";
  confirm.onclose = () => {
    if (confirm.returnValue === "go") void post("/api/challenge", body);
  };
  confirm.showModal();
};
// The debrief's controls above the table, its charts below it (issue 45).
const debrief = new LecturerDebrief(
  byId("debrief-slot"),
  (k, args = {}) => fill(words[k] ?? k, args),
  document.documentElement.lang,
  auth,
  post,
  byId("table-box"),
);

byId("close").onclick = () => void post("/api/challenge/close", {});
byId("stop").onclick = () => void post("/api/show", { entry: null });
byId("print").onclick = () => window.print();
byId<HTMLAnchorElement>("export").href = base + "/api/export.csv";
setInterval(tick, 1000);
// The projector's key (in its link) lets this page's stream past the students' streams.
const projectorLink = byId<HTMLAnchorElement>("projector");
// The past rounds: at the start, and again when a round closes or a new one opens.
let roundsSeen: string | null = null;
async function refreshRounds(): Promise<void> {
  const c = challenge.info;
  const now = c ? `${c.id}:${c.open}` : "";
  if (now === roundsSeen) return;
  roundsSeen = now;
  await showRounds(words, base, projectorLink.href);
}
listen(base + "/api/stream" + new URL(projectorLink.href).search, () => {
  if (renaming !== null) return; // the box being typed in stays; the next message redraws
  // Once closed, or once the lecturer has looked early: the debrief kept current.
  void refresh().then(() => {
    void refreshRounds();
    if (debrief.doc || (challenge.info && !challenge.info.open)) void debrief.refresh();
  });
});
