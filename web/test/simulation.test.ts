// The web Simulation on the WebAssembly core: analytic cases, lifecycle, the win, the start,
// the state, bad input.
import { describe, expect, it } from "vitest";
import {
  GRAVITY,
  Simulation,
  WALL_MIN_NORMAL_SPEED,
  type SimulationOptions,
} from "../src/physics/index";
import { stateText } from "../src/physics/trace";
import { CLASSIC_ROOM } from "../src/physics/room";
import { screenOrigin, toScreen, WINDOW, windowRoom } from "../src/view/screen";

const G = GRAVITY;
const A = 0.01;

/** A simulation with exactly these atoms, the rim out of reach, events recorded. */
function make(pos: number[][], vel: number[][], extra: SimulationOptions = {}): Simulation {
  return new Simulation({
    positions: pos as [number, number][],
    velocities: vel as [number, number][],
    trapHeight: Infinity,
    recordEvents: true,
    ...extra,
  });
}

function kinds(sim: Simulation): string[] {
  return sim.eventLog.map((e) => e.kind);
}

function close(a: number, b: number, tol = 1e-12): void {
  expect(Math.abs(a - b)).toBeLessThanOrEqual(tol * Math.max(1, Math.abs(b)));
}

describe("collisions", () => {
  it("head on, unequal masses: 1D elastic velocities at t = 76/3", () => {
    const sim = make(
      [
        [-50, 200],
        [50, 200],
      ],
      [
        [2, 0],
        [-1, 0],
      ],
      { mass: [1, 3] },
    );
    const e0 = sim.totalEnergy();
    sim.advance(30);
    expect(kinds(sim)).toEqual(["pair"]);
    close(sim.eventLog[0].time, 76 / 3);
    const v = sim.velocities;
    close(v[0], -2.5);
    close(v[2], 0.5);
    close(v[1], -G * 30);
    close(v[0] + 3 * v[2], 2 - 3);
    close(sim.totalEnergy(), e0, 1e-14);
  });

  it("glancing, unequal masses: momentum exchanged along the line of centres", () => {
    const sim = make(
      [
        [-60, 300],
        [0, 288],
      ],
      [
        [3, 0],
        [0, 0],
      ],
      { mass: [2, 1] },
    );
    sim.advance(14);
    expect(kinds(sim)).toEqual(["pair"]);
    close(sim.eventLog[0].time, (60 - Math.sqrt(24 ** 2 - 12 ** 2)) / 3);
    const v = sim.velocities;
    const s3 = Math.sqrt(3);
    close(v[0], 1.5);
    close(v[1], s3 / 2 - G * 14);
    close(v[2], 3);
    close(v[3], -s3 - G * 14);
  });

  it("a dropped atom bounces on the vertex back to its height", () => {
    const sim = make([[0, 100]], [[0, 0]]);
    const fall = Math.sqrt((2 * 100) / G);
    sim.advance(2 * fall);
    expect(kinds(sim)).toEqual(["wall"]);
    close(sim.eventLog[0].time, fall);
    close(sim.positions[1], 100, 1e-9);
  });
});

describe("the rim, the knife, the lifecycle", () => {
  it("an atom over the rim escapes, falls out of the window and is gone", () => {
    const sim = make([[150, 240]], [[3, 0]], { trapHeight: 200 });
    sim.advance(10);
    expect(sim.nTrapped).toBe(0);
    expect(sim.nEscaped).toBe(1);
    expect(sim.escapedPositions.length).toBe(2);
    sim.advance(200);
    expect(kinds(sim)).toEqual(["escape", "gone"]);
    expect(sim.nEscaped).toBe(0);
  });

  it("a trapped atom thrown high is never removed", () => {
    const sim = make([[0, 10]], [[0, 40]], { trapHeight: 450 });
    sim.advance(200);
    expect(sim.nTrapped).toBe(1);
  });

  it("the knife removes atoms above m g H at once, when H is lowered", () => {
    const sim = make(
      [
        [0, 20],
        [100, 150],
      ],
      [
        [0, 0],
        [0, 0],
      ],
      { escape: "knife", trapHeight: 400 },
    );
    expect(sim.nTrapped).toBe(2);
    sim.trapHeight = 120;
    expect(sim.nTrapped).toBe(1);
    expect(kinds(sim)).toEqual(["knife"]);
    expect(sim.escape).toBe("knife");
  });
});

