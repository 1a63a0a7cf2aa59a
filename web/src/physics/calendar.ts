/**
 * The event queue: one key per row, (time, rank, a, b), the least handed out first.
 *
 * An event calendar (Paul, J. Comput. Phys. 221, 615 (2007); Smallenburg 2022), as in the
 * Numba engine: time is cut into bins of width dt from a base time. Rows whose key lies in
 * the current bin or earlier sit in a small indexed 4-ary heap ordered by the full key;
 * later ones sit, unordered, in the doubly linked list of their bin (a ring of nBins lists),
 * beyond the ring in an overflow list, and with no event (time infinity) in a list of their
 * own. The bin of a time is monotone in the time, so every heap key comes before every
 * listed key and the heap's root is the least key of all. Most re-filed rows go to a list
 * in O(1); the heap stays about EVENTS_PER_BIN rows deep. A row's key parts and links share
 * one 32-byte line; everything is preallocated.
 */

/** The bin width aims at this many events per bin (the heap's typical size). */
const EVENTS_PER_BIN = 8;
/** The ring spans about this many events per row into the future. */
const RING_EVENTS_PER_ATOM = 2;

/** KEYED, 8 integers a row: the key parts after the time, heap place, list and its links. */
export const KEYED_RANK = 0; // key: (keyT, rank, tieA, tieB), see tables.ts's RANK_*
export const KEYED_TIE_A = 1;
export const KEYED_TIE_B = 2;
export const KEYED_HEAP_POS = 3; // place in the heap, -1 if in a list
export const KEYED_BIN = 4; // list it is filed in, -1 if in the heap
export const KEYED_NEXT = 5; // neighbours in that list, -1 at the ends
export const KEYED_PREV = 6;
export const KEYED_WIDTH = 8;

export class EventQueue {
  /** Key time of every row. */
  readonly keyT: Float64Array;
  /** KEYED rows. */
  readonly keyed: Int32Array;

  private readonly heap: Int32Array;
  private heapSize = 0;
  /** List heads: nBins ring bins, then the overflow list, then the no-event list. */
  private readonly heads: Int32Array;
  private readonly nBins: number;
  private nRing = 0;
  private nOver = 0;
  private binBase = 0.5;
  private binWidth = Infinity;
  /** The current bin and the bin of the last re-filing of the overflow list. */
  private bin = 0.5; // doubles from the start: bins outgrow 32-bit integers in long runs
  private scanBin = 0.5;

  constructor(readonly n: number) {
    this.keyT = new Float64Array(n).fill(Infinity);
    this.keyed = new Int32Array(KEYED_WIDTH * n);
    for (let r = 0; r < n; r++) {
      this.keyed[KEYED_WIDTH * r + KEYED_HEAP_POS] = -1;
      this.keyed[KEYED_WIDTH * r + KEYED_BIN] = -1;
    }
    this.heap = new Int32Array(n);
    const want = Math.max(1, Math.floor((RING_EVENTS_PER_ATOM * n) / EVENTS_PER_BIN));
    this.nBins = Math.max(16, 2 ** Math.ceil(Math.log2(want)));
    this.heads = new Int32Array(this.nBins + 2).fill(-1);
  }

  /**
   * Row r's new key: its time already written to keyT[r] (times never travel as arguments:
   * V8 boxes a double passed to a call it does not inline), then the other parts; re-filed.
   */
  file(r: number, rank: number, a: number, b: number): void {
    this.load(r, rank, a, b);
    this.place(r);
  }

  /** Row r's key parts beside keyT[r], not filed (rebuild files every row). */
  load(r: number, rank: number, a: number, b: number): void {
    const q = KEYED_WIDTH * r;
    this.keyed[q + KEYED_RANK] = rank;
    this.keyed[q + KEYED_TIE_A] = a;
    this.keyed[q + KEYED_TIE_B] = b;
  }

  rankOf(r: number): number {
    return this.keyed[KEYED_WIDTH * r + KEYED_RANK];
  }

