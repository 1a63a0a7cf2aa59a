/**
 * The core's WebAssembly module and its instances (one per engine, start or check: each its
 * own memory), and the core's functions that need no engine: the start from a seed, the cup's
 * capacity and the portable power (core/start.c).
 */
import packedCore from "virtual:evapcool-wasm";
import { ParameterError, pyG } from "../limits";
import { SEED_PORTABLE_MAX } from "./start";
import type { CoreExports } from "./core-exports";

/** The WebAssembly memory (at most 4 GB) could not hold the engine's tables. */
export const OUT_OF_MEMORY = (n: number) =>
  `nAtoms must fit the engine core's memory (${n} atoms did not: not enough memory)`;

let compiled: WebAssembly.Module | null = null;
/** The core's bytes handed over by the page (the worker's bundle carries none of its own). */
let given: Uint8Array<ArrayBuffer> | null = null;

/** The core's bytes: the page's own, or those handed over (empty if neither). */
export function coreBytes(): Uint8Array<ArrayBuffer> {
  return given ?? packedCore;
}

/** Whether this page or worker has the WebAssembly core and can compile it (its SIMD
 * included): the page cannot start without. */
export function haveCore(): boolean {
  const bytes = coreBytes();
  return bytes.length > 0 && WebAssembly.validate(bytes);
}

/** The physics worker gets the core from the page: one copy in the page's file, not two. */
export function provideCore(bytes: Uint8Array<ArrayBuffer>): void {
  given = bytes;
}

/** A fresh instance of the core (its own memory: an engine, one start or one check computed);
 * its module is compiled once, synchronously, on first use. */
export function instance(): CoreExports {
  if (compiled === null) {
    const bytes = coreBytes();
    if (bytes.length === 0) throw new Error("the engine core was not handed to this worker");
    compiled = new WebAssembly.Module(bytes);
  }
  return new WebAssembly.Instance(compiled, {}).exports as unknown as CoreExports;
}

/**
 * The start from a seed (core/start.c, the shared start generator of both editions): positions
 * and velocities ([x0, y0, ...], [vx0, vy0, ...]) of n atoms of equal radius, rows of cells from
 * the bottom, each atom at a uniform point of its cell's jitter disk, moving in a uniform
 * direction. ParameterError if they do not fit below yTop; RangeError for a bad seed.
 */
export function loadCup(
  n: number,
  radius: number,
  curvature: number,
  yTop: number,
  seed: number,
): { positions: Float64Array; velocities: Float64Array } {
  if (!Number.isSafeInteger(seed) || seed < 0)
    throw new RangeError(
      `seed must be a whole number from 0 to ${SEED_PORTABLE_MAX} (got ${seed})`,
    );
  const c = instance();
  const at = c.core_buffer(c.core_new(), 4 * n);
  if (at === 0) throw new RangeError(OUT_OF_MEMORY(n));
  const placed = c.core_load_cup(
    at,
    at + 16 * n,
    n,
    radius,
    curvature,
    yTop,
    seed >>> 0,
    Math.floor(seed / 4294967296) >>> 0,
  );
  if (placed < 0)
    throw new Error(`no point in the disk for an atom (seed ${seed}): impossible odds`);
  if (placed < n)
    throw new ParameterError(
      "nAtoms",
      `${n} atoms of radius ${pyG(radius)} do not fit in the cup below the window top ` +
        `(at most ${placed} fit)`,
      ": ",
    );
  const out = new Float64Array(c.memory.buffer, at, 4 * n);
  return { positions: out.slice(0, 2 * n), velocities: out.slice(2 * n) };
}

/** An instance for the core's functions that take no memory: one serves every call. */
let tools: CoreExports | null = null;

/** How many atoms of this radius the start places with every disk below yTop (core/start.c). */
export function startCapacity(radius: number, curvature: number, yTop: number): number {
  tools ??= instance();
  return tools.core_cup_capacity(radius, curvature, yTop);
}

/** x^p for x >= 0 and 0 < p <= 10 from products and square roots: the same bits everywhere. */
export function power(x: number, p: number): number {
  tools ??= instance();
  return tools.core_power(x, p);
}
