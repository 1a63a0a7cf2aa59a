/**
 * The shared start generator (issue 22.1), twin of src/evapcool/physics/start.py: the same
 * atoms from the same seed in every edition. Random numbers come from a counter-based hash
 * (MurmurHash3's 32-bit finalizer over the seed, a stream number and a counter); turning them
 * into a start takes only + - * / and sqrt, which IEEE 754 rounds exactly everywhere. The
 * golden starts (web/test/golden/starts.json, written by Python) hold both to the same bits.
 */

/** Which generator built a start from a seed (recorded in replays). */
export const START_GENERATOR = 1;
/** Largest seed a double holds exactly: larger seeds cannot be replayed in a browser. */
export const SEED_PORTABLE_MAX = 2 ** 53 - 1;
/** Streams: each use of random numbers has its own. */
export const STREAM_JITTER = 1;
export const STREAM_SPEED = 2;
export const STREAM_DIRECTION = 3;
/** Candidates per atom for a point of the unit disk; then its own fallback stream. */
export const CANDIDATES = 8;
export const FALLBACK = 16;

/** MurmurHash3's finalizer: a bijection of 32-bit words that mixes every bit. */
function fmix32(h: number): number {
  h = (h ^ (h >>> 16)) >>> 0;
  h = Math.imul(h, 0x85ebca6b) >>> 0;
  h = (h ^ (h >>> 13)) >>> 0;
  h = Math.imul(h, 0xc2b2ae35) >>> 0;
  return (h ^ (h >>> 16)) >>> 0;
}

/** One stream of a seed: 32-bit words and doubles in [0, 1) by counter. */
export class Stream {
  private readonly keyA: number;
  private readonly keyB: number;

  /** seed: a whole number 0 .. 2^53 - 1 (its low and high 32-bit words are used). */
  constructor(seed: number, stream: number) {
    if (!Number.isSafeInteger(seed) || seed < 0)
      throw new RangeError(
        `seed must be a whole number from 0 to ${SEED_PORTABLE_MAX} (got ${seed})`,
      );
    const lo = seed >>> 0;
    const hi = Math.floor(seed / 4294967296) >>> 0;
    const salt = Math.imul(0x9e3779b9, stream) >>> 0;
    this.keyA = fmix32((lo ^ salt) >>> 0);
    this.keyB = fmix32((hi ^ this.keyA ^ 0x5bd1e995) >>> 0);
  }

  /** The 32-bit word at counter c (0 <= c < 2^32). */
  word(c: number): number {
    return fmix32((fmix32((c ^ this.keyA) >>> 0) ^ this.keyB) >>> 0);
  }

  /** The k-th double in [0, 1), from words 2k and 2k + 1 (27 + 26 bits). */
  uniform(k: number): number {
    const hi = this.word(2 * k) >>> 5;
    const lo = this.word(2 * k + 1) >>> 6;
    return (hi * 67108864 + lo) / 9007199254740992;
  }
}

/**
 * Atom i's first candidate (x, y) of the square [-1, 1)^2 with inner <= x^2 + y^2 < 1, written
 * into out[2i], out[2i + 1], for i < n: candidates i * CANDIDATES + c, then the fallback stream.
 */
export function diskPoints(seed: number, stream: number, n: number, inner = 0): Float64Array {
  const out = new Float64Array(2 * n);
  const main = new Stream(seed, stream);
  let spare: Stream | null = null;
  for (let i = 0; i < n; i++) {
    if (pick(main, i * CANDIDATES, CANDIDATES, inner, out, i)) continue;
    spare ??= new Stream(seed, stream + 16 * FALLBACK);
    if (!pick(spare, i * FALLBACK, FALLBACK, inner, out, i))
      throw new Error(`no point in the disk for atom ${i} (seed ${seed}): impossible odds`);
  }
  return out;
}

function pick(
  s: Stream,
  first: number,
  count: number,
  inner: number,
  out: Float64Array,
  i: number,
): boolean {
  for (let c = first; c < first + count; c++) {
    const x = 2 * s.uniform(2 * c) - 1;
    const y = 2 * s.uniform(2 * c + 1) - 1;
    const r2 = x * x + y * y;
    if (r2 >= inner && r2 < 1) {
      out[2 * i] = x;
      out[2 * i + 1] = y;
      return true;
    }
  }
  return false;
}

/** A fresh seed a desktop can replay too (crypto randomness where available), <= 2^53 - 1. */
export function randomSeed(): number {
  const c = (globalThis as { crypto?: { getRandomValues?: (a: Uint32Array) => Uint32Array } })
    .crypto;
  const a = new Uint32Array(2);
  if (c && c.getRandomValues) c.getRandomValues(a);
  else for (let k = 0; k < 2; k++) a[k] = Math.floor(Math.random() * 4294967296);
  return (a[0] & 0x1fffff) * 4294967296 + a[1];
}
