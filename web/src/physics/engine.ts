/**
 * The event engine: hard disks in the parabolic cup, one event at a time, exactly.
 *
 * It processes the events of Python's ReferenceEngine (src/evapcool/physics/reference.py)
 * in the same order with the same arithmetic (kernels.ts), so the golden traces replay bit
 * for bit. Techniques (Smallenburg, Eur. Phys. J. E 45, 22 (2022); Bannerman et al.,
 * J. Comput. Chem. 32, 3329 (2011)), as in the Numba engine (physics/fast.py):
 *
 * - each atom keeps only its earliest event (wall, exit, pair, or crossing a cell edge),
 *   keyed (time, rank, a, b) so ties fall as in the reference engine: crossings first (they
 *   change no state), then solo events by atom index, then pairs by (lower, higher) index;
 *   the keys sit in an event calendar (queue.ts);
 * - a pair event remembers the partner's event counter and is re-predicted if the partner
 *   has changed since (lazy invalidation);
 * - trapped atoms live in a uniform grid of cells 1.1 contact distances wide, its edge cells
 *   reaching to infinity; pairs are looked for in the 3 x 3 block around an atom, and a
 *   crossing scans only the row or column of cells that came within reach;
 * - stored states move only at an atom's real events (lazy positions); escaped atoms leave
 *   the grid and have only their exit event.
 *
 * Memory: atom i of the world lives in row row[i] of a few tables whose rows fill cache
 * lines (S: stored state; I: integers; E: event times), and every few events per atom the
 * rows are renumbered in cell order, so the atoms of neighbouring cells sit next to each
 * other. What orders events or is seen outside (tie-break indices, the log, the knife's
 * order) uses the world index, never the row. Everything is allocated once: no allocation
 * per event.
 */
import {
  ESCAPED,
  EV_ESCAPE,
  EV_GONE,
  EV_KNIFE,
  EV_PAIR,
  EV_WALL,
  GONE,
  TRAPPED,
  WALL_MIN_NORMAL_SPEED,
  WIN_DAMPING,
  WIN_DAMPING_MIN_SPEED,
  WIN_NORMAL_SPEED_FLOOR,
} from "./constants";
import {
  IO_A,
  IO_G,
  IO_KEEP,
  IO_M1,
  IO_M2,
  IO_OUT,
  IO_RX,
  IO_RY,
  IO_SIZE,
  IO_VMIN,
  IO_VX,
  IO_VX1,
  IO_VX2,
  IO_VY,
  IO_VY1,
  IO_VY2,
  IO_T0,
  IO_X,
  IO_XL,
  IO_XR,
  IO_Y,
  IO_YB,
  atomEnergy,
  bounceWall,
  collidePair,
  exitTime,
  flightVy,
  flightX,
  flightY,
  pairContactTime,
  settleWall,
  wallContactTime,
} from "./kernels";
import { EventQueue } from "./queue";

// S, 8 floats a row: the stored state at the atom's own time, radius, event counter, world
// index (the pair scan and the partner check read them on one cache line; both exact as floats).
const X = 0;
const Y = 1;
const VX = 2;
const VY = 3;
const T = 4;
const R = 5;
const CNT = 6;
const SID = 7;
const SW = 8;
// I, 16 integers a row: lifecycle, the partner's event counter (low 32 bits) when the pair was
// predicted, cell and the previous row in it, the real event (kind, partner row, key parts),
// the crossing (axis, target cell), world index.
const I_ST = 0;
const I_PC = 1;
const I_CX = 2;
const I_CY = 3;
const I_PRV = 4;
const I_KIND = 5;
const I_ARG = 6;
const I_RANK = 8;
const I_RA = 9;
const I_RB = 10;
const I_XK = 11;
const I_XT = 12;
const I_ID = 13;
const IW = 16;
// E, 4 floats a row: real-event time, crossing time, the time of the arc's last y crossing,
// mass.
const E_RT = 0;
const E_CT = 1;
const E_TLY = 2;
const E_M = 3;
const EW = 4;

// Internal event kinds.
const K_NONE = 0;
const K_PAIR = 1;
const K_WALL = 2;
const K_EXIT = 3;
const K_CROSS_X = 4;
const K_CROSS_Y = 5;

// Ranks order events of equal time (see the file's comment).
const R_CROSS = -1;
const R_SOLO = 0;
const R_PAIR = 1;

/** Cell edge in contact distances; > 1 leaves room for round-off in crossing times. */
const CELL_FACTOR = 1.1;
/** At most this many cells per atom (bounds memory for tiny, sparse atoms). */
const MAX_CELLS_PER_ATOM = 8;
/** Rows are put in cell order, and the queue's bins fitted, every this many events per atom. */
const RENUMBER_EVENTS_PER_ATOM = 8;

