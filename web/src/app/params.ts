/**
 * Settings from the page address, e.g. `?atoms=10000&radius=1&seed=3&speed=2`: for this
 * visit only, never saved (like the desktop's command-line options). One message per bad
 * value, naming it and what is allowed; the value is then ignored.
 */
import { checkSpeed } from "../game/rules";
import {
  checkEscape,
  checkNAtoms,
  checkRadius,
  checkTcLaw,
  maxAtoms,
  RADIUS_MAX,
  RADIUS_MIN,
  type Settings,
} from "../game/settings";

export interface PageParams {
  overrides: Partial<Settings>;
  seed: number | null;
  speed: number;
  notices: string[];
}

/** Physics' own limit on a count in the browser: beyond this a frame cannot keep up. */
export const URL_ATOMS_MAX = 100_000;

function num(text: string): number {
  return text.trim() === "" ? NaN : Number(text);
}

export function parseParams(search: string, saved: Settings): PageParams {
  const q = new URLSearchParams(search);
  const out: PageParams = { overrides: {}, seed: null, speed: 1, notices: [] };
  const bad = (name: string, err: unknown) =>
    out.notices.push(`Address: ${name} ${(err as Error).message.replace(/^\S+ /, "")}; ignored.`);
  const known = new Set(["atoms", "radius", "seed", "speed", "tc-law", "escape"]);
  for (const key of q.keys()) {
    if (!known.has(key))
      out.notices.push(`Address: unknown option ${key}; known: ${[...known].join(", ")}.`);
  }
  let radius = saved.radius;
  if (q.has("radius")) {
    try {
      radius = checkRadius(num(q.get("radius")!), false);
      out.overrides.radius = radius;
    } catch (err) {
      bad("radius", err);
    }
  }
  if (q.has("atoms")) {
    try {
      const n = checkNAtoms(num(q.get("atoms")!), radius, false);
      if (n > URL_ATOMS_MAX) {
        throw new RangeError(
          `n_atoms must be a whole number from 1 to ${URL_ATOMS_MAX} (got ${n})`,
        );
      }
      out.overrides.nAtoms = n;
    } catch (err) {
      bad("atoms", err);
    }
  } else if (out.overrides.radius !== undefined && radius >= RADIUS_MIN && radius <= RADIUS_MAX) {
    // Bigger atoms than saved: the saved count may not fit; take what does.
    out.overrides.nAtoms = Math.min(saved.nAtoms, maxAtoms(radius));
  }
  if (q.has("tc-law")) {
    try {
      out.overrides.tcLaw = checkTcLaw(q.get("tc-law"));
    } catch (err) {
      bad("tc-law", err);
    }
  }
  if (q.has("escape")) {
    try {
      out.overrides.escape = checkEscape(q.get("escape"));
    } catch (err) {
      bad("escape", err);
    }
  }
  if (q.has("seed")) {
    const s = num(q.get("seed")!);
    if (Number.isInteger(s) && s >= 0 && s <= 0xffffffff) out.seed = s;
    else
      out.notices.push(
        `Address: seed must be a whole number from 0 to 4294967295 (got ${q.get("seed")}); ignored.`,
      );
  }
  if (q.has("speed")) {
    try {
      out.speed = checkSpeed(num(q.get("speed")!));
    } catch (err) {
      bad("speed", err);
    }
  }
  return out;
}
