/**
 * A tall phone's readout in the spare height between the scene and the controls: the atoms
 * left and the temperature against Tc, drawn large enough to read at arm's length (the
 * scene's own thermometer is a finger wide there).
 */
import * as C from "./colors";
import type { Rect } from "./geometry";
import { mercuryFraction } from "./scene";
import { drawText, fitSize } from "./text";
import type { SimLike } from "../game/sim";
import { t } from "../i18n";

/** Largest text of the readout, logical px (about 70 CSS px on a 390 px wide phone). */
const COUNT_MAX = 120;
const COUNT_MIN = 24;

/** Draw the readout in r; returns the atom count's text size (logical px). */
export function drawReadout(ctx: CanvasRenderingContext2D, r: Rect, sim: SimLike): number {
  // The count takes the upper half, the thermometer the lower (its bar, then its labels).
  const text = t("status.atoms", { n: sim.nTrapped });
  const size = fitSize(ctx, text, Math.min(COUNT_MAX, r.h * 0.4), r.w, COUNT_MIN);
  drawText(ctx, text, size, C.TEXT, r.x + r.w / 2, r.y + r.h * 0.25, "center");
  const barH = Math.max(16, r.h * 0.16);
  const labelSize = Math.max(COUNT_MIN, barH);
  const bar = { x: r.x + labelSize * 1.2, y: r.y + r.h * 0.55, w: r.w - labelSize * 1.2, h: barH };
  ctx.fillStyle = C.GLASS;
  ctx.beginPath();
  ctx.roundRect(bar.x, bar.y, bar.w, bar.h, bar.h / 2);
  ctx.fill();
  const inset = 4;
  const fill = mercuryFraction(sim.temperature, sim.initialTemperature);
  ctx.fillStyle = C.MERCURY;
  ctx.beginPath();
  const mercuryW = Math.max(bar.h - 2 * inset, fill * (bar.w - 2 * inset));
  ctx.roundRect(bar.x + inset, bar.y + inset, mercuryW, bar.h - 2 * inset, (bar.h - 2 * inset) / 2);
  ctx.fill();
  // Tc: a mark across the bar and its name under it (the scene's thermometer's words).
  const tcX =
    bar.x +
    inset +
    mercuryFraction(sim.criticalTemperature, sim.initialTemperature) * (bar.w - 2 * inset);
  ctx.fillStyle = C.BLACK;
  ctx.fillRect(tcX - 2, bar.y - 6, 4, bar.h + 12);
  drawText(ctx, "T", labelSize, C.TEXT, r.x, bar.y + bar.h / 2, "midleft");
  drawText(ctx, "Tc", labelSize, C.TEXT, tcX, bar.y + bar.h + 8, "midtop");
  return size;
}
