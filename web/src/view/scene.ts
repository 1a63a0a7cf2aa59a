/**
 * The 640 x 672 scene in logical pixels (the app sets the transform for the window and
 * the device's pixel ratio): borders, title, cup, atoms, thermometer, status and the
 * messages over the play area. Positions and colours follow the desktop applet.
 * Python's twin: `src/evapcool/view/scene.py` (docs/twins.md).
 */
import { formatNumber, t } from "../i18n";
import { BORDER_TOP, screenOrigin } from "./screen";
import type { Game } from "../game/rules";
import type { AtomArrays, SimLike } from "../game/sim";
import * as C from "./colors";
import { PLAY_RECT, SCENE_W, SCENE_H, type Rect } from "./geometry";
import { AtomLayer, atomSprite } from "./sprites";
import { drawText, fitSize, textWidth, wrap } from "./text";

/** Where messages over the play area go (the desktop's), and panels under them. */
export const MESSAGE_Y = PLAY_RECT.y + 62;
export const UNDER_MESSAGE = PLAY_RECT.y + 150;

// Thermometer in the right border; the mercury top is at SCALE_ZERO - f (SCALE_ZERO - SCALE_FULL).
export const THERMO_X = 592;
/** The title's width at most: centred, clear of the speed line (170 px from x = 10). */
const TITLE_WIDTH = SCENE_W - 2 * 190;
const TUBE_WIDTH = 20;
const TUBE_TOP = 72;
const SCALE_FULL = 88;
const SCALE_ZERO = 572;
export const BULB_CENTER: readonly [number, number] = [THERMO_X, 598];
const BULB_RADIUS = 20;
const MERCURY_WIDTH = 10;
const THERMO_MAX_FRACTION = 1.2;

/** Height of the mercury as a fraction of the scale: T / (1.2 T0), clipped to [0, 1]. */
export function mercuryFraction(temperature: number, initial: number): number {
  if (!(initial > 0)) return 0;
  return Math.min(1, Math.max(0, temperature / (THERMO_MAX_FRACTION * initial)));
}

/** Pixel row of a thermometer reading (0 = empty, 1 = full scale). */
export function scaleRow(fraction: number): number {
  return Math.round(SCALE_ZERO - fraction * (SCALE_ZERO - SCALE_FULL));
}

/**
 * Points (trap coordinates, flat x, y pairs) at distance `offset` outside the wall
 * y = a x^2, from -xRim to xRim: a disk of radius `offset` touches this curve exactly
 * when its centre touches the wall.
 */
export function cupOutline(a: number, xRim: number, offset: number, samples = 161): Float64Array {
  const out = new Float64Array(samples * 2);
  for (let k = 0; k < samples; k++) {
    const x = -xRim + (2 * xRim * k) / (samples - 1);
    const slope = 2 * a * x;
    const norm = Math.sqrt(1 + slope * slope);
    out[2 * k] = x + (offset * slope) / norm;
    out[2 * k + 1] = a * x * x - offset / norm;
  }
  return out;
}

export class Scene {
  private cupKey = "";
  private cupPath: Path2D | null = null;
  /** Device px per logical px (set by the app before drawing). */
  deviceScale = 1;
  private layer = new AtomLayer();
  /** From this many atoms on, one image of the play area instead of a drawImage per atom. */
  static LAYER_MIN_ATOMS = 200;

  /** Background, cup, atoms, borders, title, thermometer, status text. */
  draw(ctx: CanvasRenderingContext2D, game: Game, atoms: AtomArrays, atomAlpha = 1): void {
    const sim = game.sim;
    ctx.fillStyle = C.BACKGROUND;
    ctx.fillRect(PLAY_RECT.x, PLAY_RECT.y, PLAY_RECT.w, PLAY_RECT.h);
    ctx.save();
    ctx.beginPath();
    ctx.rect(PLAY_RECT.x, PLAY_RECT.y, PLAY_RECT.w, PLAY_RECT.h);
    ctx.clip(); // escaping atoms slide under the borders
    this.drawCup(ctx, sim);
    this.drawAtoms(ctx, sim, atoms, atomAlpha);
    ctx.restore();
  }

