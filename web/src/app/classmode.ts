/**
 * Class mode (issue 22): the page served by `evapcool class` carries a marker
 * (`<script id="evapcool-class">{"api":"/api"}</script>`); the student picks a display name,
 * plays the open challenge's settings and seed, and each win's replay code is sent to the
 * server, which replays it and ranks only verified results. The page from a file has no
 * marker and never talks to anything.
 * Python's twin: `src/evapcool/app/classmode.py` (docs/twins.md).
 */
import { activeTranslator, t } from "../i18n";
import type { Recording, ReplaySettings } from "../game/replay";
import { encode } from "../game/replaycode";
import { gamePath, type GamePath } from "../game/path";
import type { SimFactory } from "../game/rules";
import { rect } from "../view/geometry";
import { PathPanel } from "../view/panels";

export interface Challenge {
  id: number;
  settings: ReplaySettings;
  seed: number;
  max_frames: number;
  attempts: number | null;
  /** When the challenge closes (ISO 8601), or null. */
  closes_at: string | null;
  /** Lost games count too (sent, ranked with 0 atoms). */
  lost?: boolean;
}

/** A challenge as the leaderboard's stream tells every page: open or not, seconds left. */
export interface ChallengeState extends Challenge {
  open: boolean;
  /** Seconds left in its window when the server sent it, or null (no window). */
  closes_in: number | null;
}

/** The leaderboard document of the server's stream (docs/class.md); a joined student's
 * stream holds their own row alone in `entries` and counts the board in `players`. */
export interface Board {
  info: ChallengeState | null;
  players?: number;
  /** name: null in the debrief's anonymous mode. */
  entries: Array<{
    rank: number;
    /** The entry's id: a student's page finds its own row by it, never by name. */
    entry?: number;
    name: string | null;
    score: number;
    frames: number;
  }>;
  debrief?: { anonymous: boolean };
}

/** What the student's page reads of the server's debrief (docs/class.md). */
interface ClassDebrief {
  law: { n0: number; tc0: number; exponent: number; t0: number };
  games: Array<{ entry: number; frames: number; path: { n: number[]; t: number[] } | null }>;
  you: { entry: number; rank: number } | null;
}

/** A student's standing in the current challenge, as /api/me and /api/submit answer. */
interface Standing {
  challenge: number | null;
  attempts?: number | null;
  used?: number;
  best?: number | null;
  /** The best game's entry (its row on the board), its place, and students ranked. */
  best_entry?: number | null;
  rank?: number | null;
  count?: number;
}

export interface ClassHost {
  notify(text: string): void;
  say(text: string): void;
  /** Play this challenge from now on (its settings and seed at every restart). */
  play(challenge: Challenge): void;
  /** Called with each win's code. */
  readonly onCode: Array<(code: string, rec: Recording) => void>;
  /** Called with each game lost for good (sent when the challenge counts lost games). */
  readonly onLost?: Array<(rec: Recording) => void>;
  /** The page's engine: the debrief draws the student's own game's path from it. */
  readonly factory?: SimFactory;
}

/** The class marker's API base, or null (the page from a file: no class mode). */
export function classApi(doc: Document): string | null {
  return marker(doc)?.api ?? null;
}

/** The server's longest name (its marker says; the name box takes no more). */
export function classNameMax(doc: Document): number {
  return marker(doc)?.nameMax ?? 24;
}

function marker(doc: Document): { api: string; nameMax: number } | null {
  const el = doc.getElementById("evapcool-class");
  if (!el) return null;
  try {
    const m = JSON.parse(el.textContent ?? "") as { api?: unknown; name_max?: unknown };
    if (typeof m.api !== "string" || !m.api.startsWith("/")) return null;
    const n = m.name_max;
    return { api: m.api, nameMax: typeof n === "number" && n >= 1 && n <= 100 ? n : 24 };
  } catch {
    return null;
  }
}

/** Times a game is sent again while the server answers 503 (its database away): about two
 * minutes at the server's 5 s. */
const STORE_AWAY_RESENDS = 24;

/** Seconds to wait before sending again, from a Retry-After header (1 to 30; 5 if none). */
function waitAsked(header: string | null): number {
  const asked = Number(header);
  return Number.isFinite(asked) && asked >= 1 ? Math.min(Math.round(asked), 30) : 5;
}