describe("stalls (issue 13)", () => {
  it("an atom at rest on the vertex rests: bounded hops at the floor speed", () => {
    const sim = make([[0, 1e-300]], [[0, 0]]);
    let most = 0;
    for (let f = 0; f < 30; f++) {
      const before = sim.wallCollisionCount;
      sim.advance(1);
      most = Math.max(most, sim.wallCollisionCount - before);
    }
    expect(most).toBeLessThanOrEqual(170);
    expect(sim.positions[0]).toBe(0);
    expect(sim.positions[1]).toBeLessThanOrEqual(
      (WALL_MIN_NORMAL_SPEED ** 2 / (2 * G)) * (1 + 1e-9),
    );
    expect(sim.totalEnergy()).toBeLessThanOrEqual(0.5 * WALL_MIN_NORMAL_SPEED ** 2 * (1 + 1e-9));
  });

  it("a grazing atom slides with its energy kept", () => {
    const x = 50;
    const norm = Math.hypot(1, 2 * A * x);
    const sim = make([[x, A * x * x + 1e-9]], [[3 / norm, (3 * 2 * A * x) / norm]]);
    const e0 = sim.totalEnergy();
    sim.advance(30);
    const v2 = 2 * sim.totalEnergy();
    expect(sim.wallCollisionCount).toBeLessThanOrEqual(
      2 + (30 * (0.5 * G + A * v2)) / WALL_MIN_NORMAL_SPEED,
    );
    close(sim.totalEnergy(), e0);
  });
});

describe("the win", () => {
  it("forceWin stops pair collisions and damps the bounces until the gas settles", () => {
    const sim = Simulation.classic(3);
    sim.advance(20);
    expect(sim.won).toBe(false);
    sim.forceWin();
    const pairs = sim.pairCollisionCount;
    const e0 = sim.totalEnergy();
    sim.advance(600);
    expect(sim.pairCollisionCount).toBe(pairs);
    expect(sim.totalEnergy()).toBeLessThan(0.5 * e0);
    const v = sim.velocities;
    for (let k = 0; k < v.length; k += 2) expect(Math.hypot(v[k], v[k + 1])).toBeLessThan(2);
  });

  it("a falling rim wins (T < Tc(N)); win: false never does", () => {
    for (const win of [true, false]) {
      const sim = Simulation.classic(1, { win });
      let won = false;
      for (let f = 0; f < 1800 && !won; f++) {
        sim.trapHeight = 400 - (360 * f) / 1799;
        sim.advance(1);
        won = sim.won;
      }
      expect(won).toBe(win);
      expect(sim.winRule).toBe(win);
      if (!win) expect(sim.temperature).toBeLessThan(sim.criticalTemperature);
    }
  });

  it("Tc(N) = 0.75 T(0) (N / N0)^p", () => {
    const sim = Simulation.classic(5);
    close(sim.criticalTemperature, 0.75 * sim.initialTemperature);
    expect(Simulation.classic(5, { tcExponent: 0.4 }).tcExponent).toBe(0.4);
  });
});