  /** Borders and title (drawn after the play area and any glow over it). */
  drawFrame(
    ctx: CanvasRenderingContext2D,
    game: Game,
    sceneHeight = SCENE_H,
    minTextSize = 0,
  ): void {
    ctx.fillStyle = C.BORDER;
    const bottom = PLAY_RECT.y + PLAY_RECT.h;
    ctx.fillRect(0, 0, SCENE_W, BORDER_TOP);
    ctx.fillRect(0, bottom, SCENE_W, sceneHeight - bottom);
    ctx.fillRect(0, 0, PLAY_RECT.x, sceneHeight);
    ctx.fillRect(PLAY_RECT.x + PLAY_RECT.w, 0, SCENE_W - PLAY_RECT.x - PLAY_RECT.w, sceneHeight);
    // The title shrinks to stay clear of the speed line whatever its language's length.
    const title = t("app.title");
    const titleSize = fitSize(ctx, title, 40 * C.TEXT_SCALE, TITLE_WIDTH, 16);
    drawText(ctx, title, titleSize, C.TEXT, SCENE_W / 2, BORDER_TOP / 2 + 1, "center");
    this.drawThermometer(ctx, game.sim);
    // Left of the title whatever the size: the title starts 183 px in at its size of 40.
    const label = t("status.speed", { speed: speedNumber(game.speed) });
    let size = Math.max(22 * C.TEXT_SCALE, minTextSize);
    while (size > 12 && textWidth(ctx, label, size) > 170) size -= 1;
    drawText(ctx, label, size, C.DIM_TEXT, 10, BORDER_TOP / 2, "midleft");
  }

  drawCup(ctx: CanvasRenderingContext2D, sim: SimLike): void {
    const [ox, oy] = screenOrigin(sim);
    const radius = sim.originLift; // the drawn cup bottom lies this far below the origin
    const key = `${sim.trapHeight}|${sim.curvature}|${radius}|${ox}|${oy}`;
    if (key !== this.cupKey || !this.cupPath) {
      const xRim = sim.rimHalfWidth;
      const inner = cupOutline(sim.curvature, xRim, radius);
      const outer = cupOutline(sim.curvature, xRim, radius + C.CUP_WIDTH);
      const path = new Path2D();
      const n = inner.length / 2;
      for (let k = 0; k < n; k++) {
        const x = ox + inner[2 * k];
        const y = oy - inner[2 * k + 1];
        if (k === 0) path.moveTo(x, y);
        else path.lineTo(x, y);
      }
      for (let k = n - 1; k >= 0; k--) path.lineTo(ox + outer[2 * k], oy - outer[2 * k + 1]);
      path.closePath();
      this.cupPath = path;
      this.cupKey = key;
    }
    ctx.fillStyle = C.CUP_COLOR;
    ctx.fill(this.cupPath);
  }

  /** The atoms, escaped ones too, from one sprite per radius in one pass. */
  drawAtoms(ctx: CanvasRenderingContext2D, sim: SimLike, atoms: AtomArrays, alpha = 1): void {
    const [ox, oy] = screenOrigin(sim);
    const esc = sim.escaped();
    if (atoms.count + esc.count >= Scene.LAYER_MIN_ATOMS) {
      // Device px of the play area's corner; the layer covers the play area.
      const s = this.deviceScale;
      const m = ctx.getTransform();
      const left = Math.round(m.e + PLAY_RECT.x * s);
      const top = Math.round(m.f + PLAY_RECT.y * s);
      const x0 = m.e + ox * s - left;
      const y0 = m.f + oy * s - top;
      this.layer.begin(PLAY_RECT.w * s, PLAY_RECT.h * s);
      this.layer.add(esc.x, esc.y, esc.radius, esc.count, s, x0, y0);
      if (alpha > 0) this.layer.add(atoms.x, atoms.y, atoms.radius, atoms.count, s, x0, y0);
      this.layer.draw(ctx, left, top);
      return;
    }
    this.blitAtoms(ctx, esc, ox, oy);
    if (alpha <= 0) return;
    ctx.globalAlpha = alpha;
    this.blitAtoms(ctx, atoms, ox, oy);
    ctx.globalAlpha = 1;
  }

