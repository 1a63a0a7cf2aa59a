/**
 * The frame's picture: the scene and its condensate, the controls, a tall phone's readout,
 * the win's lines, the open panel, notices, charts and the slow-motion line, drawn in that
 * order; the tap targets drawn, and what the frame showed (for the tests). The canvas's
 * text alternative (the status line) is written from the same game.
 */
import type { Game } from "../game/rules";
import { emptyAtoms, type AtomArrays } from "../game/sim";
import type { Condensate } from "../view/condensate";
import * as C from "../view/colors";
import { PLAY_RECT } from "../view/geometry";
import { drawFocusRing, drawNotices, type Target } from "../view/overlays";
import { drawReadout } from "../view/readout";
import type { Scene } from "../view/scene";
import { drawText } from "../view/text";
import type { Charts } from "./charts";
import type { Controls } from "./controls";
import type { Screen } from "./layout";
import type { FrameLoop } from "./loop";
import { StatusLine, type Notices } from "./notices";
import type { Overlay, Panels } from "./panels";
import type { Play } from "./play";
import type { GameLike } from "../runtime/remote";
import type { Verifier } from "./verifier";
import type { WinScreen } from "./winscreen";

/** The slow-motion line's colour: dark on the play area's grey. */
const SLOW_TEXT = "rgb(30,30,30)";

/** What the last drawn frame showed of the controls (tests count frames from a key to it). */
export interface DrawnControls {
  /** The display frame (FrameLoop.frames) it was drawn in. */
  frame: number;
  trapHeight: number;
  paused: boolean;
  speed: number;
  energy: boolean;
  overlay: Overlay;
}

/** The rooms the picture draws. */
export interface PictureRooms {
  readonly canvas: HTMLCanvasElement;
  readonly screen: Screen;
  readonly scene: Scene;
  readonly condensate: Condensate;
  readonly charts: Charts;
  readonly controls: Controls;
  readonly win: WinScreen;
  readonly panels: Panels;
  readonly verifier: Verifier;
  readonly notices: Notices;
  readonly play: Play;
  readonly loop: FrameLoop;
  readonly reducedMotion: boolean;
}

export class Picture {
  /** The drawn tap targets (last frame), in the panel's own coordinates when zoomed. */
  targets: Target[] = [];
  /** Whether those targets were drawn zoomed with the panels (overlayZoom) or on the scene. */
  targetsZoomed = false;
  /** The tall readout's atom count size as last drawn (logical px; 0: none drawn). */
  readoutSize = 0;
  readonly drawn: DrawnControls = {
    frame: -1,
    trapHeight: 0,
    paused: true,
    speed: 1,
    energy: false,
    overlay: null,
  };
  private readonly ctx: CanvasRenderingContext2D;
  private readonly statusLine: StatusLine;
  private atoms: AtomArrays = emptyAtoms();

  constructor(
    private readonly rooms: PictureRooms,
    status: HTMLElement,
  ) {
    const ctx = rooms.canvas.getContext("2d", { alpha: false });
    if (!ctx) throw new Error("this browser cannot draw on a canvas");
    this.ctx = ctx;
    this.statusLine = new StatusLine(status);
  }

  /**
   * What the picture depends on besides input (every input event marks it dirty): while
   * this stays the same, a frame draws nothing (a paused applet costs no battery). ""
   * means animated: draw every frame.
   */
  key(): string {
    const { play, condensate, screen, canvas, notices } = this.rooms;
    const g = play.game;
    const c = condensate.level;
    if ((g.won && !this.rooms.reducedMotion) || (c > 0 && c < 1)) return "";
    const l = screen.layout;
    const shown = [g.generation, g.sim.time, g.trapHeight, g.paused, g.speed];
    const place = [l.scale, l.offsetX, l.offsetY, l.width, l.height, canvas.width, canvas.height];
    return [...shown, notices.visible.length, ...place].join("|");
  }

  /** Draw the frame; true if the status line waits to be written (draw again soon). */
  draw(): boolean {
    const { screen, scene, charts, panels, play } = this.rooms;
    const ctx = this.ctx;
    const l = screen.layout;
    const g = play.game;
    const sim = g.sim;
    this.atoms = sim.trapped();
    charts.record(sim, this.atoms, g.generation);
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = C.PAGE;
    ctx.fillRect(0, 0, this.rooms.canvas.width, this.rooms.canvas.height);
    const dpr = screen.dpr;
    const s = l.scale * dpr;
    ctx.setTransform(s, 0, 0, s, Math.round(l.offsetX * dpr), Math.round(l.offsetY * dpr));
    scene.deviceScale = s;
    this.drawScene(ctx);
    scene.drawFrame(ctx, sceneGame(g), l.sceneHeight, 16 / l.scale);
    this.rooms.controls.draw(ctx);
    this.readoutSize = l.readout ? drawReadout(ctx, l.readout, sim) : 0;
    this.targets = this.rooms.win.draw(ctx, panels.open !== null);
    this.targetsZoomed = false;
    if (panels.open === null) drawFocusRing(ctx, this.targets, panels.focused);
    this.rooms.verifier.show(panels.open === "verify");
    const panel = panels.draw(ctx);
    if (panel) [this.targets, this.targetsZoomed] = [panel.targets, panel.zoomed];
    drawNotices(ctx, this.rooms.notices.visible);
    charts.draw(ctx, l);
    const slow = play.slowNote();
    if (slow) {
      const [x, y] = [PLAY_RECT.x + PLAY_RECT.w - 8, PLAY_RECT.y + 14];
      drawText(ctx, slow, 20, SLOW_TEXT, x, y, "midright");
    }
    const d = this.drawn;
    d.frame = this.rooms.loop.frames;
    d.trapHeight = g.trapHeight;
    d.paused = g.paused;
    d.speed = g.speed;
    d.energy = charts.showEnergy;
    d.overlay = panels.open;
    return this.statusLine.update(g);
  }

  /** The atoms, and the condensate fading in over them. */
  private drawScene(ctx: CanvasRenderingContext2D): void {
    const { scene, condensate, play, reducedMotion } = this.rooms;
    const g = play.game;
    const sim = g.sim;
    const atoms = this.atoms;
    const fade = condensate.update(sim, atoms, g.generation, play.animTime);
    scene.draw(ctx, sceneGame(g), atoms, 1 - fade);
    if (fade <= 0) return;
    ctx.save();
    ctx.beginPath();
    ctx.rect(PLAY_RECT.x, PLAY_RECT.y, PLAY_RECT.w, PLAY_RECT.h);
    ctx.clip();
    let r = 0;
    for (let i = 0; i < atoms.count; i++) r += atoms.radius[i];
    r = atoms.count ? r / atoms.count : 1;
    const t = reducedMotion ? 0 : play.animTime;
    condensate.draw(ctx, sim, r, t, fade, reducedMotion);
    ctx.restore();
  }
}

/** The scene reads only a game's sim and speed, which the worker's game has as the page's. */
function sceneGame(g: GameLike): Game {
  return g as Game;
}
