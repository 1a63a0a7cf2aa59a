/** The simulation the game plays: the exact engine of `../physics`, seen as a SimLike. */
import { Simulation, type AtomSnapshot } from "../physics/index";
import { readTrace, replayTrace, traceText } from "../physics/trace";
import type { EscapeRule } from "../physics/constants";

/** The start's own count of the atoms a cup holds, for the settings (game/capacity.ts). */
export { startCapacity } from "../physics/instance";
/** The WebAssembly core's bytes: the page hands them to its physics worker. */
export { coreBytes, haveCore, provideCore } from "../physics/instance";
/** A fresh seed of the shared start generator, for a game that names none. */
export { randomSeed, SEED_PORTABLE_MAX, START_GENERATOR } from "../physics/start";
/** The room around the cup (the view places it on screen: view/screen.ts). */
export { CLASSIC_ROOM, roomTop, type Room } from "../physics/room";
export type { AtomSnapshot, Simulation } from "../physics/index";
/** The physics' constants the game and the view use (SPEC section 1). */
export {
  ATOM_RADIUS,
  CURVATURE,
  ESCAPE_RULES,
  FPS,
  N_ATOMS,
  REACH_NAMES,
  TC_EXPONENT_CUP,
  TC_EXPONENT_SEED,
  TRAP_HEIGHT,
  type EscapeRule,
} from "../physics/constants";

/** What a game chooses of its physics (its GameConfig but the speed: game/rules.ts). */
export interface GamePhysics {
  nAtoms: number;
  radius: number;
  seed: number | null;
  tcExponent: number;
  escape: EscapeRule;
}

/**
 * The physics' Simulation as the game plays it (a GameSim: game/sim.ts): snapshots kept
 * between frames (no allocation per frame) and T computed once per state of the gas.
 */
export class EngineSim extends Simulation {
  private trappedSnap: AtomSnapshot | undefined;
  private escapedSnap: AtomSnapshot | undefined;
  private temperatureKey = "";
  private temperatureValue = 0;

  /** T sums every trapped atom's energy: asked for several times a frame, computed once. */
  override get temperature(): number {
    const key = `${this.time}|${this.collisionCount}|${this.nTrapped}|${this.trapHeight}`;
    if (key !== this.temperatureKey) {
      this.temperatureKey = key;
      this.temperatureValue = super.temperature;
    }
    return this.temperatureValue;
  }

  trapped(): AtomSnapshot {
    return (this.trappedSnap = this.atoms("trapped", this.trappedSnap));
  }

  escaped(): AtomSnapshot {
    return (this.escapedSnap = this.atoms("escaped", this.escapedSnap));
  }
}

export function makeSimulation(config: GamePhysics): EngineSim {
  return new EngineSim({
    nAtoms: config.nAtoms,
    radius: config.radius,
    tcExponent: config.tcExponent,
    escape: config.escape,
    ...(config.seed === null ? {} : { seed: config.seed }),
  });
}

/** The text this engine writes for a golden trace's start and steps (the same, if it agrees). */
export function replayGolden(text: string): string {
  return traceText(replayTrace(readTrace(text)));
}

/** The physics' own switch to the won state, for a game's sim (tests of the condensate). */
export function forceWin(sim: object): void {
  if (sim instanceof EngineSim) sim.forceWin();
}
