/**
 * The page's screen: the layout for the viewport (scene, controls, charts; see
 * view/geometry), the canvas sized at the device's pixel ratio, and the mapping between
 * logical scene px and CSS px for elements over the canvas and for pointer events.
 * Python's twin: `src/evapcool/app/layout.py` (docs/twins.md).
 */
import { layoutFor, PLAY_RECT, type ChartsShown, type Layout, type Rect } from "../view/geometry";

export interface Zoom {
  k: number;
  cx: number;
  cy: number;
  x: number;
  y: number;
}

export class Screen {
  layout!: Layout;
  /** Device px per CSS px. */
  dpr = 1;

  constructor(private readonly canvas: HTMLCanvasElement) {}

  /** Lay out for the window as it is now, and size the canvas to it. */
  fit(charts: ChartsShown): void {
    const vw = Math.max(1, window.innerWidth);
    const vh = Math.max(1, window.innerHeight);
    this.layout = layoutFor(vw, vh, charts);
    this.dpr = Math.max(1, window.devicePixelRatio || 1);
    const c = this.canvas;
    c.style.width = `${vw}px`;
    c.style.height = `${vh}px`;
    const w = Math.round(vw * this.dpr);
    const h = Math.round(vh * this.dpr);
    if (c.width !== w || c.height !== h) {
      c.width = w;
      c.height = h;
    }
  }

  /** Logical rect -> CSS box of an element over the canvas. */
  place(el: HTMLElement, r: Rect): void {
    const l = this.layout;
    el.style.left = `${l.offsetX + r.x * l.scale}px`;
    el.style.top = `${l.offsetY + r.y * l.scale}px`;
    el.style.width = `${r.w * l.scale}px`;
    el.style.height = `${r.h * l.scale}px`;
  }

  /** A rect drawn under a panel's zoom (overlayZoom) -> the CSS box of an element over it. */
  placeZoomed(el: HTMLElement, r: Rect, z: Zoom): void {
    this.place(el, {
      x: z.x + (r.x - z.cx) * z.k,
      y: z.y + (r.y - z.cy) * z.k,
      w: r.w * z.k,
      h: r.h * z.k,
    });
  }

  /** The whole viewport in logical px, less a margin (the projector's black bands too). */
  visibleBox(margin: number): Rect {
    const l = this.layout;
    const vw = parseFloat(this.canvas.style.width) || l.width * l.scale;
    const vh = parseFloat(this.canvas.style.height) || l.height * l.scale;
    const x = -l.offsetX / l.scale;
    const y = -l.offsetY / l.scale;
    return {
      x: x + margin,
      y: y + margin,
      w: vw / l.scale - 2 * margin,
      h: vh / l.scale - 2 * margin,
    };
  }

  /** A pointer's client position -> logical scene px. */
  toLogical(clientX: number, clientY: number): [number, number] {
    const r = this.canvas.getBoundingClientRect();
    const l = this.layout;
    return [(clientX - r.left - l.offsetX) / l.scale, (clientY - r.top - l.offsetY) / l.scale];
  }

  /**
   * Panels over the play area (help, scores, settings) drawn larger in the tall layout,
   * centred on the whole scene and strip, so their text stays readable on a phone: the
   * point (cx, cy) of the play area goes to (x, y), scaled by k.
   */
  overlayZoom(): Zoom {
    const cx = PLAY_RECT.x + PLAY_RECT.w / 2;
    const cy = PLAY_RECT.y + PLAY_RECT.h / 2;
    const l = this.layout;
    if (l.mode !== "tall" || !l.strip) return { k: 1, cx, cy, x: cx, y: cy };
    const bottom = l.strip.y + l.strip.h;
    const k = Math.min((l.width - 16) / (PLAY_RECT.w - 24), (bottom - 8) / PLAY_RECT.h);
    return { k, cx, cy, x: l.width / 2, y: bottom / 2 };
  }
}
