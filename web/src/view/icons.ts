/**
 * Button faces and symbols drawn as vector paths, so they are sharp at any scale: the
 * desktop's yellow rounded squares with a black outline and a black symbol.
 * Python's twin: `src/evapcool/view/icons.py` (docs/twins.md).
 */
import { BLACK, FACE } from "./colors";
import type { Rect } from "./geometry";

export type Look = keyof typeof FACE;
export type SymbolName =
  | "play"
  | "pause"
  | "restart"
  | "chart"
  | "help"
  | "table"
  | "settings"
  | "fullscreen"
  | "step"
  | "slower"
  | "faster"
  | "path"
  | "autopilot";

function roundRect(ctx: CanvasRenderingContext2D, r: Rect, radius: number): void {
  ctx.beginPath();
  ctx.roundRect(r.x, r.y, r.w, r.h, radius);
}

/** A button: face, outline, symbol; pressed buttons sink by 2/64 of their size. */
export function drawButton(
  ctx: CanvasRenderingContext2D,
  r: Rect,
  symbol: SymbolName,
  look: Look = "idle",
): void {
  const s = r.w;
  const inset = s / 64;
  const face = { x: r.x + inset, y: r.y + inset, w: s - 2 * inset, h: s - 2 * inset };
  const line = (3 * s) / 64;
  roundRect(ctx, face, s / 6);
  ctx.fillStyle = FACE[look];
  ctx.fill();
  ctx.lineWidth = line;
  ctx.strokeStyle = BLACK;
  roundRect(
    ctx,
    { x: face.x + line / 2, y: face.y + line / 2, w: face.w - line, h: face.h - line },
    s / 6 - line / 2,
  );
  ctx.stroke();
  const shift = look === "down" ? (2 * s) / 64 : 0;
  if (look === "down") {
    ctx.strokeStyle = "rgb(150,120,10)";
    ctx.lineWidth = (2 * s) / 64;
    const i = face.x + (6 * s) / 64;
    const j = face.y + (6 * s) / 64;
    ctx.beginPath();
    ctx.moveTo(face.x + face.w - (6 * s) / 64, j);
    ctx.lineTo(i, j);
    ctx.lineTo(i, face.y + face.h - (6 * s) / 64);
    ctx.stroke();
  }
  ctx.save();
  ctx.translate(r.x + s / 2 + shift, r.y + s / 2 + shift);
  ctx.fillStyle = BLACK;
  ctx.strokeStyle = BLACK;
  SYMBOLS[symbol](ctx, s);
  ctx.restore();
}

type Painter = (ctx: CanvasRenderingContext2D, s: number) => void;