  /** The row with the least key, or -1 if no row has a finite key. */
  top(): number {
    if (this.heapSize === 0 && !this.nextBin()) return -1;
    return this.heap[0];
  }

  /**
   * Empty the queue and file every row again from base time `now`, the bin width set from
   * the pending events (so that about EVENTS_PER_BIN events fall in a bin).
   */
  rebuild(now: number): void {
    this.reset(now, this.fittedBinWidth(now));
  }

  private reset(base: number, dt: number): void {
    this.heads.fill(-1);
    const K = this.keyed;
    for (let r = 0; r < this.n; r++) {
      K[KEYED_WIDTH * r + KEYED_HEAP_POS] = -1;
      K[KEYED_WIDTH * r + KEYED_BIN] = -1;
    }
    this.heapSize = 0;
    this.nRing = 0;
    this.nOver = 0;
    this.binBase = base;
    this.binWidth = dt;
    this.bin = 0;
    this.scanBin = 0;
    for (let r = 0; r < this.n; r++) this.place(r);
  }

  /**
   * Bin width from the event rate of the bulk: the mean time to the pending events, trimmed
   * twice to the bulk (a few atoms far above the cup would dominate it), over their count.
   */
  private fittedBinWidth(now: number): number {
    let m = Infinity;
    let c = 0;
    for (let pass = 0; pass < 3; pass++) {
      let s = 0;
      c = 0;
      for (let r = 0; r < this.n; r++) {
        const g = this.keyT[r] - now;
        if (g < m * 3) {
          s += g > 0 ? g : 0;
          c++;
        }
      }
      if (c === 0 || !(s > 0)) return 1;
      m = s / c;
    }
    return (EVENTS_PER_BIN * m) / c;
  }

  /** True if row x's key comes before row y's. */
  private less(x: number, y: number): boolean {
    const tx = this.keyT[x];
    const ty = this.keyT[y];
    if (tx !== ty) return tx < ty;
    const K = this.keyed;
    const qx = KEYED_WIDTH * x;
    const qy = KEYED_WIDTH * y;
    if (K[qx + KEYED_RANK] !== K[qy + KEYED_RANK]) return K[qx + KEYED_RANK] < K[qy + KEYED_RANK];
    if (K[qx + KEYED_TIE_A] !== K[qy + KEYED_TIE_A])
      return K[qx + KEYED_TIE_A] < K[qy + KEYED_TIE_A];
    return K[qx + KEYED_TIE_B] < K[qy + KEYED_TIE_B];
  }

  /** Move the heap entry at place p up or down to its place (children 4p+1..4p+4). */
  private sift(p: number): void {
    const heap = this.heap;
    const K = this.keyed;
    const n = this.heapSize;
    const i = heap[p];
    while (p > 0) {
      const q = (p - 1) >> 2;
      const j = heap[q];
      if (!this.less(i, j)) break;
      heap[p] = j;
      K[KEYED_WIDTH * j + KEYED_HEAP_POS] = p;
      p = q;
    }
    for (;;) {
      let c = 4 * p + 1;
      if (c >= n) break;
      const end = c + 4 <= n ? c + 4 : n;
      let cj = heap[c];
      for (let d = c + 1; d < end; d++) {
        const dj = heap[d];
        if (this.less(dj, cj)) {
          c = d;
          cj = dj;
        }
      }
      if (!this.less(cj, i)) break;
      heap[p] = cj;
      K[KEYED_WIDTH * cj + KEYED_HEAP_POS] = p;
      p = c;
    }
    heap[p] = i;
    K[KEYED_WIDTH * i + KEYED_HEAP_POS] = p;
  }

  private listAdd(r: number, l: number): void {
    const K = this.keyed;
    const h = this.heads[l];
    K[KEYED_WIDTH * r + KEYED_BIN] = l;
    K[KEYED_WIDTH * r + KEYED_NEXT] = h;
    K[KEYED_WIDTH * r + KEYED_PREV] = -1;
    if (h >= 0) K[KEYED_WIDTH * h + KEYED_PREV] = r;
    this.heads[l] = r;
    if (l < this.nBins) this.nRing++;
    else if (l === this.nBins) this.nOver++;
  }

