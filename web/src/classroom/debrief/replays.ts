/**
 * Two replays in step on the projector (issue 36): each game's own page (the class's game
 * page, same origin) in a frame, driven by one clock of whole frames: the same frame in
 * both at every moment, a lagging one holding the other, each ending on its own last frame.
 */
import { classBase } from "../common";
import { nameOf, type PairDoc, type Tr } from "../../view/debrief/model";
import { nextFrame, type Shown } from "../../view/debrief/pair";
import { PLAY_RECT } from "../../view/geometry";

/** What the projector reads of the game page in a frame: its layout (same origin). */
interface FramedApp {
  layout: { scale: number; offsetX: number; offsetY: number };
}

/**
 * A replay presented (issue 45): the game page in `frame` shown only through its play
 * area (the cup and its atoms), scaled to fill the frame's stage, so that no button, no
 * slider and no key's hint of the page reaches the projector. Kept as the page lays out.
 */
export function present(frame: HTMLIFrameElement): void {
  const crop = () => {
    let app: FramedApp | undefined;
    try {
      app = (frame.contentWindow as unknown as { evapcool?: { app?: FramedApp } } | null)?.evapcool
        ?.app;
    } catch {
      return; // not ours (cannot happen: same origin)
    }
    const stage = frame.parentElement;
    if (!app?.layout || !stage) return;
    const l = app.layout;
    const [x, y] = [l.offsetX + PLAY_RECT.x * l.scale, l.offsetY + PLAY_RECT.y * l.scale];
    const [w, h] = [PLAY_RECT.w * l.scale, PLAY_RECT.h * l.scale];
    const k = Math.min(stage.clientWidth / w, stage.clientHeight / h);
    const dx = (stage.clientWidth - w * k) / 2 - x * k;
    const dy = (stage.clientHeight - h * k) / 2 - y * k;
    frame.style.transform = `translate(${dx}px, ${dy}px) scale(${k})`;
    // Nothing beside the play area either (a wide stage would show the controls' strip).
    const [fw, fh] = [frame.clientWidth, frame.clientHeight];
    frame.style.clipPath = `inset(${y}px ${fw - x - w}px ${fh - y - h}px ${x}px)`;
    frame.dataset.presented = "1";
  };
  frame.addEventListener("load", crop);
  const timer = window.setInterval(() => {
    if (!frame.isConnected) window.clearInterval(timer);
    else crop();
  }, 500);
}

/** What the game page in a replay's frame offers its parent (app/main.ts: followParent). */
type FrameHook = (k: number) => { frame: number; ended: boolean };

export class PairReplays {
  readonly box: HTMLDivElement;
  private frames: HTMLIFrameElement[] = [];
  private k = 0;

  constructor(
    before: HTMLElement,
    private readonly tr: Tr,
    private readonly locale: string,
  ) {
    this.box = document.createElement("div");
    this.box.id = "debrief-replays";
    this.box.hidden = true;
    before.before(this.box);
  }

  /** Play this pair's replays from their first frame (null, or codes missing: none). */
  set(pair: PairDoc | null): void {
    this.k = 0;
    this.frames = [];
    this.box.replaceChildren();
    const codes = pair ? pair.games.map((g) => g.code ?? "") : [];
    this.box.hidden = !pair || codes.some((c) => !c);
    if (!pair || this.box.hidden) return;
    pair.games.forEach((g, i) => {
      const stage = document.createElement("div");
      stage.className = "stage";
      const frame = document.createElement("iframe");
      frame.title = nameOf(g, this.tr);
      frame.src = this.address(codes[i]);
      stage.append(frame);
      this.box.append(stage);
      this.frames.push(frame);
      present(frame);
    });
  }

  /** Show the shared frame in both (in one task: no moment sees them apart); the frame
   * shown, or null without replays. */
  step(): number | null {
    if (!this.frames.length) return null;
    const k = this.k;
    const shown = this.frames.map((f) => this.show(f, k));
    this.box.dataset.frames = shown.map((s) => (s ? String(s.frame) : "")).join(",");
    this.box.dataset.frame = String(k);
    this.k = nextFrame(k, shown);
    return k;
  }

  private show(frame: HTMLIFrameElement, k: number): Shown {
    try {
      // Same origin only: a page of another origin cannot be reached (and throws).
      const hook = (frame.contentWindow as unknown as { evapcoolFrame?: FrameHook } | null)
        ?.evapcoolFrame;
      return hook ? hook(k) : null;
    } catch {
      return null; // not loaded yet, or not ours: the other waits
    }
  }

  private address(code: string): string {
    const lang = encodeURIComponent(this.locale);
    // "#in-step": the page waits for this clock instead of playing by itself.
    return classBase() + "/?replay=" + encodeURIComponent(code) + "&lang=" + lang + "#in-step";
  }
}
