import fc from "fast-check";
import { describe, expect, test } from "vitest";
import {
  CONTROL_ORDER,
  layoutFor,
  MIN_TARGET_CSS,
  SCENE_H,
  SCENE_W,
} from "../../src/view/geometry";
import { cupOutline, mercuryFraction, scaleRow } from "../../src/view/scene";
import { spherePixels } from "../../src/view/sprites";
import { packetSize } from "../../src/view/condensate";
import { EnergyPanel, logTicks, niceStep, PathPanel } from "../../src/view/panels";
import { forceWin, makeSimulation } from "../../src/game/engine";
import { DEFAULT_CONFIG } from "../../src/game/rules";
import { SliderModel } from "../../src/view/widgets";
import { actionFor, BINDINGS, helpRows } from "../../src/app/bindings";
import { t } from "../../src/i18n";
import { FrameStats } from "../../src/app/stats";

describe("layout", () => {
  const none = { energy: false, path: false };
  test("a desktop window gets the desktop's scene, scaled with its aspect kept", () => {
    const l = layoutFor(1280, 672, none);
    expect(l.mode).toBe("wide");
    expect(l.scale).toBe(1);
    expect(l.offsetX).toBe((1280 - SCENE_W) / 2);
    expect(layoutFor(1280, 672, { energy: true, path: false }).width).toBe(SCENE_W + 520);
  });

  test("any viewport: everything on screen; portrait phones: big controls below the scene", () => {
    fc.assert(
      fc.property(
        fc.integer({ min: 200, max: 4000 }),
        fc.integer({ min: 200, max: 4000 }),
        (w, h) => {
          const l = layoutFor(w, h, none);
          const fits =
            l.offsetX >= -1e-9 &&
            l.offsetY >= -1e-9 &&
            l.offsetX + l.width * l.scale <= w + 1e-6 &&
            l.offsetY + l.height * l.scale <= h + 1e-6;
          return fits && (l.mode === "tall" ? h > w : true) && (l.mode !== "side" || w >= h);
        },
      ),
    );
    const phone = layoutFor(390, 844, none);
    expect(phone.mode).toBe("tall");
    expect(phone.buttons.pause.w * phone.scale).toBeGreaterThanOrEqual(MIN_TARGET_CSS);
    expect(phone.slider.y).toBeGreaterThan(600);
    expect(layoutFor(844, 390, none).mode).toBe("side");
    expect(SCENE_H).toBe(672);
  });
});

describe("scene", () => {
  test("thermometer: T / (1.2 T0), clipped, on rows 572 (empty) to 88 (full)", () => {
    expect(mercuryFraction(60, 100)).toBeCloseTo(0.5, 12);
    expect(mercuryFraction(500, 100)).toBe(1);
    expect(mercuryFraction(5, 0)).toBe(0);
    expect(scaleRow(0)).toBe(572);
    expect(scaleRow(1)).toBe(88);
  });

  test("the drawn cup is at distance R outside the centres' wall", () => {
    fc.assert(
      fc.property(
        fc.double({ min: 0.5, max: 30, noNaN: true }),
        fc.double({ min: 25, max: 450, noNaN: true }),
        (r, h) => {
          const a = 0.01;
          const pts = cupOutline(a, Math.sqrt(h / a), r, 41);
          for (let k = 0; k < 41; k++) {
            const [x, y] = [pts[2 * k], pts[2 * k + 1]];
            // Distance to y = a x^2 by minimising over the curve near the sample.
            let best = Infinity;
            for (let j = -2000; j <= 2000; j++) {
              const u = x + (j / 2000) * 2 * r;
              best = Math.min(best, Math.hypot(u - x, a * u * u - y));
            }
            if (Math.abs(best - r) > 0.02 * r + 1e-3) return false;
          }
          return true;
        },
      ),
      { numRuns: 30 },
    );
  });

  test("atom sprite: opaque centre, transparent corners, lit from the upper left", () => {
    const { size, data } = spherePixels(12);
    expect(size).toBe(26);
    const at = (x: number, y: number) =>
      Array.from(data.slice((y * size + x) * 4, (y * size + x) * 4 + 4));
    expect(at(13, 13)[3]).toBe(255);
    expect(at(0, 0)[3]).toBe(0);
    expect(at(8, 8)[0] + at(8, 8)[1]).toBeGreaterThan(at(18, 18)[0] + at(18, 18)[1]);
  });

  test("the condensate grows with the atoms left", () => {
    const [w1, h1] = packetSize(10, 12, 0.01);
    const [w2, h2] = packetSize(40, 12, 0.01);
    expect(w2).toBeGreaterThan(w1);
    expect(h2).toBeGreaterThan(h1);
    expect(packetSize(0, 12, 0.01)).toEqual([0, 0]);
  });

  test("chart ticks", () => {
    expect(niceStep(100)).toBe(20);
    expect(logTicks(1, 61)).toEqual([1, 2, 5, 10, 20, 50]);
  });

  test("slider: the desktop's value <-> knob arithmetic", () => {
    let height = 400;
    const s = new SliderModel(25, 450, () => height);
    const bar = { x: 240, y: 611, w: 272, h: 8 };
    expect(s.knobX(bar)).toBe(Math.round(240 + (272 * 375) / 425));
    expect(s.valueAt(100, bar)).toBe(25);
    expect(s.valueAt(240 + 136, bar)).toBe(237.5);
    // The knob rests where the model is, read when drawn: nobody writes it back...
    height = 100;
    expect(s.value).toBe(100);
    // ...and a drag holds it where the pointer is until released.
    s.hold(300);
    height = 90;
    expect([s.value, s.dragging]).toEqual([300, true]);
    s.release();
    expect([s.value, s.dragging]).toEqual([90, false]);
  });
});

