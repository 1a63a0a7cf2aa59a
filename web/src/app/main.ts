/** The page's entry: storage, address options, the applet, and `window.evapcool` for scripts. */
import { haveCore, makeSimulation } from "../game/engine";
import { loadSettings } from "../game/settingsStore";
import { drawPageIcon } from "../view/icons";
import type { Layout } from "../view/geometry";
import { App } from "./app";
import { classApi, ClassMode, classNameMax } from "./classmode";
import { exposeApi } from "./api";
import { parseParams } from "./params";
import physicsWorkerCode from "../runtime/physics.worker?packed";
import { unpack } from "virtual:evapcool-unpack";
import { pageStorage, ReadOnly } from "./storage";
import { chooseLocale, onLocaleChange, STORAGE_KEY, t, useLocale, type Translator } from "../i18n";

function byId<T extends HTMLElement>(id: string): T {
  const el = document.getElementById(id);
  if (!el) throw new Error(`the page lacks #${id}`);
  return el as T;
}

/** The physics worker's script, unpacked from the page's own code into a URL of this page
 * (no file, no server), or null if no worker runs here. */
async function workerUrl(): Promise<string | null> {
  try {
    if (typeof Worker !== "function") return null;
    const code = await unpack(physicsWorkerCode);
    return URL.createObjectURL(new Blob([code], { type: "text/javascript" }));
  } catch (err) {
    console.warn(
      `evapcool: no physics worker here (${(err as Error).message}); playing without it.`,
    );
    return null;
  }
}

/** A worker of that script (the game's, or the verify panel's), or null if none starts. */
function startWorker(url: string | null, name: string): Worker | null {
  if (url === null) return null;
  try {
    return new Worker(url, { name });
  } catch (err) {
    console.warn(
      `evapcool: no physics worker here (${(err as Error).message}); playing without it.`,
    );
    return null;
  }
}

/** The browser's languages, then the address's ?lang= (the settings' "as the browser"). */
function browserLocale(): string {
  const languages = navigator.languages?.length ? navigator.languages : [navigator.language];
  return chooseLocale(languages, location.search, null);
}

/** The language menu's saved choice, if this browser keeps one. */
function savedLocale(): string | null {
  try {
    const saved = window.localStorage.getItem(STORAGE_KEY);
    return saved === "auto" ? null : saved;
  } catch {
    return null;
  }
}

/** The page's own words outside the canvas, and the text direction, in language `tr`. */
function retitle(tr: Translator): void {
  // The document's direction: the name box, the spoken lines and the notices inherit it.
  document.documentElement.lang = tr.locale;
  document.documentElement.dir = tr.direction;
  document.title = tr.t("page.doc_title");
  document.querySelector('meta[name="description"]')?.setAttribute("content", tr.t("page.about"));
  const canvas = document.getElementById("scene");
  canvas?.setAttribute("aria-label", tr.t("page.canvas_label"));
  if (canvas) canvas.textContent = tr.t("page.canvas_text");
  document.getElementById("name")?.setAttribute("aria-label", tr.t("page.name_label"));
}

async function main(): Promise<void> {
  if (!haveCore())
    throw new Error(
      "this browser cannot run the physics: it lacks DecompressionStream or WebAssembly's " +
        "SIMD (Chrome or Edge 103, Firefox 113, Safari 16.4 and newer have both)",
    );
  onLocaleChange(retitle);
  const browser = browserLocale();
  useLocale(chooseLocale([browser], "", savedLocale()));
  const notices: string[] = [];
  const kv = pageStorage(notices);
  // Read the saved settings once here only to size address options against them.
  const [saved] = loadSettings(new ReadOnly(kv));
  const params = parseParams(location.search, saved);
  // A watched replay plays in the page's own loop (its heights are fed frame by frame).
  const url = await workerUrl();
  const worker = params.replay === null ? startWorker(url, "evapcool physics") : null;
  // The inline font must be ready before the first frame measures text.
  try {
    await Promise.race([document.fonts.load("700 20px EvapSans"), sleep(500)]);
  } catch {
    /* the fallback fonts draw the same text */
  }
  const app = new App(
    {
      root: byId("app"),
      canvas: byId<HTMLCanvasElement>("scene"),
      live: byId("live"),
      status: byId("status"),
      nameInput: byId<HTMLInputElement>("name"),
    },
    {
      factory: makeSimulation,
      storage: kv,
      overrides: params.overrides,
      config: { seed: params.seed, speed: params.speed },
      notices: [...notices, ...params.notices],
      worker,
      verifyWorker: () => startWorker(url, "evapcool verify"),
      browserLocale: browser,
      setup: params,
      inClass: classApi(document) !== null && params.replay === null,
    },
  );
  await app.play.ready();
  if (params.replay !== null) {
    await app.watch(params.replay);
    // In the class projector's frame the replay plays by itself, again after each end,
    // unless the projector holds its clock (two games in step, issue 36).
    if (window.parent !== window) playOnItsOwn(app, followParent(app));
    // The projector presents it (issue 45): no "Space plays it" for a room without keys.
    if (window.parent !== window && /^#(present|in-step)$/.test(location.hash)) {
      app.notices.clear();
      app.win.startHint = false;
    }
  }
  const api = classApi(document);
  // A replay watched from the projector's link is not a student's game.
  if (api !== null && params.replay === null) startClass(app, api);
  exposeApi(app);
  setIcon();
  app.draw();
  performance.mark("evapcool-first-frame");
  app.start();
}