/** Everything an engine needs besides the atoms. */
export interface EngineSetup {
  curvature: number;
  gravity: number;
  trapHeight: number;
  /** Window edges in trap coordinates (an escaped atom is gone beyond them). */
  xLeft: number;
  xRight: number;
  yBottom: number;
  tcExponent: number;
  knife: boolean;
  winRule: boolean;
  recordEvents: boolean;
}

/** Atoms and the clock; for a fresh start t = 0, status trapped and the sums are computed. */
export interface EngineAtoms {
  x: ArrayLike<number>;
  y: ArrayLike<number>;
  vx: ArrayLike<number>;
  vy: ArrayLike<number>;
  t: ArrayLike<number>;
  radius: ArrayLike<number>;
  mass: ArrayLike<number>;
  status: ArrayLike<number>;
  time: number;
  /** Running sum of trapped energies; computed in index order if absent. */
  energySum?: number;
  /** T at the start (Tc0 = 0.75 of it); the current temperature if absent. */
  initialTemperature?: number;
  won: boolean;
  pairCount: number;
  wallCount: number;
}

export class Engine {
  readonly n: number;
  readonly g: number;
  readonly a: number;
  readonly xLeft: number;
  readonly xRight: number;
  readonly yBottom: number;
  readonly knife: boolean;
  readonly winRule: boolean;
  readonly tcExponent: number;
  readonly recordEvents: boolean;

  // -- the world --------------------------------------------------------------------------
  private S: Float64Array;
  private I: Int32Array;
  private E: Float64Array;
  /** row[i]: the row of world atom i. */
  private readonly row: Int32Array;
  time = 0.5;
  trapHeight: number;
  xRim: number;
  won = false;
  nTrapped = 0;
  pairCount = 0;
  wallCount = 0;
  energySum = 0.5;
  initialTemperature = 0.5;
  tc0 = 0.5;

  private readonly queue: EventQueue;
  /** Events since the rows were last renumbered. */
  private sinceRenumber = 0;

  // -- the grid: head of every cell, then the next row in cell of every row -----------------
  readonly nx: number;
  readonly ny: number;
  readonly cs: number;
  private readonly gx0: number;
  private readonly gy0: number;
  private readonly nc: number;
  private next: Int32Array;

  // -- log and statistics -----------------------------------------------------------------
  private logKind = new Uint8Array(0);
  private logI = new Int32Array(0);
  private logJ = new Int32Array(0);
  private logT = new Float64Array(0);
  nLog = 0;
  crossingCount = 0;
  staleCount = 0;
  renumberCount = 0;

  /** The velocity kernels' in/out buffer. */
  private readonly io = new Float64Array(IO_SIZE);
  /** Spare tables for renumbering (swapped with the live ones). */
  private S2: Float64Array;
  private I2: Int32Array;
  private E2: Float64Array;
  private readonly order: Int32Array;

  constructor(setup: EngineSetup, atoms: EngineAtoms) {
    const n = atoms.x.length;
    this.n = n;
    this.g = setup.gravity;
    this.a = setup.curvature;
    this.xLeft = setup.xLeft;
    this.xRight = setup.xRight;
    this.yBottom = setup.yBottom;
    this.knife = setup.knife;
    this.winRule = setup.winRule;
    this.tcExponent = setup.tcExponent;
    this.recordEvents = setup.recordEvents;
    this.trapHeight = setup.trapHeight;
    this.xRim = Math.sqrt(setup.trapHeight / setup.curvature);

    this.S = new Float64Array(SW * n);
    this.I = new Int32Array(IW * n);
    this.E = new Float64Array(EW * n);
    this.S2 = new Float64Array(SW * n);
    this.I2 = new Int32Array(IW * n);
    this.E2 = new Float64Array(EW * n);
    this.order = new Int32Array(n);
    this.row = new Int32Array(n);
    const S = this.S;
    for (let i = 0; i < n; i++) {
      const b = SW * i;
      S[b + X] = atoms.x[i];
      S[b + Y] = atoms.y[i];
      S[b + VX] = atoms.vx[i];
      S[b + VY] = atoms.vy[i];
      S[b + T] = atoms.t[i];
      S[b + R] = atoms.radius[i];
      this.E[EW * i + E_M] = atoms.mass[i];
      S[b + SID] = i;
      this.I[IW * i + I_ST] = atoms.status[i];
      this.I[IW * i + I_ID] = i;
      this.I[IW * i + I_PRV] = -1;
      this.E[EW * i + E_TLY] = -Infinity;
      this.row[i] = i;
      if (atoms.status[i] === TRAPPED) this.nTrapped++;
    }
    this.time = atoms.time;
    this.won = atoms.won;
    this.pairCount = atoms.pairCount;
    this.wallCount = atoms.wallCount;
    this.energySum = atoms.energySum ?? this.sequentialEnergySum();
    this.initialTemperature =
      atoms.initialTemperature ?? (this.nTrapped > 0 ? this.energySum / this.nTrapped : 0);
    // seed Eq. (46): Tc0 is 3/4 of the starting temperature.
    this.tc0 = 0.75 * this.initialTemperature;

    this.queue = new EventQueue(n);
    const grid = this.gridShape();
    this.cs = grid.cs;
    this.nx = grid.nx;
    this.ny = grid.ny;
    this.gx0 = -0.5 * grid.nx * grid.cs;
    this.gy0 = -0.5 * grid.cs;
    this.nc = grid.nx * grid.ny;
    this.next = new Int32Array(this.nc + n).fill(-1);
    this.setup();
  }