describe("keys and help", () => {
  test("every key of the README's table has an action; the help lists them all", () => {
    const readme: Record<string, string> = {
      " ": "pause",
      r: "restart",
      ArrowLeft: "lower",
      ArrowDown: "lower",
      ArrowRight: "raise",
      ArrowUp: "raise",
      s: "step",
      "+": "faster",
      "-": "slower",
      e: "energy",
      g: "path",
      t: "table",
      Delete: "clear",
      x: "clear",
      o: "settings",
      Enter: "next",
      F11: "fullscreen",
      h: "help",
      F1: "help",
      Escape: "escape",
      R: "restart",
      H: "help",
    };
    for (const [key, action] of Object.entries(readme)) expect(actionFor(key)).toBe(action);
    expect(actionFor("q")).toBeUndefined();
    const labels = helpRows().map(([k]) => k);
    // Named in the active language (a help.key.* message) or by the key cap itself.
    for (const b of BINDINGS)
      expect(labels).toContain(b.label.startsWith("help.") ? t(b.label) : b.label);
    expect(labels).toContain("Space");
  });

  test("frame statistics: median, p95 and the rate over the span", () => {
    const st = new FrameStats(10);
    for (let k = 0; k < 30; k++) st.add(k * 20, k % 10);
    const s = st.summary(10);
    expect(s.frames).toBe(10);
    expect(s.medianMs).toBe(4.5);
    expect(s.fps).toBeCloseTo(50, 9);
  });
});

describe("tap targets", () => {
  test("a tap under a target hits it; near small ones, the nearest within 44 px", async () => {
    const { pickTarget } = await import("../../src/app/app");
    const t = (x: number, y: number, w: number, h: number, action: string) => ({
      rect: { x, y, w, h },
      action,
    });
    const targets = [
      t(100, 100, 20, 20, "a"),
      t(100, 140, 20, 20, "b"),
      t(0, 0, 600, 600, "close"),
    ];
    expect(pickTarget(targets, 110, 110, 70)?.action).toBe("a");
    expect(pickTarget(targets, 110, 133, 70)?.action).toBe("close");
    expect(pickTarget(targets.slice(0, 2), 110, 133, 70)?.action).toBe("b");
    expect(pickTarget(targets.slice(0, 2), 110, 126, 70)?.action).toBe("a");
    expect(pickTarget(targets.slice(0, 2), 300, 300, 70)).toBeNull();
  });
});

describe("a phone on its side (issue 27.3)", () => {
  test("every control beside the scene, 52 CSS px or more; the slider upright and long", () => {
    const none = { energy: false, path: false };
    for (const charts of [none, { energy: true, path: true }]) {
      const l = layoutFor(844, 390, charts);
      expect(l.mode).toBe("side");
      for (const name of CONTROL_ORDER) {
        const b = l.buttons[name];
        expect(b.w * l.scale).toBeGreaterThanOrEqual(charts.energy ? 44 : 52);
        expect(b.x).toBeGreaterThanOrEqual(SCENE_W);
        expect(l.offsetX + (b.x + b.w) * l.scale).toBeLessThanOrEqual(844);
        expect(l.offsetY + (b.y + b.h) * l.scale).toBeLessThanOrEqual(390);
      }
      // Upright, over most of the height: 1 CSS px moves the trap by at most 1.4 units (1.6
      // with the charts open), where the lying slider of before moved it by 2.7.
      expect(l.slider.h).toBeGreaterThan(l.slider.w);
      expect((450 - 25) / (l.slider.h * l.scale)).toBeLessThan(charts.energy ? 1.6 : 1.4);
    }
    expect(layoutFor(1280, 800, none).buttons.help.y).toBe(6);
  });
});

describe("one temperature in the charts (issue 49.7)", () => {
  test("after the win the energy chart holds the win's T, as the path chart does", () => {
    const sim = makeSimulation({ ...DEFAULT_CONFIG, seed: 7 });
    const [energy, path] = [new EnergyPanel(), new PathPanel()];
    const record = () => {
      energy.record(sim, sim.trapped(), 1);
      path.record(sim, 1);
    };
    sim.advance(1);
    record();
    forceWin(sim);
    record();
    const tWin = sim.temperature;
    for (let k = 0; k < 240; k++) {
      sim.advance(1);
      record();
    }
    expect(sim.temperature).toBeLessThan(0.5 * tWin); // the atoms settled meanwhile
    expect(energy.temperature).toBe(tWin);
    expect(path.t[path.t.length - 1]).toBe(tWin);
    energy.record(sim, sim.trapped(), 2); // a new game records again
    expect(energy.temperature).toBe(sim.temperature);
  });

  test("the energy chart's readout is the desktop's: N and T, no second scale", () => {
    expect(t("chart.readout_energy", { n: 49, t: "36.4" })).toBe("N = 49   T = 36.4");
    expect(t("page.readout_energy", { n: 49, t: "36.4", kt: "14.6" })).toBe("page.readout_energy");
  });
});