const SYMBOLS: Record<SymbolName, Painter> = {
  play(ctx, s) {
    const h = 0.4 * s;
    const left = -0.33 * h;
    ctx.beginPath();
    ctx.moveTo(left, -h / 2);
    ctx.lineTo(left, h / 2);
    ctx.lineTo(0.55 * h, 0);
    ctx.closePath();
    ctx.fill();
  },
  pause(ctx, s) {
    const w = 0.12 * s;
    const h = 0.4 * s;
    const gap = 0.08 * s;
    ctx.fillRect(-gap / 2 - w, -h / 2, w, h);
    ctx.fillRect(gap / 2, -h / 2, w, h);
  },
  restart(ctx, s) {
    // A clockwise ring arrow: the gap at the upper left, the head pointing up-right.
    const rOut = 0.24 * s;
    const rIn = 0.15 * s;
    const a0 = (-200 * Math.PI) / 180;
    const a1 = (95 * Math.PI) / 180;
    const at = (r: number, a: number): [number, number] => [r * Math.cos(a), -r * Math.sin(a)];
    ctx.beginPath();
    ctx.arc(0, 0, rOut, -a0, -a1, true);
    ctx.arc(0, 0, rIn, -a1, -a0, false);
    ctx.closePath();
    ctx.fill();
    const rMid = (rOut + rIn) / 2;
    const w = 0.13 * s;
    ctx.beginPath();
    ctx.moveTo(...at(rMid + w, a0 + 0.05));
    ctx.lineTo(...at(rMid, a0 - 0.6));
    ctx.lineTo(...at(rMid - w, a0 + 0.05));
    ctx.closePath();
    ctx.fill();
  },
  chart(ctx, s) {
    // Four histogram bars and the red cut line: "show the energies".
    const base = 0.26 * s;
    const w = 0.11 * s;
    [0.25, 0.48, 0.36, 0.16].forEach((f, k) => {
      ctx.fillRect(-0.3 * s + k * (w + 0.03 * s), base - f * s, w, f * s);
    });
    ctx.strokeStyle = "rgb(200,20,20)";
    ctx.lineWidth = (3 * s) / 40;
    ctx.beginPath();
    ctx.moveTo(0.22 * s, -0.3 * s);
    ctx.lineTo(0.22 * s, base);
    ctx.stroke();
  },
  help(ctx, s) {
    ctx.lineWidth = 0.1 * s;
    ctx.lineCap = "round";
    ctx.beginPath();
    ctx.arc(0, -0.1 * s, 0.14 * s, Math.PI * 1.05, Math.PI * 2.35);
    ctx.quadraticCurveTo(0, 0.0 * s, 0, 0.1 * s);
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(0, 0.25 * s, 0.065 * s, 0, 2 * Math.PI);
    ctx.fill();
  },
  table(ctx, s) {
    // A podium: three steps, the winner's highest.
    const w = 0.17 * s;
    ctx.fillRect(-1.5 * w, 0.0 * s, w, 0.25 * s);
    ctx.fillRect(-0.5 * w, -0.2 * s, w, 0.45 * s);
    ctx.fillRect(0.5 * w, 0.08 * s, w, 0.17 * s);
    ctx.beginPath();
    ctx.arc(0, -0.3 * s, 0.06 * s, 0, 2 * Math.PI);
    ctx.fill();
  },
  settings(ctx, s) {
    // A gear: eight teeth around a ring.
    const rOut = 0.27 * s;
    const rIn = 0.19 * s;
    ctx.beginPath();
    for (let k = 0; k < 16; k++) {
      const a0 = (k * Math.PI) / 8;
      const r = k % 2 === 0 ? rOut : rIn;
      ctx.arc(0, 0, r, a0 - Math.PI / 16, a0 + Math.PI / 16);
    }
    ctx.closePath();
    ctx.moveTo(0.08 * s, 0);
    ctx.arc(0, 0, 0.08 * s, 0, 2 * Math.PI, true);
    ctx.fill("evenodd");
  },
  fullscreen(ctx, s) {
    const a = 0.26 * s;
    const b = 0.1 * s;
    ctx.lineWidth = 0.08 * s;
    ctx.lineCap = "square";
    for (const [sx, sy] of [
      [-1, -1],
      [1, -1],
      [1, 1],
      [-1, 1],
    ]) {
      ctx.beginPath();
      ctx.moveTo(sx * a, sy * (a - b));
      ctx.lineTo(sx * a, sy * a);
      ctx.lineTo(sx * (a - b), sy * a);
      ctx.stroke();
    }
  },
  step(ctx, s) {
    // One frame forward: a small play triangle against a bar.
    const h = 0.36 * s;
    ctx.beginPath();
    ctx.moveTo(-0.2 * s, -h / 2);
    ctx.lineTo(-0.2 * s, h / 2);
    ctx.lineTo(0.1 * s, 0);
    ctx.closePath();
    ctx.fill();
    ctx.fillRect(0.12 * s, -h / 2, 0.09 * s, h);
  },
  slower(ctx, s) {
    ctx.fillRect(-0.24 * s, -0.05 * s, 0.48 * s, 0.1 * s);
  },
  faster(ctx, s) {
    ctx.fillRect(-0.24 * s, -0.05 * s, 0.48 * s, 0.1 * s);
    ctx.fillRect(-0.05 * s, -0.24 * s, 0.1 * s, 0.48 * s);
  },
  path(ctx, s) {
    // The path chart: axes, the dashed Tc line, a path falling to it with its end dot.
    const a = 0.28 * s;
    ctx.lineWidth = 0.06 * s;
    ctx.lineCap = "round";
    ctx.beginPath();
    ctx.moveTo(-a, -a);
    ctx.lineTo(-a, a);
    ctx.lineTo(a, a);
    ctx.stroke();
    ctx.strokeStyle = "rgb(200,20,20)";
    ctx.lineWidth = 0.04 * s;
    ctx.setLineDash([0.07 * s, 0.05 * s]);
    ctx.beginPath();
    ctx.moveTo(-a, 0.12 * s);
    ctx.lineTo(a, -0.02 * s);
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.strokeStyle = BLACK;
    ctx.lineWidth = 0.06 * s;
    ctx.beginPath();
    ctx.moveTo(0.2 * s, -0.22 * s);
    ctx.quadraticCurveTo(0.05 * s, 0.1 * s, -0.14 * s, 0.12 * s);
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(-0.14 * s, 0.12 * s, 0.06 * s, 0, 2 * Math.PI);
    ctx.fill();
  },
  autopilot(ctx, s) {
    // A steering wheel: the autopilot holds the trap.
    ctx.lineWidth = 0.07 * s;
    ctx.beginPath();
    ctx.arc(0, 0, 0.25 * s, 0, 2 * Math.PI);
    ctx.stroke();
    ctx.beginPath();
    ctx.arc(0, 0, 0.07 * s, 0, 2 * Math.PI);
    ctx.fill();
    for (const angle of [Math.PI / 2, (7 * Math.PI) / 6, (11 * Math.PI) / 6]) {
      ctx.beginPath();
      ctx.moveTo(0, 0);
      ctx.lineTo(0.25 * s * Math.cos(angle), 0.25 * s * Math.sin(angle));
      ctx.stroke();
    }
  },
};