/** A refusal's message from the server's JSON error, or the HTTP status. */
async function refusal(res: Response): Promise<string> {
  try {
    const body = (await res.json()) as { error?: { field?: string; message?: string } };
    if (body.error?.message) return body.error.message;
  } catch {
    /* not JSON */
  }
  return t("page.class_status", { status: res.status });
}

/** The server's refusals in the page's language, not only the browser's. */
const speaking = (): Record<string, string> => ({ "accept-language": activeTranslator().locale });

/** The saved student, one per class: this origin's class at its API path (a student of two
 * classes of one server is herself in each). The single class's was kept under the bare key. */
const TOKEN_KEY = "evapcool.class.player";
export const tokenKey = (api: string): string =>
  api === "/api" ? TOKEN_KEY : `${TOKEN_KEY}:${api}`;
/** Without the stream (refused or gone), the board is asked for this often, ms. */
const POLL_MS = 3000;

/** m:ss of a number of seconds (rounded up: "0:00" only at the end). */
export function clock(seconds: number): string {
  const s = Math.max(0, Math.ceil(seconds));
  return `${Math.floor(s / 60)}:${String(s % 60).padStart(2, "0")}`;
}

/**
 * The student's side of a class competition: the challenge's state from the server's
 * stream (open with its countdown, closed with the final place), attempts left before and
 * after each game, the last game's verified score and the best and place, kept current
 * from the board; in the class bar, never over the cup (a tall screen's band under the
 * scene, else over the title row).
 */
export class ClassMode {
  challenge: ChallengeState | null = null;
  player: { token: string; name: string } | null = null;
  /** Games of this challenge sent and accepted; the best score, its entry and place, of
   * how many ranked. */
  used = 0;
  best: number | null = null;
  bestEntry: number | null = null;
  rank: number | null = null;
  ranked = 0;
  /** The last game's result: [text, "ok" | "bad" | ""]. */
  result: [string, string] = ["", ""];
  private received = 0;
  /** The event stream, once the student has joined; whether the board is being polled. */
  private events: EventSource | null = null;
  private polling = false;
  private form: HTMLFormElement | null = null;
  readonly bar: HTMLElement;
  private readonly stateLine: HTMLElement;
  private readonly resultLine: HTMLElement;
  /** After the close: the student's best path over the class's cloud, and their place. */
  debrief: HTMLElement | null = null;
  private debriefKey = "";
  /** This challenge's games the server took, by entry: the page's own paths of them. */
  private readonly sent = new Map<number, Recording>();
  /** The path this page computed of its best game for the debrief (equal to the server's). */
  ownPath: GamePath | null = null;

  constructor(
    private readonly api: string,
    private readonly host: ClassHost,
    private readonly root: HTMLElement,
    private readonly storage: Storage | null,
    private readonly nameMax = 24,
    /** Where the bar goes, CSS px from the top, for its height (a tall screen's band
     * above the slider; else 0). */
    private readonly barTop: (height: number) => number = () => 0,
  ) {
    host.onCode.push((code, rec) => void this.submit(code, rec));
    host.onLost?.push((rec) => void this.submitLost(rec));
    this.bar = document.createElement("div");
    this.bar.id = "classbar";
    this.bar.setAttribute("role", "status");
    this.stateLine = document.createElement("p");
    this.resultLine = document.createElement("p");
    this.bar.append(this.stateLine, this.resultLine);
    root.append(this.bar);
  }

  /** Follow the challenge (the stream), else read the board once and ask for a name. */
  async start(): Promise<void> {
    this.player = this.storedPlayer();
    this.render();
    setInterval(() => this.render(), 1000);
    window.addEventListener("resize", () => this.render());
    if (!this.player) {
      void this.look();
      this.askName();
    } else {
      this.follow();
      this.host.notify(t("page.class_playing_as", { name: this.player.name }));
      await this.refreshStanding();
    }
  }

  /** The board from the server's event stream, opened with the student's token (a hall
   * behind one address streams within each token's bound, not the address's); by polling
   * if the stream is refused. */
  private follow(): void {
    if (typeof EventSource === "undefined") return void this.poll();
    this.events?.close();
    const token = this.player ? `?token=${encodeURIComponent(this.player.token)}` : "";
    const events = new EventSource(`${this.api}/stream${token}`);
    this.events = events;
    events.onmessage = (e) => this.take(JSON.parse(String(e.data)) as Board);
    events.onerror = () => {
      if (events.readyState === EventSource.CLOSED && this.events === events) void this.poll();
    };
  }