  /** Sum of trapped energies added in world index order (the engines continue it). */
  sequentialEnergySum(): number {
    let total = 0.0;
    for (let i = 0; i < this.n; i++) if (this.statusOf(i) === TRAPPED) total += this.atomEnergy(i);
    return total;
  }

  /**
   * Cells: 1.1 of the largest contact distance, over the region the trapped atoms can reach
   * (below the height of the most energetic one, y <= E / (m g)), as long as that takes at
   * most 8 cells per atom; beyond it atoms sit in the edge cells, which reach to infinity.
   * Cells are never widened for a few hot atoms (that would make every scan long).
   */
  private gridShape(): { cs: number; nx: number; ny: number } {
    const S = this.S;
    let rMax = 0;
    let top = 1;
    for (let r = 0; r < this.n; r++) {
      if (this.I[IW * r + I_ST] !== TRAPPED) continue;
      const b = SW * r;
      if (S[b + R] > rMax) rMax = S[b + R];
      const h = this.energy(r) / (this.E[EW * r + E_M] * this.g);
      if (h > top) top = h;
    }
    const cs = rMax > 0 ? CELL_FACTOR * 2 * rMax : 1;
    const maxCells = MAX_CELLS_PER_ATOM * this.n + 64;
    // Box: |x| <= sqrt(yTop / a) + cs, 0 <= y <= yTop; shrink yTop until it fits.
    let yTop = top + cs;
    for (;;) {
      const halfW = Math.sqrt(yTop / this.a) + cs;
      const nx = Math.max(1, Math.ceil((2 * halfW) / cs));
      const ny = Math.max(1, Math.ceil((yTop + 0.5 * cs) / cs));
      if (nx * ny <= maxCells || yTop <= cs) return { cs, nx, ny };
      yTop *= 0.8;
    }
  }

  /** Energy of row r from its stored state (conserved in flight). */
  private energy(r: number): number {
    const S = this.S;
    const b = SW * r;
    return atomEnergy(this.E[EW * r + E_M], S[b + Y], S[b + VX], S[b + VY], this.g);
  }

  /** Put trapped atoms in their cells (positions now), predict every atom, file the keys. */
  private setup(): void {
    const S = this.S;
    const halfG = 0.5 * this.g;
    const now = this.time;
    for (let r = 0; r < this.n; r++) {
      if (this.I[IW * r + I_ST] !== TRAPPED) continue;
      const b = SW * r;
      const dt = now - S[b + T];
      const xn = flightX(S[b + X], S[b + VX], dt);
      const yn = flightY(S[b + Y], S[b + VY], halfG, dt);
      this.link(r, this.clampCell(xn, this.gx0, this.nx), this.clampCell(yn, this.gy0, this.ny));
    }
    for (let r = 0; r < this.n; r++) {
      this.predictReal(r);
      this.predictCross(r);
      this.loadKey(r);
    }
    this.queue.rebuild(now);
    this.sinceRenumber = 0;
  }

  // -- keys ------------------------------------------------------------------------------
  /** Row r's key is the earlier of its crossing and its real event; re-file it. */
  private setKey(r: number): void {
    const I = this.I;
    const i = IW * r;
    const e = EW * r;
    const ct = this.E[e + E_CT];
    const rt = this.E[e + E_RT];
    const q = this.queue;
    if (ct <= rt) {
      q.keyT[r] = ct;
      q.file(r, R_CROSS, I[i + I_ID], I[i + I_XK]);
    } else {
      q.keyT[r] = rt;
      q.file(r, I[i + I_RANK], I[i + I_RA], I[i + I_RB]);
    }
  }

