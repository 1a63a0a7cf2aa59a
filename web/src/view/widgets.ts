/**
 * The trap-height slider and the control buttons, drawn from plain state.
 * Python's twin: `src/evapcool/view/widgets.py` (docs/twins.md).
 */
import * as C from "./colors";
import { drawButton, type Look, type SymbolName } from "./icons";
import type { Rect } from "./geometry";
import { drawText } from "./text";

/** Slider value <-> knob position (the desktop's Slider arithmetic). */
/**
 * A slider's value: where a drag holds the knob, else where `follow` says it rests (e.g. the
 * game's trap height, read when asked). The slider owns its drag; nobody writes the model's
 * value back into it (issue 26.2, as the desktop's Slider).
 */
export class SliderModel {
  private held: number | null = null;
  constructor(
    readonly min: number,
    readonly max: number,
    private readonly follow: () => number,
  ) {}
  get value(): number {
    return Math.min(this.max, Math.max(this.min, this.held ?? this.follow()));
  }
  /** 0 at min, 1 at max. */
  get activation(): number {
    return (this.value - this.min) / (this.max - this.min);
  }
  /** A drag holds the knob at v until release(). */
  hold(v: number): void {
    this.held = v;
  }
  release(): void {
    this.held = null;
  }
  get dragging(): boolean {
    return this.held !== null;
  }
  /** An upright bar (taller than wide): its top is the maximum. */
  static upright(r: Rect): boolean {
    return r.h > r.w;
  }
  /** The value for a knob at logical position p along the bar r (x, or y if upright). */
  valueAt(p: number, r: Rect): number {
    const f = SliderModel.upright(r) ? 1 - (p - r.y) / r.h : (p - r.x) / r.w;
    const a = Math.min(1, Math.max(0, f));
    return this.min + a * (this.max - this.min);
  }
  /** The knob's position along the bar (x, or y if upright). */
  knobAt(r: Rect): number {
    return SliderModel.upright(r) ? r.y + (1 - this.activation) * r.h : r.x + this.activation * r.w;
  }
  knobX(r: Rect): number {
    return this.knobAt(r);
  }
}

export function drawSlider(
  ctx: CanvasRenderingContext2D,
  r: Rect,
  model: SliderModel,
  knobRadius: number,
  label: string,
  hot: boolean,
  enabled: boolean,
  labelSize = 24,
): void {
  ctx.fillStyle = C.WHITE;
  ctx.beginPath();
  ctx.roundRect(r.x, r.y, r.w, r.h, 3);
  ctx.fill();
  ctx.strokeStyle = C.BLACK;
  ctx.lineWidth = C.THEME === "projector" ? 3 : 1;
  ctx.beginPath();
  ctx.roundRect(r.x + 0.5, r.y + 0.5, r.w - 1, r.h - 1, 3);
  ctx.stroke();
  const upright = SliderModel.upright(r);
  if (label && upright) {
    drawText(ctx, label, labelSize, C.TEXT, r.x + r.w / 2, r.y - knobRadius - 14, "midbottom");
  } else if (label) {
    // The desktop's slider label is pygame's default font at 24 (no extra weight).
    drawText(ctx, label, labelSize, C.TEXT, r.x + r.w / 2, r.y + r.h + knobRadius + 4, "midtop");
  }
  const cx = upright ? r.x + r.w / 2 : model.knobAt(r);
  const cy = upright ? model.knobAt(r) : r.y + r.h / 2;
  ctx.fillStyle = !enabled ? "rgb(170,170,170)" : hot ? "rgb(255,245,70)" : C.YELLOW;
  ctx.beginPath();
  ctx.arc(cx, cy, knobRadius, 0, 2 * Math.PI);
  ctx.fill();
  ctx.strokeStyle = C.BLACK;
  ctx.lineWidth = 2;
  ctx.beginPath();
  ctx.arc(cx, cy, knobRadius - 1, 0, 2 * Math.PI);
  ctx.stroke();
}

export function drawControlButton(
  ctx: CanvasRenderingContext2D,
  r: Rect,
  symbol: SymbolName,
  look: Look,
): void {
  drawButton(ctx, r, symbol, look);
}
