/**
 * The panels over the play area: help, the score table, the settings screen and the verify
 * panel. Which one is open, opening and closing them (spoken), and drawing the open one
 * (zoomed with the strip in the tall layout) with its tap targets.
 */
import { formatFixed, t } from "../i18n";
import { MIN_TARGET_CSS } from "../view/geometry";
import { drawFocusRing, drawHelp, drawSettings, drawTable, drawVerify } from "../view/overlays";
import type { TableCell, Target } from "../view/overlays";
import { helpRows } from "./bindings";
import type { Screen } from "./layout";
import type { FrameLoop } from "./loop";
import type { SettingsEditor } from "./options";
import type { Play } from "./play";
import { describeRun, type Scoreboard } from "./scoring";
import { PASTE_BOX, type Verifier } from "./verifier";

export type Overlay = null | "help" | "table" | "settings" | "verify";
export type Panel = Exclude<Overlay, null>;

/** Each panel's title, spoken when it opens. */
const TITLES: Record<Panel, string> = {
  help: "help.title",
  table: "scores.title",
  settings: "settings.title",
  verify: "verify.title",
};

/** The rooms a panel shows. */
export interface PanelRooms {
  readonly screen: Screen;
  readonly options: SettingsEditor;
  readonly scores: Scoreboard;
  readonly verifier: Verifier;
  readonly play: Play;
  readonly loop: FrameLoop;
  /** A touch screen: buttons of 44 CSS px at least. */
  readonly coarse: boolean;
  say(text: string): void;
}

export class Panels {
  open: Overlay = null;
  /** The help's row size as last drawn (logical px; tests check it is legible). */
  helpSize = 0;
  /** The score table's words and where they were drawn (the last table drawn). */
  tableCells: TableCell[] = [];
  /** The target whose element has the keyboard's visible focus (panelkeys.ts), ringed. */
  focused: string | null = null;

  constructor(private readonly rooms: PanelRooms) {}

  /** Open the panel, or close it if it is the one open (its title spoken when it opens). */
  toggle(name: Panel): void {
    this.open = this.open === name ? null : name;
    if (this.open === name) this.rooms.say(t("page.panel_shown", { panel: t(TITLES[name]) }));
  }

  /** Draw the open panel; its tap targets (in the zoomed coordinates, except the help's). */
  draw(ctx: CanvasRenderingContext2D): { targets: Target[]; zoomed: boolean } | null {
    const { screen, options, scores, verifier } = this.rooms;
    const scale = screen.layout.scale;
    if (this.open === null) return null;
    if (this.open === "help") {
      // Over the whole screen: a projector's black bands hold larger text, a phone's rows
      // wrap at 16 CSS px or more.
      const box = screen.visibleBox(12);
      const help = drawHelp(ctx, helpRows(), this.rateLines(), box, 16 / scale);
      this.helpSize = help.size;
      drawFocusRing(ctx, help.targets, this.focused);
      return { targets: help.targets, zoomed: false };
    }
    const zoom = screen.overlayZoom();
    ctx.save();
    ctx.translate(zoom.x, zoom.y);
    ctx.scale(zoom.k, zoom.k);
    ctx.translate(-zoom.cx, -zoom.cy);
    let targets: Target[] = [];
    if (this.open === "table") {
      const title = t("page.table_for", { run: describeRun(options.runSettings()) });
      const rank = scores.storedRank;
      const table = drawTable(
        ctx,
        title,
        scores.table.entries,
        rank,
        scores.footer(),
        scores.buttons(),
      );
      targets = table.targets;
      this.tableCells = table.cells;
    } else if (this.open === "verify") {
      const h = this.rooms.coarse ? Math.max(34, MIN_TARGET_CSS / scale) : 34;
      targets = drawVerify(ctx, PASTE_BOX, verifier.lines(), verifier.busy, h);
    } else {
      targets = drawSettings(ctx, options.rows(), options.row, options.footer());
    }
    drawFocusRing(ctx, targets, this.focused);
    ctx.restore();
    return { targets, zoomed: true };
  }

  /** The display rate while playing (paused frames are not counted) and the game's pace. */
  rateLines(): string[] {
    const { loop, play } = this.rooms;
    const st = loop.playStats.summary();
    const atoms = t("status.atoms", { n: play.game.sim.nTrapped });
    if (st.frames < 2) return [t("page.rate_later", { atoms })];
    const fps = Math.round(st.fps);
    const ms = formatFixed(st.medianMs, 1);
    const pace = play.pace.pace;
    const paceLine =
      pace >= 0.98 ? t("page.real_time") : t("page.too_slow", { pace: formatFixed(pace, 2) });
    return [t("page.rate", { fps, ms, atoms }), paceLine];
  }
}