  private loadKey(r: number): void {
    const I = this.I;
    const i = IW * r;
    const e = EW * r;
    const ct = this.E[e + E_CT];
    const rt = this.E[e + E_RT];
    const q = this.queue;
    if (ct <= rt) {
      q.keyT[r] = ct;
      q.load(r, R_CROSS, I[i + I_ID], I[i + I_XK]);
    } else {
      q.keyT[r] = rt;
      q.load(r, I[i + I_RANK], I[i + I_RA], I[i + I_RB]);
    }
  }

  // -- grid ------------------------------------------------------------------------------
  private clampCell(u: number, u0: number, n: number): number {
    const c = Math.floor((u - u0) / this.cs);
    if (c < 0) return 0;
    if (c > n - 1) return n - 1;
    return c;
  }

  private link(r: number, ci: number, cj: number): void {
    const I = this.I;
    const next = this.next;
    I[IW * r + I_CX] = ci;
    I[IW * r + I_CY] = cj;
    const c = cj * this.nx + ci;
    const q = next[c];
    next[this.nc + r] = q;
    I[IW * r + I_PRV] = -1;
    if (q >= 0) I[IW * q + I_PRV] = r;
    next[c] = r;
  }

  private unlink(r: number): void {
    const I = this.I;
    const next = this.next;
    const p = I[IW * r + I_PRV];
    const q = next[this.nc + r];
    const c = I[IW * r + I_CY] * this.nx + I[IW * r + I_CX];
    if (p >= 0) next[this.nc + p] = q;
    else if (next[c] === r) next[c] = q;
    if (q >= 0) I[IW * q + I_PRV] = p;
    next[this.nc + r] = -1;
    I[IW * r + I_PRV] = -1;
  }

  // -- predictions -----------------------------------------------------------------------
  /**
   * Pairs of trapped row r with the rows of cells [xlo, xhi] x [ylo, yhi] (seed Eqs. 15-19).
   * An earlier pair replaces r's real event; on a tie the solo event stays and pairs go in
   * (lower, higher) world index order, as in the reference engine.
   */
  private scan(r: number, xlo: number, xhi: number, ylo: number, yhi: number): void {
    const S = this.S;
    const E = this.E;
    const I = this.I;
    const next = this.next;
    const nc = this.nc;
    const nx = this.nx;
    const g = this.g;
    const b = SW * r;
    const x = S[b + X];
    const y = S[b + Y];
    const vx = S[b + VX];
    const vy = S[b + VY];
    const t0 = S[b + T];
    const ri = S[b + R];
    const ii = S[b + SID];
    const ir = IW * r;
    let bt = E[EW * r + E_RT];
    let pair = I[ir + I_RANK] === R_PAIR;
    let ba = I[ir + I_RA];
    let bb = I[ir + I_RB];
    let best = -1;
    // Integer arithmetic in asm.js style (shifts, | 0): no overflow checks in the hot loop.
    for (let yy = ylo; yy <= yhi; yy++) {
      const rowStart = (yy * nx) | 0;
      for (let xx = xlo; xx <= xhi; xx++) {
        for (let j = next[(rowStart + xx) | 0]; j >= 0; j = next[(nc + j) | 0]) {
          if (j === r) continue;
          const bj = j << 3; // SW = 8: bj | k is bj + k
          const t = pairContactTime(
            x,
            y,
            vx,
            vy,
            t0,
            S[bj],
            S[bj | Y],
            S[bj | VX],
            S[bj | VY],
            S[bj | T],
            ri + S[bj | R],
            g,
          );
          if (t <= bt) {
            const jj = S[bj | SID]; // rare: only now the partner's world index
            const lo = ii < jj ? ii : jj;
            const hi = ii < jj ? jj : ii;
            if (t < bt || (pair && (lo < ba || (lo === ba && hi < bb)))) {
              bt = t;
              pair = true;
              ba = lo;
              bb = hi;
              best = j;
            }
          }
        }
      }
    }
    if (best >= 0) {
      E[EW * r + E_RT] = bt;
      I[ir + I_RANK] = R_PAIR;
      I[ir + I_RA] = ba;
      I[ir + I_RB] = bb;
      I[ir + I_KIND] = K_PAIR;
      I[ir + I_ARG] = best;
      I[ir + I_PC] = S[SW * best + CNT] | 0;
    }
  }