/** The page's icon (like the desktop's window icon): atoms in a black cup on a grey tile. */
export function drawPageIcon(ctx: CanvasRenderingContext2D, s: number): void {
  ctx.fillStyle = "rgb(159,159,159)";
  ctx.beginPath();
  ctx.roundRect(0, 0, s, s, s / 6);
  ctx.fill();
  ctx.strokeStyle = "rgb(79,79,79)";
  ctx.lineWidth = s / 32;
  ctx.stroke();
  // The cup y = k x^2 through (±0.38 s, 0.30 s) with its bottom at 0.80 s.
  const k = (0.8 - 0.3) / (0.38 * 0.38 * s);
  ctx.strokeStyle = BLACK;
  ctx.lineWidth = s / 16;
  ctx.beginPath();
  for (let x = -0.38 * s; x <= 0.38 * s + 1e-9; x += s / 64) {
    const y = 0.8 * s - k * x * x;
    if (x === -0.38 * s) ctx.moveTo(s / 2 + x, y);
    else ctx.lineTo(s / 2 + x, y);
  }
  ctx.stroke();
  const r = 0.085 * s;
  for (const [fx, fy] of [
    [0.5, 0.7],
    [0.34, 0.62],
    [0.66, 0.62],
    [0.5, 0.52],
    [0.6, 0.3],
  ]) {
    const g = ctx.createRadialGradient(
      fx * s - r / 3,
      fy * s - r / 2,
      r / 6,
      fx * s,
      fy * s - r / 4,
      r,
    );
    g.addColorStop(0, "rgb(200,250,255)");
    g.addColorStop(0.5, "rgb(30,215,245)");
    g.addColorStop(1, "rgb(12,90,110)");
    ctx.fillStyle = g;
    ctx.beginPath();
    ctx.arc(fx * s, fy * s - s / 32, r, 0, 2 * Math.PI);
    ctx.fill();
  }
}
