/** The simulation the game plays: the exact engine of `../physics`, seen as a SimLike. */
import { Simulation, type AtomSnapshot } from "../physics/index";
import { readTrace, replayTrace, traceText } from "../physics/trace";

/** The start's own count of the atoms a cup holds, for the settings (game/capacity.ts). */
export { startCapacity } from "../physics/wasm";
/** The WebAssembly core's bytes: the page hands them to its physics worker. */
export { coreBytes, haveCore, provideCore } from "../physics/wasm";
/** A fresh seed of the shared start generator, for a game that names none. */
export { randomSeed, SEED_PORTABLE_MAX, START_GENERATOR } from "../physics/start";
/** The room around the cup (the view places it on screen: view/screen.ts). */
export { CLASSIC_ROOM, roomTop, type Room } from "../physics/room";
export type { AtomSnapshot } from "../physics/index";
/** The physics' constants the game and the view use (game/constants.ts). */
export {
  ATOM_RADIUS,
  CURVATURE,
  ESCAPE_RULES,
  FPS,
  GRAVITY,
  N_ATOMS,
  TC_EXPONENT_CUP,
  TC_EXPONENT_SEED,
  type EscapeRule,
} from "../physics/constants";
import type { GameConfig } from "./rules";
import type { AtomArrays, GameSim, SimLike } from "./sim";

/** The physics' Simulation with snapshots kept between frames (no allocation per frame). */
export class EngineSim implements GameSim {
  private trappedSnap: AtomSnapshot | undefined;
  private escapedSnap: AtomSnapshot | undefined;
  private temperatureKey = "";
  private temperatureValue = 0;

  constructor(readonly sim: Simulation) {}

  get time() {
    return this.sim.time;
  }
  get nAtoms() {
    return this.sim.nAtoms;
  }
  get nTrapped() {
    return this.sim.nTrapped;
  }
  get nEscaped() {
    return this.sim.nEscaped;
  }
  get trapHeight() {
    return this.sim.trapHeight;
  }
  set trapHeight(h: number) {
    this.sim.trapHeight = h;
  }
  get rimHalfWidth() {
    return this.sim.rimHalfWidth;
  }
  get curvature() {
    return this.sim.curvature;
  }
  get gravity() {
    return this.sim.gravity;
  }
  /** T sums every trapped atom's energy: asked for several times a frame, computed once. */
  get temperature() {
    const s = this.sim;
    const key = `${s.time}|${s.collisionCount}|${s.nTrapped}|${s.trapHeight}`;
    if (key !== this.temperatureKey) {
      this.temperatureKey = key;
      this.temperatureValue = s.temperature;
    }
    return this.temperatureValue;
  }
  get initialTemperature() {
    return this.sim.initialTemperature;
  }
  get criticalTemperature() {
    return this.sim.criticalTemperature;
  }
  get tcExponent() {
    return this.sim.tcExponent;
  }
  get won() {
    return this.sim.won;
  }
  get winRule() {
    return this.sim.winRule;
  }
  get collisionCount() {
    return this.sim.collisionCount;
  }
  get room() {
    return this.sim.room;
  }
  get originLift() {
    return this.sim.originLift;
  }
  advance(dt: number): void {
    this.sim.advance(dt);
  }
  frame(height: number): void {
    this.sim.frame(height);
  }
  frameEnd(): void {
    this.sim.frameEnd();
  }
  get score() {
    return this.sim.score;
  }
  replay(runs: ReadonlyArray<readonly [number, number]>, limit: number): number {
    return this.sim.replay(runs, limit);
  }
  trapped(): AtomArrays {
    return (this.trappedSnap = this.sim.atoms("trapped", this.trappedSnap));
  }
  escaped(): AtomArrays {
    return (this.escapedSnap = this.sim.atoms("escaped", this.escapedSnap));
  }
}

export function makeSimulation(config: GameConfig): GameSim {
  const sim = new Simulation({
    nAtoms: config.nAtoms,
    radius: config.radius,
    tcExponent: config.tcExponent,
    escape: config.escape,
    ...(config.seed === null ? {} : { seed: config.seed }),
  });
  return new EngineSim(sim);
}

/** The text this engine writes for a golden trace's start and steps (the same, if it agrees). */
export function replayGolden(text: string): string {
  return traceText(replayTrace(readTrace(text)));
}

/** The physics' own switch to the won state, for a game's sim (tests of the condensate). */
export function forceWin(sim: SimLike): void {
  if (sim instanceof EngineSim) sim.sim.forceWin();
}