  /** Row r's real event: wall (SPEC 2.1) or pair if trapped, exit if escaped. */
  private predictReal(r: number): void {
    const S = this.S;
    const I = this.I;
    const b = SW * r;
    const ir = IW * r;
    const st = I[ir + I_ST];
    let t = Infinity;
    let kind = K_NONE;
    if (st === TRAPPED || st === ESCAPED) {
      const io = this.io;
      io[IO_X] = S[b + X];
      io[IO_Y] = S[b + Y];
      io[IO_VX] = S[b + VX];
      io[IO_VY] = S[b + VY];
      io[IO_T0] = S[b + T];
      io[IO_G] = this.g;
      if (st === TRAPPED) {
        io[IO_A] = this.a;
        wallContactTime(io);
        kind = K_WALL;
      } else {
        const rad = S[b + R];
        io[IO_XL] = this.xLeft - rad;
        io[IO_XR] = this.xRight + rad;
        io[IO_YB] = this.yBottom - rad;
        exitTime(io);
        kind = K_EXIT;
      }
      t = io[IO_OUT];
    }
    this.E[EW * r + E_RT] = t;
    I[ir + I_RANK] = R_SOLO;
    I[ir + I_RA] = I[ir + I_ID];
    I[ir + I_RB] = 0;
    I[ir + I_KIND] = kind;
    if (st === TRAPPED && !this.won) {
      const ci = I[ir + I_CX];
      const cj = I[ir + I_CY];
      this.scan(
        r,
        ci > 0 ? ci - 1 : 0,
        ci < this.nx - 1 ? ci + 1 : this.nx - 1,
        cj > 0 ? cj - 1 : 0,
        cj < this.ny - 1 ? cj + 1 : this.ny - 1,
      );
    }
  }

  /**
   * Row r's next cell crossing (none unless trapped and the game is on). x: straight to the
   * next edge along vx. y: up through the top edge (first root, if the arc passes it), else
   * down through the bottom edge; roots at or before the arc's last y crossing (TLY) are
   * ones already taken. Edge cells reach to infinity: no outer edge.
   */
  private predictCross(r: number): void {
    const I = this.I;
    const E = this.E;
    const ir = IW * r;
    let bt = Infinity;
    let bk = K_NONE;
    let barg = 0;
    if (I[ir + I_ST] === TRAPPED && !this.won) {
      const S = this.S;
      const b = SW * r;
      const g = this.g;
      const cs = this.cs;
      const x = S[b + X];
      const y = S[b + Y];
      const vx = S[b + VX];
      const vy = S[b + VY];
      const t0 = S[b + T];
      const ci = I[ir + I_CX];
      const cj = I[ir + I_CY];
      if (vx > 0.0 && ci < this.nx - 1) {
        bt = t0 + (this.gx0 + (ci + 1) * cs - x) / vx;
        bk = K_CROSS_X;
        barg = ci + 1;
      } else if (vx < 0.0 && ci > 0) {
        bt = t0 + (this.gx0 + ci * cs - x) / vx;
        bk = K_CROSS_X;
        barg = ci - 1;
      }
      let tc = Infinity;
      let tgt = 0;
      const tl = E[EW * r + E_TLY];
      if (vy > 0.0 && cj < this.ny - 1) {
        const d = this.gy0 + (cj + 1) * cs - y;
        const disc = vy * vy - 2.0 * g * d;
        if (disc > 0.0) {
          const s = Math.sqrt(disc);
          const t1 = t0 + (2.0 * d) / (vy + s);
          const t2 = t0 + (vy + s) / g;
          if (t2 > t1 && t1 > tl) {
            tc = t1;
            tgt = cj + 1;
          }
        }
      }
      if (tc === Infinity && cj > 0) {
        const h = y - (this.gy0 + cj * cs);
        let disc = vy * vy + 2.0 * g * h;
        if (disc < 0.0) disc = 0.0;
        const s = Math.sqrt(disc);
        let t2: number;
        if (vy > 0.0) t2 = t0 + (vy + s) / g;
        else if (s - vy > 0.0) t2 = t0 + (2.0 * h) / (s - vy);
        else t2 = t0;
        if (t2 > tl) {
          tc = t2;
          tgt = cj - 1;
        }
      }
      if (tc < bt) {
        bt = tc;
        bk = K_CROSS_Y;
        barg = tgt;
      }
    }
    E[EW * r + E_CT] = bt;
    I[ir + I_XK] = bk;
    I[ir + I_XT] = barg;
  }

  /** Everything about row r from its stored state. */
  private predict(r: number): void {
    this.predictReal(r);
    this.predictCross(r);
    this.setKey(r);
  }

