/**
 * A stand-in for the exact engine while `../physics` is being written: free flight under
 * gravity, mirror bounces off the cup, escape over the rim, no atom-atom collisions
 * (the win comes from a cooling factor). Only for developing the page; not exact.
 */
import { CURVATURE, GRAVITY, cupVertex } from "./constants";
import type { GameConfig } from "./rules";
import { ensureAtoms, type AtomArrays, type SimLike } from "./sim";

export class StandInSim implements SimLike {
  time = 0;
  readonly nAtoms: number;
  private x: Float64Array;
  private y: Float64Array;
  private vx: Float64Array;
  private vy: Float64Array;
  private status: Uint8Array;
  readonly curvature = CURVATURE;
  readonly gravity = GRAVITY;
  readonly tcExponent: number;
  readonly initialTemperature: number;
  readonly screenOrigin: readonly [number, number];
  private h = 400;
  won = false;
  collisionCount = 0;

  constructor(private readonly config: GameConfig) {
    const n = config.nAtoms;
    this.nAtoms = n;
    this.tcExponent = config.tcExponent;
    const [vx0, vy0] = cupVertex();
    this.screenOrigin = [vx0, vy0 - config.radius];
    let seed = (config.seed ?? 1) + 1;
    const rnd = () => ((seed = (seed * 16807) % 2147483647) - 1) / 2147483646;
    this.x = new Float64Array(n);
    this.y = new Float64Array(n);
    this.vx = new Float64Array(n);
    this.vy = new Float64Array(n);
    this.status = new Uint8Array(n);
    const cell = (config.radius * 20) / 12;
    let k = 0;
    for (let row = 0; k < n; row++) {
      const yc = cell * (1 + 2 * row);
      const half = Math.sqrt(yc / CURVATURE);
      for (let xc = -half + cell; xc <= half - cell && k < n; xc += 2 * cell, k++) {
        this.x[k] = xc;
        this.y[k] = yc;
        const a = 2 * Math.PI * rnd();
        const s = 10 / 3 + (row + rnd()) / 3;
        this.vx[k] = s * Math.cos(a);
        this.vy[k] = s * Math.sin(a);
      }
      if (row > 1000) break;
    }
    this.initialTemperature = this.temperature;
  }

  get trapHeight(): number {
    return this.h;
  }
  set trapHeight(v: number) {
    this.h = v;
  }
  get rimHalfWidth(): number {
    return Math.sqrt(this.h / this.curvature);
  }
  get nTrapped(): number {
    let c = 0;
    for (const s of this.status) if (s === 0) c++;
    return c;
  }
  get nEscaped(): number {
    let c = 0;
    for (const s of this.status) if (s === 1) c++;
    return c;
  }
  get temperature(): number {
    let e = 0;
    let n = 0;
    for (let i = 0; i < this.nAtoms; i++) {
      if (this.status[i] !== 0) continue;
      e += 0.5 * (this.vx[i] ** 2 + this.vy[i] ** 2) + this.gravity * this.y[i];
      n++;
    }
    return n ? e / n : 0;
  }
  get criticalTemperature(): number {
    return 0.75 * this.initialTemperature * Math.pow(this.nTrapped / this.nAtoms, this.tcExponent);
  }

  advance(dt: number): void {
    const steps = Math.max(1, Math.ceil(dt * 4));
    const h = dt / steps;
    for (let s = 0; s < steps; s++) {
      for (let i = 0; i < this.nAtoms; i++) {
        if (this.status[i] === 2) continue;
        this.x[i] += this.vx[i] * h;
        this.y[i] += this.vy[i] * h - 0.5 * this.gravity * h * h;
        this.vy[i] -= this.gravity * h;
        const a = this.curvature;
        if (this.status[i] === 0 && this.y[i] < a * this.x[i] ** 2) {
          if (Math.abs(this.x[i]) > this.rimHalfWidth) {
            this.status[i] = 1;
            continue;
          }
          const nx = -2 * a * this.x[i];
          const norm = Math.hypot(nx, 1);
          const vn = (this.vx[i] * nx + this.vy[i]) / norm;
          if (vn < 0) {
            const k = this.won ? 0.8 : 0.995;
            this.vx[i] = (this.vx[i] - (2 * vn * nx) / norm) * k;
            this.vy[i] = (this.vy[i] - (2 * vn) / norm) * k;
            this.collisionCount++;
          }
          this.y[i] = a * this.x[i] ** 2;
        } else if (this.status[i] === 1 && (this.y[i] < -600 || Math.abs(this.x[i]) > 400)) {
          this.status[i] = 2;
        }
      }
    }
    this.time += dt;
    if (!this.won && this.nTrapped > 0 && this.temperature < this.criticalTemperature) {
      this.won = true;
    }
  }

  private fill(out: AtomArrays, which: number): AtomArrays {
    let n = 0;
    for (const s of this.status) if (s === which) n++;
    ensureAtoms(out, n);
    let k = 0;
    for (let i = 0; i < this.nAtoms; i++) {
      if (this.status[i] !== which) continue;
      out.x[k] = this.x[i];
      out.y[k] = this.y[i];
      out.vx[k] = this.vx[i];
      out.vy[k] = this.vy[i];
      out.radius[k] = this.config.radius;
      out.mass[k] = 1;
      k++;
    }
    return out;
  }
  trapped(out: AtomArrays): AtomArrays {
    return this.fill(out, 0);
  }
  escaped(out: AtomArrays): AtomArrays {
    return this.fill(out, 1);
  }
}
