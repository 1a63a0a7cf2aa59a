/**
 * The seeds of the shared start generator (issue 22.1). The generator itself is the core's
 * (core/start.c, called by instance.ts's loadCup): the same atoms from the same seed in every
 * edition; the golden starts (web/test/golden/starts.json, written by Python) hold it.
 * Python's twin: `src/evapcool/physics/start.py` (docs/twins.md).
 */

/** Which generator built a start from a seed (recorded in replays). */
export const START_GENERATOR = 1;
/** Largest seed a double holds exactly: larger seeds cannot be replayed in a browser. */
export const SEED_PORTABLE_MAX = 2 ** 53 - 1;
/** A fresh seed a desktop can replay too (crypto randomness where available), <= 2^53 - 1. */
export function randomSeed(): number {
  const c = (globalThis as { crypto?: { getRandomValues?: (a: Uint32Array) => Uint32Array } })
    .crypto;
  const a = new Uint32Array(2);
  if (c && c.getRandomValues) c.getRandomValues(a);
  else for (let k = 0; k < 2; k++) a[k] = Math.floor(Math.random() * 4294967296);
  return (a[0] & 0x1fffff) * 4294967296 + a[1];
}
