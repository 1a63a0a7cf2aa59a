/**
 * `window.evapcool`: the applet's state and a few commands for scripts, lecturers' consoles
 * and the end-to-end tests (which check the page through it, and pixels through screenshots).
 */
import type { App } from "./app";

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
}

export function exposeApi(app: App): void {
  const api = {
    app,
    state(): PageState {
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
      };
    },
    /** Play n frames of 1/30 s x speed now, each drawn (unpauses). */
    runFrames(n: number): void {
      app.game.paused = false;
      app.runFrames(n);
    },
    /** Frame work (physics + drawing) median / p95 in ms and the display rate, last n frames. */
    frameStats(n = 600) {
      return app.loop.stats.summary(n);
    },
    resetStats(): void {
      app.loop.stats.reset();
    },
  };
  (window as unknown as { evapcool: typeof api }).evapcool = api;
}
