/**
 * `window.evapcool`: the applet's state and a few commands for scripts, lecturers' consoles
 * and the end-to-end tests (which check the page through it, and pixels through screenshots).
 */
import { activeTranslator, missingKeys } from "../i18n";
import type { App, DrawnControls } from "./app";
import { Sound } from "./sound";
import { PLAY_RECT } from "../view/geometry";
import { THERMO_X } from "../view/scene";
import { BORDER_TOP } from "../view/screen";

export interface PageState {
  paused: boolean;
  speed: number;
  trapHeight: number;
  nAtoms: number;
  nTrapped: number;
  temperature: number;
  initialTemperature: number;
  criticalTemperature: number;
  won: boolean;
  /** Play time (s) of the whole frame the win was counted at, or null: the physics may show
   * the gas condensed (won) a moment before the game counts it at the frame's end. */
  wonAt: number | null;
  score: number | null;
  time: number;
  overlay: string | null;
  nameBox: boolean;
  confirmReset: boolean;
  readyForNext: boolean;
  showEnergy: boolean;
  showPath: boolean;
  layout: string;
  scale: number;
  table: Array<{ name: string; score: number; seconds: number; date: string }>;
  notices: string[];
  errors: string[];
  fullscreen: boolean;
  /** Where the physics runs: "worker" or "page". */
  engine: string;
  /** The game's pace against real time over the last second of play (1 = real time). */
  pace: number;
  /** The slow-motion line shown, or null. */
  slowNote: string | null;
  /** The worker's ms spent on the physics for its newest frame (NaN without a worker). */
  physicsMs: number;
  /** The autopilot holds the trap (key A or the wheel button). */
  autopilot: boolean;
  /** The help's row size as last drawn, logical px (x scale: CSS px). */
  helpSize: number;
  /** The language the page speaks (a shipped tag, or en-XA) and its direction. */
  locale: string;
  direction: "ltr" | "rtl";
  /** Keys asked for that the language's catalog lacks (shown in English); empty when whole. */
  missingKeys: string[];
  theme: string;
  soundOn: boolean;
  volume: number;
}

export function exposeApi(app: App): void {
  const api = {
    app,
    /** The state once the worker (if any) has applied every input so far. */
    async state(): Promise<PageState> {
      await app.play.settled();
      return this.stateNow();
    },
    /** The state as the page has it now (the worker's newest frame). */
    stateNow(): PageState {
      const g = app.game;
      const s = g.sim;
      return {
        paused: g.paused,
        speed: g.speed,
        trapHeight: g.trapHeight,
        nAtoms: s.nAtoms,
        nTrapped: s.nTrapped,
        temperature: s.temperature,
        initialTemperature: s.initialTemperature,
        criticalTemperature: s.criticalTemperature,
        won: g.won,
        wonAt: g.wonAt,
        score: g.score,
        time: s.time,
        overlay: app.overlay,
        nameBox: app.scores.nameBoxOpen,
        confirmReset: app.scores.confirmReset,
        readyForNext: app.scores.readyForNext,
        showEnergy: app.charts.showEnergy,
        showPath: app.charts.showPath,
        layout: app.layout.mode,
        scale: app.layout.scale,
        table: app.scores.table.entries,
        notices: app.notices.visible,
        errors: app.loop.errors.slice(),
        fullscreen: document.fullscreenElement !== null,
        engine: app.play.engine,
        pace: app.play.pace.pace,
        slowNote: app.play.slowNote(),
        physicsMs: app.play.physicsMs,
        autopilot: app.play.autopilotEngaged,
        helpSize: app.panels.helpSize,
        locale: activeTranslator().locale,
        direction: activeTranslator().direction,
        missingKeys: [...(missingKeys.get(activeTranslator().locale) ?? [])],
        theme: app.teaching.theme,
        soundOn: app.teaching.sound.on,
        volume: app.teaching.sound.volume,
      };
    },
    /** Play n frames of 1/30 s x speed now, drawn (unpauses); resolves once shown. */
    runFrames(n: number): Promise<void> {
      app.game.paused = false;
      return app.runFrames(n);
    },
    /**
     * n frames of 1 physics frame x speed at once in the worker (no drawing between), for
     * timing the physics: its ms are then `stateNow().physicsMs`. Unpauses.
     */
    physicsFrames(n: number): Promise<void> {
      app.game.paused = false;
      return app.play.physicsFrames(n);
    },
    /** The physics' own switch to the won state (tests of the condensate). */
    forceWin(): Promise<void> {
      return app.play.forceWin();
    },
    /** A golden trace's text replayed by the engine the page plays with (in the worker if any). */
    replay(text: string): Promise<string> {
      return app.play.replay(text);
    },
    /** Display frames run so far, and what the last drawn frame showed of the controls. */
    frames(): { frames: number; drawn: DrawnControls } {
      return { frames: app.loop.frames, drawn: app.drawn };
    },
    /** Frame work (physics + drawing) median / p95 in ms and the display rate, last n frames. */
    frameStats(n = 600) {
      return app.loop.stats.summary(n);
    },
    resetStats(): void {
      app.loop.stats.reset();
    },
    /** Where the scene draws its parts (logical px), for tests that read pixels. */
    geometry: { PLAY_RECT, BORDER_TOP, THERMO_X },
    /** The address of the setup on screen ("Copy link to this setup"). */
    link(): string {
      return app.teaching.link();
    },
    /** The CSV "Save this run" writes. */
    runCsv(): Promise<string> {
      return app.teaching.runCsv();
    },
    /**
     * The page's sound graph rendered offline: a Sound like the page's (its on and volume)
     * on an OfflineAudioContext of `seconds`, fed the game as it plays `frames` drawn frames
     * of 1/30 s, frame k heard at k/30 s. The samples, and the times atoms left.
     */
    async renderSound(frames: number, seconds: number) {
      const rate = 22050;
      const ctx = new OfflineAudioContext(1, Math.ceil(seconds * rate), rate);
      const page = app.teaching.sound;
      const sound = new Sound(page.on, page.volume);
      sound.attach(ctx);
      const left: number[] = [];
      app.game.paused = false;
      let n = app.game.sim.nTrapped;
      sound.frame(app.teaching.heard(), 0); // what the first frame is heard against
      for (let k = 1; k <= frames; k++) {
        await app.runFrames(1);
        const g = app.game;
        if (g.sim.nTrapped < n) left.push(k / 30);
        n = g.sim.nTrapped;
        sound.frame(app.teaching.heard(), k / 30);
      }
      const buffer = await ctx.startRendering();
      return { rate, samples: Array.from(buffer.getChannelData(0)), left };
    },
  };
  (window as unknown as { evapcool: typeof api }).evapcool = api;
}