  // -- state changes ---------------------------------------------------------------------
  /** Carry row r's stored state to the clock (exact free flight, seed Eqs. 3-4). */
  private move(r: number): void {
    const t = this.time;
    const S = this.S;
    const b = SW * r;
    const dt = t - S[b + T];
    S[b + X] = flightX(S[b + X], S[b + VX], dt);
    S[b + Y] = flightY(S[b + Y], S[b + VY], 0.5 * this.g, dt);
    S[b + VY] = flightVy(S[b + VY], this.g, dt);
    S[b + T] = t;
    this.E[EW * r + E_TLY] = -Infinity; // a new arc: none of its y crossings taken yet
  }

  /** Log an event at the clock's time (world indices; j = -1 for solo events). */
  private log(kind: number, i: number, j: number): void {
    if (!this.recordEvents) return;
    const t = this.time;
    const k = this.nLog;
    if (k === this.logT.length) {
      const cap = Math.max(1024, 2 * k);
      const grow = <A extends Uint8Array | Int32Array | Float64Array>(old: A, fresh: A): A => {
        fresh.set(old);
        return fresh;
      };
      this.logKind = grow(this.logKind, new Uint8Array(cap));
      this.logI = grow(this.logI, new Int32Array(cap));
      this.logJ = grow(this.logJ, new Int32Array(cap));
      this.logT = grow(this.logT, new Float64Array(cap));
    }
    this.logKind[k] = kind;
    this.logI[k] = i;
    this.logJ[k] = j;
    this.logT[k] = t;
    this.nLog = k + 1;
  }

  /** Event k of the log: [kind, i, j, time] with world indices. */
  logEntry(k: number): [number, number, number, number] {
    return [this.logKind[k], this.logI[k], this.logJ[k], this.logT[k]];
  }

  /** Tc(N) = Tc0 (N / N0)^p, seed Eq. (46) with exponent p. */
  criticalTemperatureOf(nTrapped: number): number {
    return this.tc0 * Math.pow(nTrapped / this.n, this.tcExponent);
  }

  /** T < Tc(N) with the running energy sum (seed Eqs. 1 and 46), latched. */
  private checkWin(): void {
    const n = this.nTrapped;
    if (this.won || n === 0 || !this.winRule) return;
    if (this.energySum / n < this.criticalTemperatureOf(n)) this.won = true;
  }

  /** Row r leaves the trapped set (over the rim or by the knife). */
  private remove(r: number, newStatus: number): void {
    const I = this.I;
    I[IW * r + I_ST] = newStatus;
    this.nTrapped--;
    this.energySum -= this.energy(r);
    this.S[SW * r + CNT] += 1;
    this.unlink(r);
    this.predict(r);
    this.checkWin();
  }

  /** Remove trapped row r now if its energy exceeds m g H; true if removed. */
  private knifeCut(r: number): boolean {
    if (!this.knife) return false;
    const m = this.E[EW * r + E_M];
    if (this.energy(r) > m * this.g * this.trapHeight) {
      this.log(EV_KNIFE, this.I[IW * r + I_ID], -1);
      this.remove(r, GONE);
      return true;
    }
    return false;
  }

  /**
   * Renumber the rows in cell order (row-major), the atoms off the grid last: the atoms of
   * neighbouring cells then sit next to each other in memory and the pair scans stay in the
   * caches. Moves every table row, relabels partners, rebuilds the cell lists and re-files
   * the queue. Events, their keys (world indices) and so the event order are unchanged.
   */
  private renumber(): void {
    const n = this.n;
    const nc = this.nc;
    const next = this.next;
    const order = this.order; // order[new row] = old row
    const fresh = this.row; // reused below as old row -> new row via I2's scratch
    let k = 0;
    for (let c = 0; c < nc; c++) for (let j = next[c]; j >= 0; j = next[nc + j]) order[k++] = j;
    const linked = k;
    const I = this.I;
    for (let r = 0; r < n; r++) {
      const i = I[IW * r + I_ID];
      fresh[i] = -1;
    }
    for (let q = 0; q < linked; q++) fresh[I[IW * order[q] + I_ID]] = q;
    for (let r = 0; r < n; r++) if (fresh[I[IW * r + I_ID]] < 0) order[k++] = r;
    for (let q = linked; q < n; q++) fresh[I[IW * order[q] + I_ID]] = q;
    // Move the rows into the spare tables, then swap.
    const S = this.S;
    const E = this.E;
    const S2 = this.S2;
    const I2 = this.I2;
    const E2 = this.E2;
    for (let q = 0; q < n; q++) {
      const o = order[q];
      for (let k = 0; k < SW; k++) S2[SW * q + k] = S[SW * o + k];
      for (let k = 0; k < IW; k++) I2[IW * q + k] = I[IW * o + k];
      for (let k = 0; k < EW; k++) E2[EW * q + k] = E[EW * o + k];
    }
    this.S = S2;
    this.I = I2;
    this.E = E2;
    this.S2 = S;
    this.I2 = I;
    this.E2 = E;
    // Partners are rows: relabel them (the old row's world index, then its new row).
    const In = this.I;
    for (let q = 0; q < n; q++) {
      const p = IW * q;
      if (In[p + I_KIND] === K_PAIR) In[p + I_ARG] = fresh[I[IW * In[p + I_ARG] + I_ID]];
    }
    // Cell lists: linking in descending row order leaves each list ascending.
    next.fill(-1);
    for (let q = linked - 1; q >= 0; q--) this.link(q, In[IW * q + I_CX], In[IW * q + I_CY]);
    for (let q = 0; q < n; q++) this.loadKey(q);
    this.queue.rebuild(this.time);
    this.renumberCount++;
  }

