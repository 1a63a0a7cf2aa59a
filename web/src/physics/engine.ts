/**
 * The event engine: hard disks in the parabolic cup, one event at a time, exactly
 * (src/evapcool/physics/fast/engine.py). This file is the class simulation.ts talks to;
 * the mechanism lives in rooms named like the Numba engine's: tables.ts (what it knows
 * about every atom), calendar.ts (the event calendar), grid.ts (cells), predict.ts (next
 * events), events.ts (one handler per kind) and driver.ts (the event loop).
 *
 * It processes the events of Python's ReferenceEngine (src/evapcool/physics/reference.py)
 * in the same order with the same arithmetic (kernels.ts), so the golden traces replay bit
 * for bit. Techniques: Smallenburg, Eur. Phys. J. E 45, 22 (2022); Bannerman et al.,
 * J. Comput. Chem. 32, 3329 (2011).
 */
import { advanceTo, setTrapHeight, start } from "./driver";
import { criticalTemperature } from "./events";
import { gridErrors, placeGrid } from "./grid";
import { flightVy, flightX, flightY } from "./kernels";
import {
  PLAN_STATUS,
  PLAN_WIDTH,
  QUEUED_MASS,
  QUEUED_WIDTH,
  STATE_T,
  STATE_VX,
  STATE_VY,
  STATE_WIDTH,
  STATE_X,
  STATE_Y,
  Tables,
  loadAtoms,
  rowEnergy,
  sequentialEnergySum,
} from "./tables";
import type { EngineAtoms, EngineSetup } from "./tables";

export type { EngineAtoms, EngineSetup } from "./tables";

/** What storedOf(i, k) returns for each k: STATE's fields in its order, then the mass. */
export const STORED = { x: 0, y: 1, vx: 2, vy: 3, t: 4, radius: 5, mass: 6 } as const;

export class Engine {
  private readonly tb: Tables;

  constructor(setup: EngineSetup, atoms: EngineAtoms) {
    this.tb = new Tables(setup, atoms.x.length);
    loadAtoms(this.tb, atoms);
    placeGrid(this.tb);
    start(this.tb);
  }

  // -- fixed for the engine's life ------------------------------------------------------------
  /** Atoms at the start (N0), gone ones included. */
  get nAtoms(): number {
    return this.tb.n;
  }
  get gravity(): number {
    return this.tb.gravity;
  }
  get curvature(): number {
    return this.tb.curvature;
  }
  get knife(): boolean {
    return this.tb.knife;
  }
  get winRule(): boolean {
    return this.tb.winRule;
  }
  get tcExponent(): number {
    return this.tb.tcExponent;
  }
  /** The cell grid's columns and rows. */
  get gridColumns(): number {
    return this.tb.nx;
  }
  get gridRows(): number {
    return this.tb.ny;
  }
  get cellSize(): number {
    return this.tb.cellSize;
  }

  // -- the running state -------------------------------------------------------------------
  get time(): number {
    return this.tb.time;
  }
  get trapHeight(): number {
    return this.tb.trapHeight;
  }
  get xRim(): number {
    return this.tb.xRim;
  }
  get won(): boolean {
    return this.tb.won;
  }
  get nTrapped(): number {
    return this.tb.nTrapped;
  }
  get pairCount(): number {
    return this.tb.pairs;
  }
  get wallCount(): number {
    return this.tb.walls;
  }
  get energySum(): number {
    return this.tb.energySum;
  }
  get initialTemperature(): number {
    return this.tb.initialTemperature;
  }
  get crossingCount(): number {
    return this.tb.crossings;
  }
  get staleCount(): number {
    return this.tb.stale;
  }
  get renumberCount(): number {
    return this.tb.renumbers;
  }
  get nLog(): number {
    return this.tb.nLog;
  }

  // -- driving ---------------------------------------------------------------------------
  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void {
    advanceTo(this.tb, tEnd);
  }

  /** New rim height, at once; with the knife rule, atoms above m g H go now, in index order. */
  setTrapHeight(height: number): void {
    setTrapHeight(this.tb, height);
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.tb.won = true;
  }

  // -- reading, by world index -------------------------------------------------------------
  /** Event k of the log: [kind, i, j, time] with world indices. */
  logEntry(k: number): [number, number, number, number] {
    const tb = this.tb;
    return [tb.logKind[k], tb.logA[k], tb.logB[k], tb.logT[k]];
  }

  /** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
  criticalTemperatureOf(nTrapped: number): number {
    return criticalTemperature(this.tb, nTrapped);
  }

  /** Sum of trapped energies added in world index order (the engines continue it). */
  sequentialEnergySum(): number {
    return sequentialEnergySum(this.tb);
  }

  statusOf(i: number): number {
    return this.tb.plan[PLAN_WIDTH * this.tb.row[i] + PLAN_STATUS];
  }

  /** Stored value k (STORED) of world atom i. */
  storedOf(i: number, k: number): number {
    const r = this.tb.row[i];
    if (k === STORED.mass) return this.tb.queued[QUEUED_WIDTH * r + QUEUED_MASS];
    return this.tb.state[STATE_WIDTH * r + k];
  }

  /** World atom i's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
  atomEnergy(i: number): number {
    return rowEnergy(this.tb, this.tb.row[i]);
  }

  /** Position and velocity of world atom i carried to time t into out = [x, y, vx, vy]. */
  stateAt(i: number, t: number, out: Float64Array): void {
    const S = this.tb.state;
    const s = STATE_WIDTH * this.tb.row[i];
    const g = this.tb.gravity;
    const dt = t - S[s + STATE_T];
    out[0] = flightX(S[s + STATE_X], S[s + STATE_VX], dt);
    out[1] = flightY(S[s + STATE_Y], S[s + STATE_VY], 0.5 * g, dt);
    out[2] = S[s + STATE_VX];
    out[3] = flightVy(S[s + STATE_VY], g, dt);
  }

  /** Trapped atoms filed more than one cell away from their cell now (0 if sound). */
  gridErrors(): number {
    return gridErrors(this.tb);
  }
}