  /** The board once: what a page shows before its student joins. */
  private async look(): Promise<boolean> {
    try {
      const auth: Record<string, string> = this.player
        ? { authorization: `Bearer ${this.player.token}` }
        : {};
      const res = await fetch(`${this.api}/leaderboard`, { cache: "no-store", headers: auth });
      if (res.ok) this.take((await res.json()) as Board);
      return true;
    } catch {
      return false;
    }
  }

  private async poll(): Promise<void> {
    if (this.polling) return;
    this.polling = true;
    for (;;) {
      if (!(await this.look())) {
        this.result = [t("page.class_no_answer"), "bad"];
        this.render();
      }
      await new Promise((resolve) => setTimeout(resolve, POLL_MS));
    }
  }

  /** A board from the server: a new challenge is played from now on; the standing follows. */
  take(board: Board): void {
    const info = board.info;
    this.received = Date.now();
    const fresh = info !== null && info.open && info.id !== this.challenge?.id;
    this.challenge = info;
    if (fresh) {
      [this.used, this.best, this.rank, this.result] = [0, null, null, ["", ""]];
      this.bestEntry = null;
      this.sent.clear();
      this.host.play(info);
      void this.refreshStanding();
    }
    // Found by its entry, never by name: names may be hidden (anonymous) or shared.
    const mine = board.entries.find((e) => e.entry !== undefined && e.entry === this.bestEntry);
    if (mine) [this.best, this.rank] = [mine.score, mine.rank];
    else if (this.bestEntry !== null) this.rank = null; // hidden by the lecturer
    this.ranked = board.players ?? board.entries.length;
    this.render();
    const closed = info !== null && !info.open;
    const key = closed ? `${info.id}:${board.debrief?.anonymous}:${this.ranked}` : "";
    if (key !== this.debriefKey) {
      this.debriefKey = key;
      if (closed) void this.showDebrief();
      else this.closeDebrief();
    }
  }

  /** The debrief, once the challenge is closed: the student's own path over the cloud. */
  private async showDebrief(): Promise<void> {
    const p = this.player;
    if (!p) return;
    try {
      const res = await fetch(`${this.api}/debrief`, {
        cache: "no-store",
        headers: { ...speaking(), authorization: `Bearer ${p.token}` },
      });
      if (res.ok) this.drawDebrief((await res.json()) as ClassDebrief);
    } catch {
      /* the debrief is a look back: the game goes on without it */
    }
  }

  /** The student's best path (from this page's own replay of it, when the page sent it:
   * the server's is the same, same engine and frames) over the class's, and their place. */
  private drawDebrief(doc: ClassDebrief): void {
    const mine = doc.games.find((g) => g.entry === doc.you?.entry);
    const rec = mine && this.sent.get(mine.entry);
    if (mine && rec && this.host.factory) {
      this.ownPath = gamePath(rec, this.host.factory, mine.frames);
      mine.path = this.ownPath;
    }
    const others = doc.games.filter((g) => g !== mine && g.path);
    const panel = this.debriefPanel();
    const you = panel.querySelector("#debrief-you")!;
    you.textContent = doc.you
      ? t("page.class_debrief_you", { rank: doc.you.rank, count: doc.games.length })
      : t("page.class_debrief_you_none");
    const canvas = panel.querySelector("canvas")!;
    canvas.setAttribute("aria-label", you.textContent);
    canvas.dataset.curves = [...others, ...(mine?.path ? [mine] : [])]
      .map((g) => g.entry)
      .join(",");
    const chart = new PathPanel();
    chart.showClass(
      doc.law,
      mine?.path ?? { n: [], t: [] },
      others.map((g) => g.path!),
    );
    const draw = () => {
      const dpr = window.devicePixelRatio || 1;
      const [w, h] = [canvas.clientWidth, canvas.clientHeight];
      [canvas.width, canvas.height] = [Math.round(w * dpr), Math.round(h * dpr)];
      const ctx = canvas.getContext("2d");
      if (!ctx || w === 0) return;
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      chart.draw(ctx, rect(0, 0, w, h));
    };
    draw();
    window.addEventListener("resize", draw);
  }