  // -- public ----------------------------------------------------------------------------
  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void {
    const a = this.a;
    const queue = this.queue;
    const io = this.io;
    const every = RENUMBER_EVENTS_PER_ATOM * this.n;
    for (;;) {
      if (++this.sinceRenumber > every) {
        this.sinceRenumber = 0;
        if (this.won) queue.rebuild(this.time);
        else this.renumber();
      }
      const r = queue.top();
      if (r < 0) break;
      const te = queue.keyT[r];
      if (!(te <= tEnd)) break;
      const S = this.S;
      const I = this.I;
      const ir = IW * r;
      const kind = queue.rankOf(r) === R_CROSS ? I[ir + I_XK] : I[ir + I_KIND];
      // After the event: rp's prediction (full, or only its crossing if its real event
      // stands), then the pair's second atom's knife test and prediction.
      let rp = -1;
      let full = true;
      let pend = -1;
      let t = te;
      if (kind === K_PAIR) {
        const j = I[ir + I_ARG];
        if (this.won || (S[SW * j + CNT] | 0) !== I[ir + I_PC]) {
          this.staleCount++; // the partner moved on (or pairs are over)
          rp = r;
        } else {
          // lo, hi: the rows of the lower and higher world index
          const swap = S[SW * j + SID] < S[SW * r + SID];
          const lo = swap ? j : r;
          const hi = swap ? r : j;
          t = te >= this.time ? te : this.time;
          this.time = t;
          this.move(lo);
          this.move(hi);
          const bl = SW * lo;
          const bh = SW * hi;
          io[IO_RX] = S[bh + X] - S[bl + X];
          io[IO_RY] = S[bh + Y] - S[bl + Y];
          io[IO_VX1] = S[bl + VX];
          io[IO_VY1] = S[bl + VY];
          io[IO_VX2] = S[bh + VX];
          io[IO_VY2] = S[bh + VY];
          io[IO_M1] = this.E[EW * lo + E_M];
          io[IO_M2] = this.E[EW * hi + E_M];
          collidePair(io);
          S[bl + VX] = io[IO_OUT];
          S[bl + VY] = io[IO_OUT + 1];
          S[bh + VX] = io[IO_OUT + 2];
          S[bh + VY] = io[IO_OUT + 3];
          this.pairCount++;
          S[bl + CNT] += 1;
          S[bh + CNT] += 1;
          this.log(EV_PAIR, I[IW * lo + I_ID], I[IW * hi + I_ID]);
          if (!this.knifeCut(lo)) rp = lo;
          pend = hi;
        }
      } else if (kind === K_CROSS_X || kind === K_CROSS_Y) {
        this.crossingCount++;
        if (this.won) {
          rp = r; // the grid is no longer kept once the gas has condensed
        } else {
          // Into the next cell; only the row or column of cells that came within reach
          // needs a scan: pairs with the other neighbours are held already.
          const ci = I[ir + I_CX];
          const cj = I[ir + I_CY];
          const tgt = I[ir + I_XT];
          this.unlink(r);
          if (kind === K_CROSS_X) {
            this.link(r, tgt, cj);
            const c = 2 * tgt - ci;
            if (c >= 0 && c < this.nx)
              this.scan(r, c, c, cj > 0 ? cj - 1 : 0, cj < this.ny - 1 ? cj + 1 : this.ny - 1);
          } else {
            this.link(r, ci, tgt);
            this.E[EW * r + E_TLY] = te;
            const c = 2 * tgt - cj;
            if (c >= 0 && c < this.ny)
              this.scan(r, ci > 0 ? ci - 1 : 0, ci < this.nx - 1 ? ci + 1 : this.nx - 1, c, c);
          }
          rp = r;
          full = false;
        }
      } else if (kind === K_WALL) {
        t = te >= this.time ? te : this.time;
        this.time = t;
        this.move(r);
        const b = SW * r;
        const x = S[b + X];
        if (Math.abs(x) > this.xRim) {
          // over the rim: escaped (SPEC 2.3)
          this.log(EV_ESCAPE, I[ir + I_ID], -1);
          this.remove(r, ESCAPED);
          continue;
        }
        const vx = S[b + VX];
        const vy = S[b + VY];
        const speed = Math.sqrt(vx * vx + vy * vy);
        const damped = this.won && speed >= WIN_DAMPING_MIN_SPEED; // seed Eq. (34)
        const changes = damped || speed < WALL_MIN_NORMAL_SPEED;
        if (changes) this.energySum -= this.energy(r);
        io[IO_X] = x;
        io[IO_VX] = vx;
        io[IO_VY] = vy;
        io[IO_A] = a;
        if (damped) {
          io[IO_KEEP] = 1.0 - WIN_DAMPING;
          io[IO_VMIN] = WIN_NORMAL_SPEED_FLOOR;
          settleWall(io);
        } else {
          io[IO_VMIN] = WALL_MIN_NORMAL_SPEED;
          bounceWall(io);
        }
        S[b + VX] = io[IO_OUT];
        S[b + VY] = io[IO_OUT + 1];
        if (changes) this.energySum += this.energy(r);
        this.wallCount++;
        S[b + CNT] += 1;
        this.log(EV_WALL, I[ir + I_ID], -1);
        rp = r;
      } else if (kind === K_EXIT) {
        t = te >= this.time ? te : this.time;
        this.time = t;
        this.move(r);
        I[ir + I_ST] = GONE;
        S[SW * r + CNT] += 1;
        this.log(EV_GONE, I[ir + I_ID], -1);
        rp = r;
      } else {
        break;
      }
      for (;;) {
        if (rp >= 0) {
          if (full) this.predictReal(rp);
          this.predictCross(rp);
          this.setKey(rp);
        }
        if (pend < 0) break;
        rp = this.knifeCut(pend) ? -1 : pend;
        pend = -1;
        full = true;
      }
    }
    this.time = tEnd;
  }

