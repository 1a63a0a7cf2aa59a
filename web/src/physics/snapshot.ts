/**
 * The atoms read out of the core's tables as per-atom columns: what Python reads of its
 * World's arrays with NumPy (`Simulation` calls these).
 */
import { ESCAPED, TRAPPED } from "./constants";
import { bad } from "./state";
import type { WasmEngine } from "./wasm";

/** Per-atom columns of trapped or escaped atoms now; `count` rows are valid. */
export interface AtomSnapshot {
  count: number;
  /** The atom's index (stable for the whole run: colours, selection). */
  index: Int32Array;
  x: Float64Array;
  y: Float64Array;
  vx: Float64Array;
  vy: Float64Array;
  radius: Float64Array;
  mass: Float64Array;
  /** 1/2 m v^2 + m g y. */
  energy: Float64Array;
}

export type AtomGroup = "trapped" | "escaped";

/** The group's atoms at time t, written into `out` when it has room (no allocation per
 * frame for a view that keeps its snapshot). */
export function snapshot(
  e: WasmEngine,
  which: AtomGroup,
  t: number,
  out?: AtomSnapshot,
): AtomSnapshot {
  const status = which === "trapped" ? TRAPPED : which === "escaped" ? ESCAPED : -1;
  if (status < 0) throw bad("which", `"trapped" or "escaped"`, which);
  const n = e.nAtoms;
  const snap = out !== undefined && out.index.length >= n ? out : emptySnapshot(n);
  const [count, cols] = e.columns(status, t);
  const column = (c: number) => cols.subarray(c * n, c * n + count);
  snap.index.set(column(0));
  COLUMNS.forEach((name, c) => snap[name].set(column(c + 1)));
  snap.count = count;
  return snap;
}

/** The snapshot's columns after the index, in core_snapshot's order. */
const COLUMNS = ["x", "y", "vx", "vy", "radius", "mass", "energy"] as const;

function emptySnapshot(n: number): AtomSnapshot {
  const f = () => new Float64Array(n);
  const [x, y, vx, vy, radius, mass, energy] = [f(), f(), f(), f(), f(), f(), f()];
  return { count: 0, index: new Int32Array(n), x, y, vx, vy, radius, mass, energy };
}

/** Atoms of this status (TRAPPED, ESCAPED, ...). */
export function countOf(e: WasmEngine, status: number): number {
  let k = 0;
  for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === status) k++;
  return k;
}

/** Energy 1/2 m v^2 + m g y of each of the n trapped atoms, in index order. */
export function trappedEnergies(e: WasmEngine, n: number): Float64Array {
  const out = new Float64Array(n);
  let k = 0;
  for (let i = 0; i < e.nAtoms; i++) if (e.statusOf(i) === TRAPPED) out[k++] = e.atomEnergy(i);
  return out;
}

/** Two snapshot columns interleaved, [a0, b0, a1, b1, ...], of their first n rows. */
export function interleaved(a: Float64Array, b: Float64Array, n: number): Float64Array {
  const out = new Float64Array(2 * n);
  for (let k = 0; k < n; k++) {
    out[2 * k] = a[k];
    out[2 * k + 1] = b[k];
  }
  return out;
}