  private debriefPanel(): HTMLElement {
    if (this.debrief) return this.debrief;
    const panel = document.createElement("div");
    panel.id = "class-debrief";
    const close = document.createElement("button");
    close.type = "button";
    close.textContent = t("button.close");
    close.addEventListener("click", () => this.closeDebrief());
    const title = document.createElement("h2");
    title.textContent = t("page.class_debrief_title");
    // The title and its close button side by side, a gap between (either direction).
    const head = document.createElement("header");
    head.append(title, close);
    const you = document.createElement("p");
    you.id = "debrief-you";
    const canvas = document.createElement("canvas");
    canvas.id = "debrief-paths";
    canvas.setAttribute("role", "img");
    panel.append(head, you, canvas);
    panel.addEventListener("keydown", (ev) => ev.stopPropagation()); // not the game's keys
    this.root.append(panel);
    this.debrief = panel;
    return panel;
  }

  private closeDebrief(): void {
    this.debrief?.remove();
    this.debrief = null;
  }

  /** Whether the challenge takes games now (open, its window not over). */
  get open(): boolean {
    const c = this.challenge;
    return c !== null && c.open && this.secondsLeft() !== 0;
  }

  /** Seconds left in the window (null: none), counted from the board's arrival. */
  secondsLeft(): number | null {
    const left = this.challenge?.closes_in;
    if (left === null || left === undefined) return null;
    return Math.max(0, left - (Date.now() - this.received) / 1000);
  }

  /** Attempts left, or null (no limit). */
  get attemptsLeft(): number | null {
    const limit = this.challenge?.attempts;
    return typeof limit === "number" ? Math.max(0, limit - this.used) : null;
  }

  /** The class bar: the challenge's state and attempts; the last result and the standing. */
  render(): void {
    const c = this.challenge;
    const parts: string[] = [];
    if (c === null) parts.push(t("page.class_no_challenge"));
    else if (!this.open) parts.push(t("page.class_final"));
    else {
      parts.push(t("page.class_open"));
      const left = this.secondsLeft();
      if (left !== null) parts.push(t("page.class_time_left", { time: clock(left) }));
      const attempts = this.attemptsLeft;
      if (attempts !== null) parts.push(t("page.class_attempts_left", { n: attempts }));
    }
    this.stateLine.textContent = parts.join(" · ");
    const standing =
      this.best === null || this.rank === null
        ? c === null
          ? ""
          : t("page.class_no_best")
        : this.ranked > 0
          ? t("console.student.best_of", { n: this.best, rank: this.rank, count: this.ranked })
          : t("page.class_best", { n: this.best, rank: this.rank });
    const [text, kind] = this.result;
    this.resultLine.textContent = [text, standing].filter((x) => x).join(" ");
    this.resultLine.className = kind;
    this.bar.style.top = `${this.barTop(this.bar.offsetHeight)}px`;
  }

  /** The student's games sent, best and place from the server (after a reload, a new
   * challenge); a token the server does not know asks for a name again. */
  private async refreshStanding(): Promise<void> {
    const p = this.player;
    if (!p) return;
    try {
      const res = await fetch(`${this.api}/me`, {
        cache: "no-store",
        headers: { ...speaking(), authorization: `Bearer ${p.token}` },
      });
      if (res.status === 401) {
        this.player = null;
        this.askName();
        return;
      }
      if (res.ok) this.takeStanding((await res.json()) as Standing);
    } catch {
      /* the stream's board keeps the best and place; the count comes with the next game */
    }
  }

  private takeStanding(s: Standing): void {
    if (s.challenge !== this.challenge?.id) return;
    this.used = s.used ?? this.used;
    this.best = s.best ?? null;
    this.bestEntry = s.best_entry ?? null;
    this.rank = s.rank ?? null;
    this.ranked = s.count ?? this.ranked;
    this.render();
  }

  private storedPlayer(): { token: string; name: string } | null {
    try {
      const doc = JSON.parse(this.storage?.getItem(tokenKey(this.api)) ?? "null") as unknown;
      const p = doc as { token?: unknown; name?: unknown } | null;
      return p && typeof p.token === "string" && typeof p.name === "string"
        ? { token: p.token, name: p.name }
        : null;
    } catch {
      return null;
    }
  }