describe("the start", () => {
  it("is the original's rows of cells, the same for the same seed", () => {
    const a = Simulation.classic(7);
    const b = Simulation.classic(7);
    const c = Simulation.classic(8);
    expect(a.nTrapped).toBe(49);
    expect(a.seed).toBe(7);
    expect(Array.from(a.positions)).toEqual(Array.from(b.positions));
    expect(Array.from(a.positions)).not.toEqual(Array.from(c.positions));
    expect(a.trapHeight).toBe(400);
    const p = a.positions;
    // row 0 is one atom within 8 px of the axis, and speeds follow the rows
    expect(Math.abs(p[0])).toBeLessThanOrEqual(8);
    const v = a.velocities;
    const s0 = Math.hypot(v[0], v[1]);
    expect(s0).toBeGreaterThanOrEqual(100 / 30);
    expect(s0).toBeLessThanOrEqual(110 / 30);
    // no overlap, every centre inside the cup
    for (let i = 0; i < 49; i++) {
      expect(p[2 * i + 1]).toBeGreaterThan(A * p[2 * i] ** 2);
      for (let j = i + 1; j < 49; j++)
        expect(Math.hypot(p[2 * j] - p[2 * i], p[2 * j + 1] - p[2 * i + 1])).toBeGreaterThanOrEqual(
          24,
        );
    }
  });

  it("knows its room, not the window; the view's screen map places it (issue 26.3)", () => {
    const sim = Simulation.classic(1);
    expect(sim.room).toEqual(CLASSIC_ROOM);
    expect(sim.originLift).toBe(12);
    expect(screenOrigin(sim)).toEqual([296, 532]);
    expect(Array.from(toScreen(sim, [0, 0, 10, 20]))).toEqual([296, 532, 306, 512]);
    expect(windowRoom(WINDOW)).toEqual(CLASSIC_ROOM);
    expect(sim.rimHalfWidth).toBe(200);
    // A room of another size: escaped atoms leave at its edges; the state names it by window.
    const wide = new Simulation({ nAtoms: 10, room: windowRoom([800, 700]), seed: 3 });
    expect(wide.toState().window).toEqual([800, 700]);
    expect(Simulation.fromState(wide.toState()).room).toEqual(windowRoom([800, 700]));
  });

  it("hands out per-atom snapshots without allocating when given one", () => {
    const sim = Simulation.classic(2);
    const snap = sim.atoms("trapped");
    expect(snap.count).toBe(49);
    sim.advance(5);
    const again = sim.atoms("trapped", snap);
    expect(again).toBe(snap);
    const p = sim.positions;
    expect(snap.x[3]).toBe(p[6]);
    expect(snap.energy[3]).toBe(sim.energies()[3]);
  });

  it("carries every atom of a snapshot to now as Python's World.state_at does", () => {
    const sim = new Simulation({ nAtoms: 300, radius: 4, seed: 11, trapHeight: 120 });
    sim.advance(40.5); // atoms escaped and falling, each on its own clock
    const st = sim.toState();
    const a = st.atoms;
    const g = st.gravity;
    for (const group of ["trapped", "escaped"] as const) {
      const snap = sim.atoms(group);
      const want = a.status.flatMap((s, i) => (s === group ? [i] : []));
      expect(snap.count).toBe(want.length);
      expect(want.length).toBeGreaterThan(0);
      want.forEach((i, k) => {
        const dt = st.time - a.t[i];
        expect(snap.index[k]).toBe(i);
        expect(snap.x[k]).toBe(a.x[i] + a.vx[i] * dt);
        expect(snap.y[k]).toBe(a.y[i] + a.vy[i] * dt - 0.5 * g * dt * dt);
        expect(snap.vx[k]).toBe(a.vx[i]);
        expect(snap.vy[k]).toBe(a.vy[i] - g * dt);
        expect([snap.radius[k], snap.mass[k]]).toEqual([a.radius[i], a.mass[i]]);
        const m = a.mass[i];
        expect(snap.energy[k]).toBe(
          0.5 * m * (a.vx[i] * a.vx[i] + a.vy[i] * a.vy[i]) + m * g * a.y[i],
        );
      });
    }
  });
});

describe("the state", () => {
  it("resumes exactly: save, load, go on = go on", () => {
    const straight = Simulation.classic(4, { recordEvents: true });
    const saved = Simulation.classic(4, { recordEvents: true });
    straight.advance(12.5);
    saved.advance(12.5);
    const text = JSON.stringify(saved.toState());
    const resumed = Simulation.fromState(text, { recordEvents: true });
    expect(stateText(resumed)).toBe(stateText(saved));
    straight.trapHeight = 80;
    resumed.trapHeight = 80;
    straight.advance(300);
    resumed.advance(300);
    const tail = straight.eventLog.slice(straight.eventLog.length - resumed.eventLog.length);
    expect(resumed.eventLog).toEqual(tail);
    expect(stateText(resumed)).toBe(stateText(straight));
    expect(resumed.won).toBe(straight.won);
  });

  it("keeps -0 and an infinite rim through JSON", () => {
    const sim = make([[0, 50]], [[-0, 0]]);
    const state = sim.toState();
    expect(state.trap_height).toBe("inf");
    const back = Simulation.fromState(stateText(sim));
    expect(Object.is(back.velocities[0], -0)).toBe(true);
    expect(back.trapHeight).toBe(Infinity);
  });

  it("loads a condensate whose atoms overlap (after the win they no longer collide)", () => {
    const atoms = { x: [0, 5], y: [10, 10], vx: [0, 0], vy: [0, 0] };
    expect(() => Simulation.fromState({ atoms })).toThrow("atoms 0 and 1 overlap");
    const sim = Simulation.fromState({ won: true, atoms });
    sim.advance(30);
    expect(sim.won).toBe(true);
    expect(sim.pairCollisionCount).toBe(0);
    expect(() => Simulation.fromState({ won: true, atoms: { ...atoms, y: [-1, 10] } })).toThrow(
      "atom 0",
    );
  });

  it("fills defaults for a minimal hand-written state", () => {
    const sim = Simulation.fromState({
      atoms: { x: [0, 30], y: [10, 40], vx: [1, 0], vy: [0, 0] },
    });
    expect(sim.nAtoms).toBe(2);
    expect(sim.trapHeight).toBe(400);
    expect(Array.from(sim.radii)).toEqual([12, 12]);
    close(sim.initialTemperature, sim.temperature);
  });

  it.each([
    [{ atoms: { x: [0], y: [10], vx: [0] } }, "state.atoms.vy"],
    [{ atoms: { x: [0], y: [10], vx: [0], vy: [NaN] } }, "state.atoms.vy[0]"],
    [{ atoms: { x: [0], y: [-1], vx: [0], vy: [0] } }, "atom 0"],
    [{ atoms: { x: [0, 5], y: [10, 10], vx: [0, 0], vy: [0, 0] } }, "atoms 0 and 1 overlap"],
    [{ time: 1, atoms: { x: [0], y: [10], vx: [0], vy: [0], t: [2] } }, "state.atoms.t[0]"],
    [{ escape: "net", atoms: { x: [0], y: [10], vx: [0], vy: [0] } }, "state.escape"],
    [{ format: "other", atoms: { x: [0], y: [10], vx: [0], vy: [0] } }, "state.format"],
    [{ colour: 1, atoms: { x: [0], y: [10], vx: [0], vy: [0] } }, "state must be free"],
    [{ energy_sum: 5, atoms: { x: [0], y: [10], vx: [0], vy: [0] } }, "state.energy_sum"],
    ["{not json", "state must be JSON"],
  ])("rejects a bad state with a RangeError naming the field (%#)", (state, name) => {
    expect(() => Simulation.fromState(state as never)).toThrow(RangeError);
    expect(() => Simulation.fromState(state as never)).toThrow(name);
  });
});