  private blitAtoms(ctx: CanvasRenderingContext2D, a: AtomArrays, ox: number, oy: number): void {
    if (a.count === 0) return;
    const s = this.deviceScale;
    // Draw in device pixels so every sprite lands on whole pixels (crisp and fast).
    const m = ctx.getTransform();
    ctx.setTransform(1, 0, 0, 1, m.e, m.f);
    let key = NaN;
    let sprite = atomSprite(a.radius[0], s);
    let half = sprite.size / 2;
    for (let i = 0; i < a.count; i++) {
      const r = a.radius[i];
      if (r !== key) {
        key = r;
        sprite = atomSprite(r, s);
        half = sprite.size / 2;
      }
      const x = Math.floor((ox + a.x[i]) * s - half + 0.5);
      const y = Math.floor((oy - a.y[i]) * s - half + 0.5);
      ctx.drawImage(sprite.canvas, x, y);
    }
    ctx.setTransform(m);
  }

  drawThermometer(ctx: CanvasRenderingContext2D, sim: SimLike): void {
    const tubeH = BULB_CENTER[1] - TUBE_TOP;
    const tubeLeft = THERMO_X - TUBE_WIDTH / 2;
    ctx.fillStyle = C.GLASS;
    ctx.beginPath();
    ctx.roundRect(tubeLeft, TUBE_TOP, TUBE_WIDTH, tubeH, TUBE_WIDTH / 2);
    ctx.fill();
    ctx.beginPath();
    ctx.arc(BULB_CENTER[0], BULB_CENTER[1], BULB_RADIUS, 0, 2 * Math.PI);
    ctx.fill();
    ctx.fillStyle = C.MERCURY;
    ctx.beginPath();
    ctx.arc(BULB_CENTER[0], BULB_CENTER[1], BULB_RADIUS - 5, 0, 2 * Math.PI);
    ctx.fill();
    const top = scaleRow(mercuryFraction(sim.temperature, sim.initialTemperature));
    ctx.fillRect(THERMO_X - MERCURY_WIDTH / 2, top, MERCURY_WIDTH, BULB_CENTER[1] - top);
    if (C.GLASS_EDGE) {
      ctx.strokeStyle = C.GLASS_EDGE;
      ctx.lineWidth = 3;
      ctx.beginPath();
      ctx.roundRect(tubeLeft - 1.5, TUBE_TOP - 1.5, TUBE_WIDTH + 3, tubeH, TUBE_WIDTH / 2 + 1.5);
      ctx.stroke();
      ctx.beginPath();
      ctx.arc(BULB_CENTER[0], BULB_CENTER[1], BULB_RADIUS + 1.5, 0, 2 * Math.PI);
      ctx.stroke();
    }
    ctx.strokeStyle = C.TICK;
    ctx.lineWidth = C.THEME === "projector" ? 2 : 1;
    const right = tubeLeft + TUBE_WIDTH;
    ctx.beginPath();
    for (let k = 0; k <= 10; k++) {
      const y = scaleRow(k / 10) + 0.5;
      ctx.moveTo(right - 5, y);
      ctx.lineTo(right - 1, y);
    }
    ctx.stroke();
    const tc = scaleRow(mercuryFraction(sim.criticalTemperature, sim.initialTemperature));
    ctx.fillStyle = C.BLACK;
    const mark = C.THEME === "projector" ? 4 : 2;
    ctx.fillRect(tubeLeft - 6, tc - mark / 2, TUBE_WIDTH + 8, mark);
    const size = 26 * C.TEXT_SCALE;
    drawText(ctx, "Tc", size, C.TEXT, tubeLeft - 8, tc, "midright");
    drawText(ctx, "T", size, C.TEXT, THERMO_X, TUBE_TOP - 2, "midbottom");
  }