  /** New rim height; with the knife rule, atoms above m g H go at once, in index order. */
  setTrapHeight(height: number): void {
    this.trapHeight = height;
    this.xRim = Math.sqrt(height / this.a);
    if (!this.knife) return;
    for (let i = 0; i < this.n; i++) {
      const r = this.row[i];
      if (this.I[IW * r + I_ST] === TRAPPED) this.knifeCut(r);
    }
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.won = true;
  }

  // -- reading, by world index -------------------------------------------------------------
  statusOf(i: number): number {
    return this.I[IW * this.row[i] + I_ST];
  }

  /** Stored value k of world atom i: 0 x, 1 y, 2 vx, 3 vy, 4 t, 5 radius, 6 mass. */
  storedOf(i: number, k: number): number {
    return k === 6 ? this.E[EW * this.row[i] + E_M] : this.S[SW * this.row[i] + k];
  }

  /** World atom i's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
  atomEnergy(i: number): number {
    return this.energy(this.row[i]);
  }

  /** Position and velocity of world atom i carried to time t into out = [x, y, vx, vy]. */
  stateAt(i: number, t: number, out: Float64Array): void {
    const S = this.S;
    const b = SW * this.row[i];
    const dt = t - S[b + T];
    out[0] = flightX(S[b + X], S[b + VX], dt);
    out[1] = flightY(S[b + Y], S[b + VY], 0.5 * this.g, dt);
    out[2] = S[b + VX];
    out[3] = flightVy(S[b + VY], this.g, dt);
  }

  /** Trapped atoms filed more than one cell away from their cell now (0 if sound). */
  gridErrors(): number {
    if (this.won) return 0;
    const S = this.S;
    const I = this.I;
    let bad = 0;
    for (let r = 0; r < this.n; r++) {
      if (I[IW * r + I_ST] !== TRAPPED) continue;
      const b = SW * r;
      const dt = this.time - S[b + T];
      const ci = this.clampCell(flightX(S[b + X], S[b + VX], dt), this.gx0, this.nx);
      const cj = this.clampCell(flightY(S[b + Y], S[b + VY], 0.5 * this.g, dt), this.gy0, this.ny);
      if (Math.abs(ci - I[IW * r + I_CX]) > 1 || Math.abs(cj - I[IW * r + I_CY]) > 1) bad++;
    }
    return bad;
  }
}