/** Class mode: the served page plays the open challenge and sends each win's code. */
function startClass(app: App, api: string): void {
  let storage: Storage | null = null;
  try {
    storage = window.localStorage;
  } catch {
    storage = null; // no storage: the name is asked again on each visit
  }
  const mode = new ClassMode(
    api,
    {
      notify: (t) => app.notify(t),
      say: (t) => app.say(t),
      play: (c) => app.playChallenge(c),
      onCode: app.replays.onCode,
      onLost: app.replays.onLost,
      factory: makeSimulation,
    },
    byId("app"),
    storage,
    classNameMax(document),
    (height) => barTop(app.layout, height),
  );
  app.classMode = mode;
  void mode.start();
}

/** The class bar's top for its height, CSS px: on a tall screen just above the trap
 * slider (the band under the large readout; the cup stays clear), else the title row. */
function barTop(layout: Layout, height: number): number {
  if (layout.mode !== "tall") return 0;
  const sliderTop = (layout.slider.y - layout.knobRadius) * layout.scale + layout.offsetY;
  return Math.max(0, sliderTop - height - 4);
}

/** Seconds a finished replay stays on the projector before it plays again. */
const REPLAY_PAUSE_S = 6;

/** A replay that plays without a hand on it (the projector's): unpaused, and started again
 * a few seconds after its end. */
function playOnItsOwn(app: App, driven: () => boolean): void {
  let endedAt: number | null = null;
  setInterval(() => {
    if (driven()) return;
    const g = app.game;
    const ended = g.won || g.allEscaped;
    if (ended) {
      endedAt ??= performance.now();
      if (performance.now() - endedAt > REPLAY_PAUSE_S * 1000) {
        endedAt = null;
        app.restart();
      }
    } else if (g.paused) g.togglePause();
  }, 250);
}

/** The projector's clock (same origin only: a cross-origin parent cannot reach the
 * window's properties): `evapcoolFrame(k)` shows the replay's frame k, paused, or its
 * last if it ended before; returns the frame shown and whether the game has ended. */
function followParent(app: App): () => boolean {
  // "#in-step": the projector's pair; paused on frame 0 until its clock asks for a frame.
  let driven = location.hash === "#in-step";
  const ended = () => app.game.won || app.game.allEscaped;
  const show = (k: number) => {
    if (!Number.isInteger(k) || k < 0)
      throw new RangeError(`frame must be a whole number >= 0 (got ${k})`);
    driven = true;
    if (!app.game.paused) app.game.paused = true;
    if (app.game.sim.time > k) app.restart();
    while (app.game.sim.time < k && !ended()) app.game.step();
    app.dirty = true;
    return { frame: Math.round(app.game.sim.time), ended: ended() };
  };
  (window as unknown as { evapcoolFrame: typeof show }).evapcoolFrame = show;
  return () => driven;
}

/** The tab's icon, drawn in code (no image file). */
function setIcon(): void {
  const c = document.createElement("canvas");
  c.width = c.height = 64;
  const ctx = c.getContext("2d");
  const link = document.querySelector<HTMLLinkElement>('link[rel="icon"]');
  if (!ctx || !link) return;
  drawPageIcon(ctx, 64);
  link.href = c.toDataURL("image/png");
}

const sleep = (ms: number) => new Promise((resolve) => setTimeout(resolve, ms));

void main().catch((err: unknown) => {
  const box = document.getElementById("fatal");
  if (box) {
    box.hidden = false;
    box.textContent = t("page.fatal", { problem: (err as Error).message });
  }
  console.error(err);
});