  // -- messages over the play area -------------------------------------------------
  /** "Score: N" in large text at the top of the play area (the win). */
  drawScore(ctx: CanvasRenderingContext2D, score: number): void {
    const cx = PLAY_RECT.x + PLAY_RECT.w / 2;
    const width = PLAY_RECT.w - 20;
    const big = t("win.score_big", { n: score });
    const bigSize = fitSize(ctx, big, 84, width, 40);
    shadowed(ctx, big, bigSize, cx, MESSAGE_Y);
    const line = t("win.condensed");
    const size = fitSize(ctx, line, 30, width, 16);
    // Under the score's plate (each plate reaches 0.75 of its size from its centre), not on it.
    const y = MESSAGE_Y + 0.75 * (bigSize + size) + 2;
    plate(ctx, textWidth(ctx, line, size), size, cx, y);
    drawText(ctx, line, size, C.TEXT, cx, y, "center", true);
  }

  /** The gas can no longer condense: say why and offer a restart. */
  drawTooFew(ctx: CanvasRenderingContext2D, reason: string, retry: string): void {
    const cx = PLAY_RECT.x + PLAY_RECT.w / 2;
    const title = t("lose.too_few");
    shadowed(ctx, title, fitSize(ctx, title, 52, PLAY_RECT.w - 20, 26), cx, MESSAGE_Y);
    const width = PLAY_RECT.w - 40;
    const lines = [...wrap(ctx, reason, 26, width), ...wrap(ctx, retry, 26, width)];
    lines.forEach((line, k) => {
      plate(ctx, textWidth(ctx, line, 26), 26, cx, MESSAGE_Y + 48 + 30 * k);
      drawText(ctx, line, 26, C.TEXT, cx, MESSAGE_Y + 48 + 30 * k, "center", true);
    });
  }

  drawStartHint(ctx: CanvasRenderingContext2D, touch: boolean): void {
    const text = t(touch ? "start.tap_play" : "start.press_space");
    const cx = PLAY_RECT.x + PLAY_RECT.w / 2;
    const size = fitSize(ctx, text, 28, PLAY_RECT.w - 20, 16);
    plate(ctx, textWidth(ctx, text, size), size, cx, PLAY_RECT.y + 40);
    drawText(ctx, text, size, C.TEXT, cx, PLAY_RECT.y + 40, "center", true);
  }
}

/** A plate behind a line of `size` px and width w centred at (cx, cy): its words stand at
 * 7:1 against it whatever the atoms or the play area behind (issue 48). */
function plate(ctx: CanvasRenderingContext2D, w: number, size: number, cx: number, cy: number) {
  ctx.fillStyle = C.PLATE;
  ctx.beginPath();
  ctx.roundRect(cx - w / 2 - 10, cy - size * 0.75, w + 20, size * 1.5, 6);
  ctx.fill();
}

export function shadowed(
  ctx: CanvasRenderingContext2D,
  text: string,
  size: number,
  cx: number,
  cy: number,
): void {
  plate(ctx, textWidth(ctx, text, size) + 6, size, cx + 1.5, cy + 1.5);
  drawText(ctx, text, size, C.SHADOW, cx + 3, cy + 3, "center", true);
  drawText(ctx, text, size, C.TEXT, cx, cy, "center", true);
}

/** A translucent dark panel with the accent border. */
export function frame(ctx: CanvasRenderingContext2D, r: Rect): void {
  ctx.fillStyle = C.OVERLAY_SHADE;
  ctx.fillRect(r.x, r.y, r.w, r.h);
  ctx.strokeStyle = C.ACCENT;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.roundRect(r.x + 1, r.y + 1, r.w - 2, r.h - 2, 4);
  ctx.stroke();
}

/** A speed as people write it: 0.3x, 0.25x, 2x (two significant digits, no float noise). */
export function speedText(s: number): string {
  return `${speedNumber(s)}x`;
}

/** The speed's number alone, as the active language writes it (0,25 in German). */
export function speedNumber(s: number): string {
  return formatNumber(Number(s.toPrecision(2)));
}
