// The layouts' use of the screen (issue 24): a tall phone filled top to bottom with the
// controls at its bottom edge and the charts between scene and controls; wide screens
// with the charts beside the scene.
import fc from "fast-check";
import { describe, expect, test } from "vitest";
import { layoutFor, SCENE_W, TALL_SCENE_H } from "../../src/view/geometry";

const none = { energy: false, path: false };
const both = { energy: true, path: true };

describe("layouts use the screen", () => {
  test("a 390 x 844 phone: no band above or below, the controls at the bottom edge", () => {
    const l = layoutFor(390, 844, none);
    expect(l.mode).toBe("tall");
    expect(l.offsetY).toBeLessThan(1);
    expect(l.height * l.scale).toBeGreaterThan(844 - 2);
    expect(l.width * l.scale).toBeCloseTo(390, 6);
    const bottom = l.buttons.fullscreen.y + l.buttons.fullscreen.h;
    expect((l.height - bottom) * l.scale).toBeLessThan(16);
    expect(l.slider.y).toBeGreaterThan(l.height - 330);
  });

  test("charts open on a phone: between the scene and the controls, nothing overlaps", () => {
    const l = layoutFor(390, 844, both);
    const e = l.charts.energy!;
    const p = l.charts.path!;
    expect(e.y).toBe(TALL_SCENE_H);
    expect(p.y).toBeCloseTo(e.y + e.h, 9);
    expect(l.strip!.y).toBeCloseTo(p.y + p.h, 9);
    expect(l.slider.y).toBeGreaterThan(l.strip!.y);
    expect(l.buttons.pause.y + l.buttons.pause.h).toBeLessThanOrEqual(l.height);
    // The page is at most a thin band narrower than the phone.
    expect(l.width * l.scale).toBeGreaterThan(390 * 0.9);
  });

  test("wide screens: the charts beside the scene, not over it", () => {
    for (const [w, h] of [
      [1920, 1080],
      [1280, 720],
      [844, 390],
    ]) {
      const l = layoutFor(w, h, both);
      expect(l.mode).toBe(w < 1000 ? "side" : "wide");
      expect(l.charts.energy!.x).toBeGreaterThanOrEqual(SCENE_W);
      expect(l.charts.path!.x).toBeGreaterThanOrEqual(SCENE_W);
    }
  });

  test("any portrait screen: the tall layout fits and its strip reaches the bottom", () => {
    fc.assert(
      fc.property(
        fc.integer({ min: 200, max: 3000 }),
        fc.integer({ min: 200, max: 6000 }),
        fc.boolean(),
        fc.boolean(),
        (w, h, energy, path) => {
          const l = layoutFor(w, h, { energy, path });
          if (l.mode !== "tall") return true;
          const fits =
            l.offsetY >= -1e-9 &&
            l.offsetX >= -1e-9 &&
            l.offsetY + l.height * l.scale <= h + 1e-6 &&
            l.offsetX + l.width * l.scale <= w + 1e-6;
          return fits && Math.abs(l.strip!.y + l.strip!.h - l.height) < 1e-9;
        },
      ),
    );
  });
});
