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
 *   the keys sit in an indexed 4-ary heap of all atoms;
 * - a pair event remembers the partner's event counter and is re-predicted if the partner
 *   has changed since (lazy invalidation);
 * - trapped atoms live in a uniform grid of cells 1.1 contact distances wide, its edge cells
 *   reaching to infinity; pairs are looked for in the 3 x 3 block around an atom, and a
 *   crossing scans only the row or column of cells that came within reach;
 * - stored states move only at an atom's real events (lazy positions); escaped atoms leave
 *   the grid and have only their exit event.
 *
 * Everything lives in typed arrays allocated once: no allocation per event.
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

// Stored state: one row of 8 floats (64 bytes, a cache line) per atom.
const X = 0;
const Y = 1;
const VX = 2;
const VY = 3;
const T = 4;
const R = 5;
const M = 6;
const ROW = 8;

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

  // -- the world: stored states at their own times, lifecycle, clock, sums ---------------
  /** Rows of (x, y, vx, vy, t, radius, mass, -) per atom: the stored (lazy) states. */
  readonly S: Float64Array;
  readonly status: Int8Array;
  /** Events per atom (lazy invalidation of pairs). */
  readonly counter: Int32Array;
  time = 0;
  trapHeight: number;
  xRim: number;
  won = false;
  nTrapped = 0;
  pairCount = 0;
  wallCount = 0;
  energySum = 0;
  initialTemperature = 0;
  tc0 = 0;

  // -- the pending events ---------------------------------------------------------------
  /** Real event (wall, exit, pair): time, kind, partner, partner's counter, key parts. */
  private readonly rt: Float64Array;
  private readonly rKind: Uint8Array;
  private readonly rArg: Int32Array;
  private readonly rPc: Int32Array;
  private readonly rRank: Int8Array;
  private readonly rA: Int32Array;
  private readonly rB: Int32Array;
  /** Cell crossing: time, axis kind, target cell; time of the arc's last y crossing. */
  private readonly ct: Float64Array;
  private readonly xk: Uint8Array;
  private readonly xt: Int32Array;
  private readonly tly: Float64Array;
  /** Heap key parts beside the time (rank, a, b). */
  private readonly kRank: Int8Array;
  private readonly kA: Int32Array;
  private readonly kB: Int32Array;
  /** Indexed 4-ary heap of all atoms: heap[p] is an atom, heapT[p] its key time. */
  private readonly heap: Int32Array;
  private readonly heapT: Float64Array;
  private readonly hpos: Int32Array;

  // -- the grid -------------------------------------------------------------------------
  readonly nx: number;
  readonly ny: number;
  readonly cs: number;
  private readonly gx0: number;
  private readonly gy0: number;
  private readonly head: Int32Array;
  private readonly next: Int32Array;
  private readonly prev: Int32Array;
  private readonly cx: Int32Array;
  private readonly cy: Int32Array;

  // -- log and statistics -----------------------------------------------------------------
  private logKind = new Uint8Array(0);
  private logI = new Int32Array(0);
  private logJ = new Int32Array(0);
  private logT = new Float64Array(0);
  nLog = 0;
  crossingCount = 0;
  staleCount = 0;

  private readonly out = new Float64Array(4);

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

    const S = new Float64Array(ROW * n);
    this.S = S;
    this.status = new Int8Array(n);
    this.counter = new Int32Array(n);
    for (let i = 0; i < n; i++) {
      const b = ROW * i;
      S[b + X] = atoms.x[i];
      S[b + Y] = atoms.y[i];
      S[b + VX] = atoms.vx[i];
      S[b + VY] = atoms.vy[i];
      S[b + T] = atoms.t[i];
      S[b + R] = atoms.radius[i];
      S[b + M] = atoms.mass[i];
      this.status[i] = atoms.status[i];
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

    this.rt = new Float64Array(n);
    this.rKind = new Uint8Array(n);
    this.rArg = new Int32Array(n);
    this.rPc = new Int32Array(n);
    this.rRank = new Int8Array(n);
    this.rA = new Int32Array(n);
    this.rB = new Int32Array(n);
    this.ct = new Float64Array(n);
    this.xk = new Uint8Array(n);
    this.xt = new Int32Array(n);
    this.tly = new Float64Array(n).fill(-Infinity);
    this.kRank = new Int8Array(n);
    this.kA = new Int32Array(n);
    this.kB = new Int32Array(n);
    this.heap = new Int32Array(n);
    this.heapT = new Float64Array(n);
    this.hpos = new Int32Array(n);

    const grid = this.gridShape();
    this.cs = grid.cs;
    this.nx = grid.nx;
    this.ny = grid.ny;
    this.gx0 = -0.5 * grid.nx * grid.cs;
    this.gy0 = -0.5 * grid.cs;
    this.head = new Int32Array(grid.nx * grid.ny).fill(-1);
    this.next = new Int32Array(n).fill(-1);
    this.prev = new Int32Array(n).fill(-1);
    this.cx = new Int32Array(n);
    this.cy = new Int32Array(n);
    this.setup();
  }

  /** Sum of trapped energies added in index order (the engines continue it). */
  sequentialEnergySum(): number {
    let total = 0.0;
    for (let i = 0; i < this.n; i++) if (this.status[i] === TRAPPED) total += this.energy(i);
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
    for (let i = 0; i < this.n; i++) {
      if (this.status[i] !== TRAPPED) continue;
      const b = ROW * i;
      if (S[b + R] > rMax) rMax = S[b + R];
      const h = this.energy(i) / (S[b + M] * this.g);
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

  private energy(i: number): number {
    const b = ROW * i;
    return atomEnergy(this.S[b + M], this.S[b + Y], this.S[b + VX], this.S[b + VY], this.g);
  }

  /** Put trapped atoms in their cells (positions now) and predict every atom. */
  private setup(): void {
    const S = this.S;
    const halfG = 0.5 * this.g;
    const now = this.time;
    for (let i = 0; i < this.n; i++) {
      if (this.status[i] !== TRAPPED) continue;
      const b = ROW * i;
      const dt = now - S[b + T];
      const xn = flightX(S[b + X], S[b + VX], dt);
      const yn = flightY(S[b + Y], S[b + VY], halfG, dt);
      this.link(i, this.clampCell(xn, this.gx0, this.nx), this.clampCell(yn, this.gy0, this.ny));
    }
    for (let i = 0; i < this.n; i++) {
      this.heap[i] = i;
      this.hpos[i] = i;
      this.heapT[i] = Infinity;
    }
    for (let i = 0; i < this.n; i++) {
      this.predictReal(i);
      this.predictCross(i);
      this.setKey(i);
    }
  }

  // -- heap ------------------------------------------------------------------------------
  /** True if atom x's key (tx, rank, a, b) comes before atom y's. */
  private less(x: number, tx: number, y: number, ty: number): boolean {
    if (tx !== ty) return tx < ty;
    const kr = this.kRank;
    if (kr[x] !== kr[y]) return kr[x] < kr[y];
    const ka = this.kA;
    if (ka[x] !== ka[y]) return ka[x] < ka[y];
    return this.kB[x] < this.kB[y];
  }

  /** Atom i's key time changed to t: move it up or down to its place. */
  private sift(i: number, t: number): void {
    const heap = this.heap;
    const heapT = this.heapT;
    const hpos = this.hpos;
    const n = this.n;
    let p = hpos[i];
    while (p > 0) {
      const q = (p - 1) >> 2;
      const j = heap[q];
      const tj = heapT[q];
      if (!this.less(i, t, j, tj)) break;
      heap[p] = j;
      heapT[p] = tj;
      hpos[j] = p;
      p = q;
    }
    for (;;) {
      let c = 4 * p + 1;
      if (c >= n) break;
      const end = c + 4 <= n ? c + 4 : n;
      let cj = heap[c];
      let tc = heapT[c];
      for (let d = c + 1; d < end; d++) {
        const dj = heap[d];
        const td = heapT[d];
        if (this.less(dj, td, cj, tc)) {
          c = d;
          cj = dj;
          tc = td;
        }
      }
      if (!this.less(cj, tc, i, t)) break;
      heap[p] = cj;
      heapT[p] = tc;
      hpos[cj] = p;
      p = c;
    }
    heap[p] = i;
    heapT[p] = t;
    hpos[i] = p;
  }

  /** Atom i's key is the earlier of its crossing and its real event. */
  private setKey(i: number): void {
    let t: number;
    if (this.ct[i] <= this.rt[i]) {
      t = this.ct[i];
      this.kRank[i] = R_CROSS;
      this.kA[i] = i;
      this.kB[i] = this.xk[i];
    } else {
      t = this.rt[i];
      this.kRank[i] = this.rRank[i];
      this.kA[i] = this.rA[i];
      this.kB[i] = this.rB[i];
    }
    this.sift(i, t);
  }

  // -- grid ------------------------------------------------------------------------------
  private clampCell(u: number, u0: number, n: number): number {
    const c = Math.floor((u - u0) / this.cs);
    if (c < 0) return 0;
    if (c > n - 1) return n - 1;
    return c;
  }

  private link(i: number, ci: number, cj: number): void {
    this.cx[i] = ci;
    this.cy[i] = cj;
    const c = cj * this.nx + ci;
    const q = this.head[c];
    this.next[i] = q;
    this.prev[i] = -1;
    if (q >= 0) this.prev[q] = i;
    this.head[c] = i;
  }

  private unlink(i: number): void {
    const p = this.prev[i];
    const q = this.next[i];
    if (p >= 0) this.next[p] = q;
    else if (this.head[this.cy[i] * this.nx + this.cx[i]] === i)
      this.head[this.cy[i] * this.nx + this.cx[i]] = q;
    if (q >= 0) this.prev[q] = p;
    this.next[i] = -1;
    this.prev[i] = -1;
  }

  // -- predictions -----------------------------------------------------------------------
  /**
   * Pairs of trapped atom i with the atoms of cells [xlo, xhi] x [ylo, yhi] (seed Eqs.
   * 15-19). An earlier pair replaces i's real event; on a tie the solo event stays and
   * pairs go in (lower, higher) index order, as in the reference engine.
   */
  private scan(i: number, xlo: number, xhi: number, ylo: number, yhi: number): void {
    const S = this.S;
    const head = this.head;
    const next = this.next;
    const nx = this.nx;
    const g = this.g;
    const bi = ROW * i;
    const x = S[bi + X];
    const y = S[bi + Y];
    const vx = S[bi + VX];
    const vy = S[bi + VY];
    const t0 = S[bi + T];
    const ri = S[bi + R];
    let bt = this.rt[i];
    let pair = this.rRank[i] === R_PAIR;
    let ba = this.rA[i];
    let bb = this.rB[i];
    let best = -1;
    for (let yy = ylo; yy <= yhi; yy++) {
      for (let xx = xlo; xx <= xhi; xx++) {
        for (let j = head[yy * nx + xx]; j >= 0; j = next[j]) {
          if (j === i) continue;
          const bj = ROW * j;
          const t = pairContactTime(
            x,
            y,
            vx,
            vy,
            t0,
            S[bj + X],
            S[bj + Y],
            S[bj + VX],
            S[bj + VY],
            S[bj + T],
            ri + S[bj + R],
            g,
          );
          if (t <= bt) {
            const lo = i < j ? i : j;
            const hi = i < j ? j : i;
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
      this.rt[i] = bt;
      this.rRank[i] = R_PAIR;
      this.rA[i] = ba;
      this.rB[i] = bb;
      this.rKind[i] = K_PAIR;
      this.rArg[i] = best;
      this.rPc[i] = this.counter[best];
    }
  }

  /** Atom i's real event: wall (SPEC 2.1) or pair if trapped, exit if escaped. */
  private predictReal(i: number): void {
    const S = this.S;
    const b = ROW * i;
    const st = this.status[i];
    let t = Infinity;
    let kind = K_NONE;
    if (st === TRAPPED) {
      t = wallContactTime(S[b + X], S[b + Y], S[b + VX], S[b + VY], S[b + T], this.a, this.g);
      kind = K_WALL;
    } else if (st === ESCAPED) {
      const r = S[b + R];
      t = exitTime(
        S[b + X],
        S[b + Y],
        S[b + VX],
        S[b + VY],
        S[b + T],
        this.g,
        this.xLeft - r,
        this.xRight + r,
        this.yBottom - r,
      );
      kind = K_EXIT;
    }
    this.rt[i] = t;
    this.rRank[i] = R_SOLO;
    this.rA[i] = i;
    this.rB[i] = 0;
    this.rKind[i] = kind;
    if (st === TRAPPED && !this.won) {
      const ci = this.cx[i];
      const cj = this.cy[i];
      this.scan(
        i,
        ci > 0 ? ci - 1 : 0,
        ci < this.nx - 1 ? ci + 1 : this.nx - 1,
        cj > 0 ? cj - 1 : 0,
        cj < this.ny - 1 ? cj + 1 : this.ny - 1,
      );
    }
  }

  /**
   * Atom i's next cell crossing (none unless trapped and the game is on). x: straight to
   * the next edge along vx. y: up through the top edge (first root, if the arc passes it),
   * else down through the bottom edge; roots at or before the arc's last y crossing (tly)
   * are ones already taken. Edge cells reach to infinity: no outer edge.
   */
  private predictCross(i: number): void {
    let bt = Infinity;
    let bk = K_NONE;
    let barg = 0;
    if (this.status[i] === TRAPPED && !this.won) {
      const S = this.S;
      const b = ROW * i;
      const g = this.g;
      const cs = this.cs;
      const x = S[b + X];
      const y = S[b + Y];
      const vx = S[b + VX];
      const vy = S[b + VY];
      const t0 = S[b + T];
      const ci = this.cx[i];
      const cj = this.cy[i];
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
      const tl = this.tly[i];
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
    this.ct[i] = bt;
    this.xk[i] = bk;
    this.xt[i] = barg;
  }

  /** Everything about atom i from its stored state. */
  private predict(i: number): void {
    this.predictReal(i);
    this.predictCross(i);
    this.setKey(i);
  }

  // -- state changes ---------------------------------------------------------------------
  /** Carry atom i's stored state to time t (exact free flight, seed Eqs. 3-4). */
  private move(i: number, t: number): void {
    const S = this.S;
    const b = ROW * i;
    const dt = t - S[b + T];
    S[b + X] = flightX(S[b + X], S[b + VX], dt);
    S[b + Y] = flightY(S[b + Y], S[b + VY], 0.5 * this.g, dt);
    S[b + VY] = flightVy(S[b + VY], this.g, dt);
    S[b + T] = t;
    this.tly[i] = -Infinity; // a new arc: none of its y crossings taken yet
  }

  private log(kind: number, i: number, j: number, t: number): void {
    if (!this.recordEvents) return;
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

  /** Event k of the log: [kind, i, j, time]. */
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

  /** Atom i leaves the trapped set (over the rim or by the knife). */
  private remove(i: number, newStatus: number): void {
    this.status[i] = newStatus;
    this.nTrapped--;
    this.energySum -= this.energy(i);
    this.counter[i] = (this.counter[i] + 1) | 0;
    this.unlink(i);
    this.predict(i);
    this.checkWin();
  }

  /** Remove trapped atom i at once if its energy exceeds m g H; true if removed. */
  private knifeCut(i: number, t: number): boolean {
    if (!this.knife) return false;
    const m = this.S[ROW * i + M];
    if (this.energy(i) > m * this.g * this.trapHeight) {
      this.log(EV_KNIFE, i, -1, t);
      this.remove(i, GONE);
      return true;
    }
    return false;
  }

  // -- public ----------------------------------------------------------------------------
  /** Process every event with time <= tEnd in time order, then set the clock. */
  advanceTo(tEnd: number): void {
    const S = this.S;
    const a = this.a;
    const heap = this.heap;
    const heapT = this.heapT;
    const counter = this.counter;
    const out = this.out;
    for (;;) {
      const i = heap[0];
      const te = heapT[0];
      if (!(te <= tEnd)) break;
      const kind = this.kRank[i] === R_CROSS ? this.xk[i] : this.rKind[i];
      // After the event: rp's prediction (full, or only its crossing if its real event
      // stands), then the pair's second atom's knife test and prediction.
      let rp = -1;
      let full = true;
      let pend = -1;
      let t = te;
      if (kind === K_PAIR) {
        const j = this.rArg[i];
        if (this.won || counter[j] !== this.rPc[i]) {
          this.staleCount++; // the partner moved on (or pairs are over)
          rp = i;
        } else {
          const lo = i < j ? i : j;
          const hi = i < j ? j : i;
          t = te >= this.time ? te : this.time;
          this.time = t;
          this.move(lo, t);
          this.move(hi, t);
          const bl = ROW * lo;
          const bh = ROW * hi;
          collidePair(
            S[bh + X] - S[bl + X],
            S[bh + Y] - S[bl + Y],
            S[bl + VX],
            S[bl + VY],
            S[bh + VX],
            S[bh + VY],
            S[bl + M],
            S[bh + M],
            out,
          );
          S[bl + VX] = out[0];
          S[bl + VY] = out[1];
          S[bh + VX] = out[2];
          S[bh + VY] = out[3];
          this.pairCount++;
          counter[lo] = (counter[lo] + 1) | 0;
          counter[hi] = (counter[hi] + 1) | 0;
          this.log(EV_PAIR, lo, hi, t);
          if (!this.knifeCut(lo, t)) rp = lo;
          pend = hi;
        }
      } else if (kind === K_CROSS_X || kind === K_CROSS_Y) {
        this.crossingCount++;
        if (this.won) {
          rp = i; // the grid is no longer kept once the gas has condensed
        } else {
          // Into the next cell; only the row or column of cells that came within reach
          // needs a scan: pairs with the other neighbours are held already.
          const ci = this.cx[i];
          const cj = this.cy[i];
          const tgt = this.xt[i];
          this.unlink(i);
          if (kind === K_CROSS_X) {
            this.link(i, tgt, cj);
            const c = 2 * tgt - ci;
            if (c >= 0 && c < this.nx)
              this.scan(i, c, c, cj > 0 ? cj - 1 : 0, cj < this.ny - 1 ? cj + 1 : this.ny - 1);
          } else {
            this.link(i, ci, tgt);
            this.tly[i] = te;
            const c = 2 * tgt - cj;
            if (c >= 0 && c < this.ny)
              this.scan(i, ci > 0 ? ci - 1 : 0, ci < this.nx - 1 ? ci + 1 : this.nx - 1, c, c);
          }
          rp = i;
          full = false;
        }
      } else if (kind === K_WALL) {
        t = te >= this.time ? te : this.time;
        this.time = t;
        this.move(i, t);
        const b = ROW * i;
        const x = S[b + X];
        if (Math.abs(x) > this.xRim) {
          // over the rim: escaped (SPEC 2.3)
          this.log(EV_ESCAPE, i, -1, t);
          this.remove(i, ESCAPED);
          continue;
        }
        const vx = S[b + VX];
        const vy = S[b + VY];
        const speed = Math.sqrt(vx * vx + vy * vy);
        const damped = this.won && speed >= WIN_DAMPING_MIN_SPEED; // seed Eq. (34)
        const changes = damped || speed < WALL_MIN_NORMAL_SPEED;
        if (changes) this.energySum -= this.energy(i);
        if (damped) settleWall(x, vx, vy, a, 1.0 - WIN_DAMPING, WIN_NORMAL_SPEED_FLOOR, out);
        else bounceWall(x, vx, vy, a, WALL_MIN_NORMAL_SPEED, out);
        S[b + VX] = out[0];
        S[b + VY] = out[1];
        if (changes) this.energySum += this.energy(i);
        this.wallCount++;
        counter[i] = (counter[i] + 1) | 0;
        this.log(EV_WALL, i, -1, t);
        rp = i;
      } else if (kind === K_EXIT) {
        t = te >= this.time ? te : this.time;
        this.time = t;
        this.move(i, t);
        this.status[i] = GONE;
        counter[i] = (counter[i] + 1) | 0;
        this.log(EV_GONE, i, -1, t);
        rp = i;
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
        rp = this.knifeCut(pend, t) ? -1 : pend;
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
      if (this.status[i] === TRAPPED) this.knifeCut(i, this.time);
    }
  }

  /** Declare the gas condensed now (demonstrations and tests). */
  forceWin(): void {
    this.won = true;
  }

  // -- reading ---------------------------------------------------------------------------
  /** Stored state of atom i: [x, y, vx, vy, t, radius, mass]. */
  stored(i: number): Float64Array {
    return this.S.subarray(ROW * i, ROW * i + 7);
  }

  /** Atom i's energy 1/2 m v^2 + m g y from its stored state (conserved in flight). */
  atomEnergy(i: number): number {
    return this.energy(i);
  }

  /** Position and velocity of atom i carried to time t into out = [x, y, vx, vy]. */
  stateAt(i: number, t: number, out: Float64Array): void {
    const S = this.S;
    const b = ROW * i;
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
    let bad = 0;
    for (let i = 0; i < this.n; i++) {
      if (this.status[i] !== TRAPPED) continue;
      const b = ROW * i;
      const dt = this.time - S[b + T];
      const ci = this.clampCell(flightX(S[b + X], S[b + VX], dt), this.gx0, this.nx);
      const cj = this.clampCell(flightY(S[b + Y], S[b + VY], 0.5 * this.g, dt), this.gy0, this.ny);
      if (Math.abs(ci - this.cx[i]) > 1 || Math.abs(cj - this.cy[i]) > 1) bad++;
    }
    return bad;
  }
}