  private listDel(r: number): void {
    const K = this.keyed;
    const l = K[KEYED_WIDTH * r + KEYED_BIN];
    const p = K[KEYED_WIDTH * r + KEYED_PREV];
    const q = K[KEYED_WIDTH * r + KEYED_NEXT];
    if (p >= 0) K[KEYED_WIDTH * p + KEYED_NEXT] = q;
    else this.heads[l] = q;
    if (q >= 0) K[KEYED_WIDTH * q + KEYED_PREV] = p;
    K[KEYED_WIDTH * r + KEYED_BIN] = -1;
    if (l < this.nBins) this.nRing--;
    else if (l === this.nBins) this.nOver--;
  }

  /** File row r under its key time: in the heap if its bin has come, else in a list. */
  private place(r: number): void {
    const K = this.keyed;
    const t = this.keyT[r];
    const q = (t - this.binBase) / this.binWidth;
    let p = K[KEYED_WIDTH * r + KEYED_HEAP_POS];
    if (q < this.bin + 1) {
      if (p < 0) {
        if (K[KEYED_WIDTH * r + KEYED_BIN] >= 0) this.listDel(r);
        p = this.heapSize++;
        this.heap[p] = r;
      }
      this.sift(p);
      return;
    }
    const nb = this.nBins;
    const l = t === Infinity ? nb + 1 : q < this.bin + nb ? Math.floor(q) % nb : nb;
    if (p < 0) {
      const was = K[KEYED_WIDTH * r + KEYED_BIN];
      if (was === l) return; // lists are unordered: nothing to do
      if (was >= 0) this.listDel(r);
      this.listAdd(r, l);
      return;
    }
    this.listAdd(r, l);
    K[KEYED_WIDTH * r + KEYED_HEAP_POS] = -1;
    const last = --this.heapSize;
    if (p === last) return;
    const j = this.heap[last];
    this.heap[p] = j;
    K[KEYED_WIDTH * j + KEYED_HEAP_POS] = p;
    this.sift(p);
  }

  /** Fill the empty heap from the next non-empty bin; false if no row has an event. */
  private nextBin(): boolean {
    const nb = this.nBins;
    const K = this.keyed;
    while (this.heapSize === 0) {
      if (this.nRing === 0) {
        if (this.nOver === 0) return false;
        // Nothing in the ring: jump to the overflow's earliest bin.
        let m = Infinity;
        for (let j = this.heads[nb]; j >= 0; j = K[KEYED_WIDTH * j + KEYED_NEXT])
          if (this.keyT[j] < m) m = this.keyT[j];
        if (!(m < Infinity)) return false; // only a NaN could do this: nothing to hand out
        const q = (m - this.binBase) / this.binWidth;
        if (q > 1e15) {
          this.reset(m, this.binWidth); // far beyond: start the bins there
          continue;
        }
        this.bin = Math.floor(q) - 1;
        this.scanBin = this.bin - nb;
      }
      const cb = ++this.bin;
      if (cb >= this.scanBin + nb) {
        // The ring moved on by its length: re-file the overflow list.
        this.scanBin = cb;
        for (let j = this.heads[nb]; j >= 0;) {
          const k = K[KEYED_WIDTH * j + KEYED_NEXT];
          this.place(j);
          j = k;
        }
      }
      const s = cb % nb;
      let j = this.heads[s];
      this.heads[s] = -1;
      while (j >= 0) {
        const k = K[KEYED_WIDTH * j + KEYED_NEXT];
        K[KEYED_WIDTH * j + KEYED_BIN] = -1;
        this.nRing--;
        const p = this.heapSize++;
        this.heap[p] = j;
        this.sift(p);
        j = k;
      }
    }
    return true;
  }
}
