/**
 * What each action does (a key of the key table, a button, a tap on a drawn target): the
 * one place a new button's effect is written. The rooms it moves are the host's.
 */
import { t } from "../i18n";
import { speedText } from "../view/scene";
import { HEIGHT_STEP, type Action } from "./bindings";
import type { Charts } from "./charts";
import type { Hints } from "./hints";
import type { SettingsEditor } from "./options";
import type { Panels } from "./panels";
import type { Play } from "./play";
import type { GameLike } from "../runtime/remote";
import type { Replays } from "./replays";
import type { Scoreboard } from "./scoring";
import type { Teaching } from "./teaching";

/** The rooms an action moves. */
export interface ActionHost {
  readonly game: GameLike;
  readonly play: Play;
  readonly panels: Panels;
  readonly options: SettingsEditor;
  readonly scores: Scoreboard;
  readonly replays: Replays;
  readonly charts: Charts;
  readonly hints: Hints;
  readonly teaching: Teaching;
  /** New atoms with the current settings (the scores and panels follow). */
  restart(): void;
  /** Lay out again (a chart shown or hidden). */
  resize(): void;
  say(text: string): void;
  notify(text: string): void;
}

/** Do what the action means, in the host's rooms. */
export function act(host: ActionHost, action: Action): void {
  const g = host.game;
  const panels = host.panels;
  const teaching = host.teaching;
  if (teaching.blocked(action)) return;
  // Another panel over the settings: they close first, and say if changes were dropped.
  if (panels.open === "settings" && ["help", "table", "clear", "escape"].includes(action))
    host.options.close(false);
  switch (action) {
    case "pause":
      g.togglePause();
      host.say(t(g.paused ? "page.paused" : "page.playing"));
      break;
    case "restart":
      host.restart();
      break;
    case "lower":
    case "raise":
      host.play.takeOver();
      g.nudgeHeight(action === "lower" ? -HEIGHT_STEP : HEIGHT_STEP);
      host.play.heightChanged();
      break;
    case "step":
      host.play.autopilot?.steer(g);
      g.step();
      break;
    case "autopilot":
      host.play.toggleAutopilot();
      break;
    case "copycode":
      void host.replays.copy();
      break;
    case "faster":
    case "slower":
      if (action === "faster") g.faster();
      else g.slower();
      host.say(t("page.speed_spoken", { speed: speedText(g.speed) }));
      break;
    case "energy":
      host.charts.showEnergy = !host.charts.showEnergy;
      host.resize();
      host.say(t(host.charts.showEnergy ? "page.energy_shown" : "page.energy_hidden"));
      break;
    case "path":
      host.charts.showPath = !host.charts.showPath;
      host.resize();
      host.say(t(host.charts.showPath ? "page.path_shown" : "page.path_hidden"));
      break;
    case "table":
      panels.toggle("table");
      host.scores.confirmReset = false;
      break;
    case "clear":
      panels.open = "table";
      host.scores.confirmReset = true;
      host.say(host.hints.confirmClearSpoken);
      break;
    case "next":
      if (host.scores.readyForNext) host.restart();
      break;
    case "settings":
      panels.open = "settings";
      host.options.open();
      break;
    case "fullscreen":
      toggleFullscreen(host);
      break;
    case "help":
    case "verify":
      panels.toggle(action);
      break;
    case "mute":
      teaching.toggleMute();
      break;
    case "describe":
      teaching.describe();
      break;
    case "copylink":
      teaching.copyLink();
      break;
    case "saverun":
      void teaching.saveRun();
      break;
    case "escape":
      if (panels.open !== null) panels.open = null;
      else if (document.fullscreenElement) void document.exitFullscreen().catch(() => {});
      break;
  }
}

function toggleFullscreen(host: ActionHost): void {
  if (document.fullscreenElement) {
    void document.exitFullscreen().catch(() => {});
  } else if (document.documentElement.requestFullscreen) {
    document.documentElement.requestFullscreen().catch((err: unknown) => {
      host.notify(t("page.fullscreen_refused", { problem: (err as Error).message }));
    });
  } else {
    host.notify(t("notice.fullscreen_unavailable"));
  }
}
