/**
 * Class mode (issue 22): the page served by `evapcool class` carries a marker
 * (`<script id="evapcool-class">{"api":"/api"}</script>`); the student picks a display name,
 * plays the open challenge's settings and seed, and each win's replay code is sent to the
 * server, which replays it and ranks only verified results. The page from a file has no
 * marker and never talks to anything.
 */
import { activeTranslator, t } from "../i18n";
import type { Recording, ReplaySettings } from "../game/replay";

export interface Challenge {
  id: number;
  settings: ReplaySettings;
  seed: number;
  max_frames: number;
  attempts: number | null;
  /** When the challenge closes (ISO 8601), or null. */
  closes_at: string | null;
}

export interface ClassHost {
  notify(text: string): void;
  say(text: string): void;
  /** Play this challenge from now on (its settings and seed at every restart). */
  play(challenge: Challenge): void;
  /** Called with each win's code. */
  readonly onCode: Array<(code: string, rec: Recording) => void>;
}

/** The class marker's API base, or null (the page from a file: no class mode). */
export function classApi(doc: Document): string | null {
  const el = doc.getElementById("evapcool-class");
  if (!el) return null;
  try {
    const api = (JSON.parse(el.textContent ?? "") as { api?: unknown }).api;
    return typeof api === "string" && api.startsWith("/") ? api : null;
  } catch {
    return null;
  }
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

const TOKEN_KEY = "evapcool.class.player";
const POLL_MS = 5000;

export class ClassMode {
  challenge: Challenge | null = null;
  player: { token: string; name: string } | null = null;
  /** Verified results of this visit: [score, rank]. */
  readonly verified: Array<{ score: number; rank: number }> = [];
  private form: HTMLFormElement | null = null;

  constructor(
    private readonly api: string,
    private readonly host: ClassHost,
    private readonly root: HTMLElement,
    private readonly storage: Storage | null,
  ) {
    host.onCode.push((code) => void this.submit(code));
  }

  /** Find the open challenge (waiting for one if none), then ask for a name if none yet. */
  async start(): Promise<void> {
    this.player = this.storedPlayer();
    await this.findChallenge();
    if (!this.player) this.askName();
    else this.host.notify(t("page.class_playing_as", { name: this.player.name }));
  }

  private async findChallenge(): Promise<void> {
    for (let first = true; ; first = false) {
      try {
        const res = await fetch(`${this.api}/challenge`, {
          cache: "no-store",
          headers: speaking(),
        });
        if (res.ok) {
          this.challenge = (await res.json()) as Challenge;
          this.host.play(this.challenge);
          return;
        }
        if (first) this.host.notify(t("page.class_waiting", { problem: await refusal(res) }));
      } catch {
        if (first) this.host.notify(t("page.class_no_answer"));
      }
      await new Promise((resolve) => setTimeout(resolve, POLL_MS));
    }
  }

  private storedPlayer(): { token: string; name: string } | null {
    try {
      const doc = JSON.parse(this.storage?.getItem(TOKEN_KEY) ?? "null") as unknown;
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
    const form = document.createElement("form");
    form.id = "join";
    const label = document.createElement("label");
    label.textContent = t("page.class_name_label");
    const input = document.createElement("input");
    input.name = "name";
    input.maxLength = 24;
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
      this.storage?.setItem(TOKEN_KEY, JSON.stringify(this.player));
      this.form?.remove();
      this.form = null;
      this.host.notify(t("page.class_joined", { name: this.player.name }));
    } catch {
      status.textContent = t("page.class_try_again");
    }
  }

  /** Send a win's code; the server answers once it has replayed and stored it. */
  async submit(code: string): Promise<void> {
    const c = this.challenge;
    const p = this.player;
    if (!c || !p) {
      this.host.notify(t("page.class_join_first"));
      return;
    }
    this.host.say(t("page.class_sending"));
    try {
      const res = await fetch(`${this.api}/submit`, {
        method: "POST",
        headers: {
          ...speaking(),
          "content-type": "application/json",
          authorization: `Bearer ${p.token}`,
        },
        body: JSON.stringify({ challenge: c.id, code }),
      });
      if (!res.ok) {
        this.host.notify(t("page.class_refused", { problem: await refusal(res) }));
        return;
      }
      const got = (await res.json()) as { score: number; rank: number };
      this.verified.push({ score: got.score, rank: got.rank });
      this.host.notify(t("page.class_verified", { n: got.score, rank: got.rank }));
    } catch {
      this.host.notify(t("page.class_kept"));
    }
  }
}