  /** A small form over the page: the display name for the class's leaderboard. */
  private askName(): void {
    if (this.form) return;
    const form = document.createElement("form");
    form.id = "join";
    const label = document.createElement("label");
    label.textContent = t("page.class_name_label");
    const input = document.createElement("input");
    input.name = "name";
    input.maxLength = this.nameMax;
    input.setAttribute("autocomplete", "nickname");
    input.required = true;
    const button = document.createElement("button");
    button.type = "submit";
    button.textContent = t("page.class_join");
    const status = document.createElement("p");
    status.setAttribute("role", "status");
    label.append(input);
    form.append(label, button, status);
    form.addEventListener("submit", (ev) => {
      ev.preventDefault();
      void this.join(input.value, status);
    });
    form.addEventListener("keydown", (ev) => ev.stopPropagation()); // not the game's keys
    this.root.append(form);
    this.form = form;
    input.focus();
  }

  private async join(name: string, status: HTMLElement): Promise<void> {
    try {
      const res = await fetch(`${this.api}/join`, {
        method: "POST",
        headers: { ...speaking(), "content-type": "application/json" },
        body: JSON.stringify({ name }),
      });
      if (!res.ok) {
        status.textContent = await refusal(res);
        return;
      }
      this.player = (await res.json()) as { token: string; name: string };
      this.storage?.setItem(tokenKey(this.api), JSON.stringify(this.player));
      this.form?.remove();
      this.form = null;
      this.host.notify(t("page.class_joined", { name: this.player.name }));
      this.follow();
      await this.refreshStanding();
    } catch {
      status.textContent = t("page.class_try_again");
    }
  }

  /** One line for the last game, in the class bar (never over the cup). */
  private tell(text: string, kind: "ok" | "bad" | ""): void {
    this.result = [text, kind];
    this.render();
    this.host.say(this.resultLine.textContent ?? text);
  }

  /** A game lost for good, sent when the challenge counts lost games (cut to its frame
   * limit: the frames after it cannot win either); else kept to itself. */
  async submitLost(rec: Recording): Promise<void> {
    const c = this.challenge;
    if (!c?.lost || !this.player) return;
    const limit = c.max_frames;
    let left = limit;
    const moves: Array<[number, number]> = [];
    for (const [h, n] of rec.moves) {
      if (left <= 0) break;
      moves.push([h, Math.min(n, left)]);
      left -= Math.min(n, left);
    }
    const cut = { ...rec, moves, frames: limit - left };
    await this.submit(await encode(cut), cut, true);
  }

  /** Send a game's code (a win's; `lost`: a game lost for good); the server answers once
   * it has replayed and stored it. A game the challenge cannot take (closed, no attempts
   * left) is not sent, and says so. */
  async submit(code: string, rec?: Recording, lost = false): Promise<void> {
    const c = this.challenge;
    const p = this.player;
    if (!c || !p) return this.tell(t("page.class_join_first"), "bad");
    if (!this.open) return this.tell(t("page.class_not_sent_closed"), "bad");
    if (this.attemptsLeft === 0) return this.tell(t("page.class_not_sent_attempts"), "bad");
    this.tell(t("page.class_sending"), "");
    try {
      let res: Response;
      for (let resends = 0; ; resends++) {
        res = await fetch(`${this.api}/submit`, {
          method: "POST",
          headers: {
            ...speaking(),
            "content-type": "application/json",
            authorization: `Bearer ${p.token}`,
          },
          body: JSON.stringify({ challenge: c.id, code }),
        });
        if (res.status !== 503 || resends >= STORE_AWAY_RESENDS) break;
        // the class's database is away for a moment (a department's server): send it again
        const wait = waitAsked(res.headers.get("retry-after"));
        this.tell(t("page.class_resending", { n: wait }), "");
        await new Promise((done) => setTimeout(done, wait * 1000));
      }
      if (!res.ok) {
        const problem = await refusal(res);
        this.tell(t("page.class_refused", { problem }), "bad");
        return void this.refreshStanding();
      }
      const got = (await res.json()) as Standing & { score: number; entry: number };
      if (rec) this.sent.set(got.entry, rec);
      this.takeStanding(got);
      this.tell(
        t(lost ? "console.student.lost_counted" : "page.class_game_verified", { n: got.score }),
        "ok",
      );
    } catch {
      this.tell(t("page.class_kept"), "bad");
    }
  }
}