describe("bad input", () => {
  it.each([
    [{ nAtoms: -3 }, "nAtoms"],
    [{ nAtoms: 2.5 }, "nAtoms"],
    [{ radius: NaN }, "radius"],
    [{ radius: -1 }, "radius"],
    [{ mass: [1, 2] }, "mass"],
    [{ curvature: 0 }, "curvature"],
    [{ gravity: Infinity }, "gravity"],
    [{ trapHeight: NaN }, "trapHeight"],
    [{ tcExponent: -1 }, "tcExponent"],
    [{ room: { left: 10, right: 10, below: 10, above: 10 } }, "room must be a room of sides"],
    [{ window: [640, 672] } as never, "options must be free of unknown names"],
    [{ seed: -1 }, "seed"],
    [{ seed: 1.5 }, "seed"],
    [{ escape: "net" as never }, "escape"],
    [{ win: 1 as never }, "win"],
    [{ nAtoms: 2000, radius: 12 }, "nAtoms: 2000 atoms of radius 12 do not fit"],
    [{ radius: [12, 10] }, "radius"],
    [{ trapheight: 3 } as never, "options must be free of unknown names"],
    [{ positions: [[0, 10]] }, "velocities"],
  ])("throws a RangeError naming the parameter (%#)", (options, name) => {
    expect(() => new Simulation(options as SimulationOptions)).toThrow(RangeError);
    expect(() => new Simulation(options as SimulationOptions)).toThrow(name);
  });

  it("rejects overlapping or outside starting atoms, naming the first offenders", () => {
    const vel = [
      [0, 0],
      [0, 0],
      [0, 0],
      [0, 0],
    ];
    const overlap = () =>
      make(
        [
          [-100, 200],
          [0, 50],
          [10, 55],
          [-90, 205],
        ],
        vel,
      );
    expect(overlap).toThrow(RangeError);
    expect(overlap).toThrow(
      "positions must not overlap: every pair at least r_i + r_j apart (atoms 0 and 3 are",
    );
    const outside = () =>
      make(
        [
          [-100, 200],
          [50, 24],
          [0, 50],
          [60, 10],
        ],
        vel,
      );
    expect(outside).toThrow("(atom 1 at (50, 24) is below the wall y = 25)");
    // touching is allowed, and so is a centre on the wall
    expect(() =>
      make(
        [
          [-12, 50],
          [12, 50],
          [50, 25],
        ],
        [
          [0, 0],
          [0, 0],
          [0, 0],
        ],
      ),
    ).not.toThrow();
  });

  it("rejects a bad dt or trap height and leaves the simulation as it was", () => {
    const sim = Simulation.classic(1);
    for (const dt of [-1, NaN, Infinity]) expect(() => sim.advance(dt)).toThrow("dt");
    for (const h of [0, -5, NaN]) expect(() => (sim.trapHeight = h)).toThrow("trapHeight");
    expect(sim.trapHeight).toBe(400);
    expect(sim.time).toBe(0);
  });
});
