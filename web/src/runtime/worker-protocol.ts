/**
 * The physics worker's protocol: the messages between the page and the worker, and the
 * layout of the frame buffers that carry the atoms and what the view needs back.
 *
 * Three ArrayBuffers go round (transferred, never copied; made by the worker at a start or
 * a restart with more atoms, never per frame): the worker fills a free one after advancing and posts it; the page draws the newest and
 * sends the one it drew before back with its next display frame ("vsync"), which also
 * paces the worker to the display. Each buffer holds a header of named Float64 slots and
 * the trapped and escaped atoms in columns (the AtomArrays the view draws).
 */
import type { Checked, Decoded } from "./verify-check";
import type { GameConfig } from "../game/rules";
import type { AtomArrays } from "../game/sim";

/** Header slots (Float64) of a frame buffer; booleans as 0 / 1, null as NaN. */
export const HEADER = {
  /** The last command the worker applied (its seq). */
  seq: 0,
  generation: 1,
  time: 2,
  nAtoms: 3,
  nTrapped: 4,
  nEscaped: 5,
  trapHeight: 6,
  rimHalfWidth: 7,
  curvature: 8,
  gravity: 9,
  temperature: 10,
  initialTemperature: 11,
  criticalTemperature: 12,
  tcExponent: 13,
  won: 14,
  winRule: 15,
  collisionCount: 16,
  /** The trap origin's lift above the wall's lowest point; the room's left and top (view/screen.ts). */
  originLift: 17,
  roomLeft: 18,
  wonAt: 19,
  trappedCount: 20,
  escapedCount: 21,
  /** Atoms each column has room for. */
  capacity: 22,
  /** Worker ms spent advancing the physics for this frame. */
  physicsMs: 23,
  /** The game's score: atoms in the cup at the whole frame the win was seen (NaN before). */
  score: 24,
  roomRight: 25,
  roomBelow: 26,
  roomAbove: 27,
  /** Why the gas can no longer condense: the core's reach code (REACH_*, LOSE_REASONS's index). */
  tooFew: 28,
  /** Every atom has left the cup (Game.allEscaped): 0 / 1. */
  allEscaped: 29,
} as const;
export const HEADER_SLOTS = 32;

/** Columns per atom group, in buffer order. */
export const COLUMNS = ["x", "y", "vx", "vy", "radius", "mass"] as const;

/** Bytes of a frame buffer with room for `capacity` atoms in each group. */
export function bufferBytes(capacity: number): number {
  return 8 * (HEADER_SLOTS + 2 * COLUMNS.length * Math.max(1, capacity));
}

/** Atoms a frame buffer has room for in each group. */
export function bufferCapacity(buffer: ArrayBuffer): number {
  return (buffer.byteLength / 8 - HEADER_SLOTS) / (2 * COLUMNS.length);
}

/** Copy n atoms into a group's columns (no allocation). */
export function copyAtoms(from: AtomArrays, to: AtomArrays): void {
  const n = from.count;
  for (const c of COLUMNS) {
    const src = from[c];
    const dst = to[c];
    for (let i = 0; i < n; i++) dst[i] = src[i];
  }
  to.count = n;
}

export interface FrameViews {
  buffer: ArrayBuffer;
  header: Float64Array;
  trapped: AtomArrays;
  escaped: AtomArrays;
}

/** Typed views over a frame buffer (a few small objects per buffer received; no data copied). */
export function frameViews(buffer: ArrayBuffer): FrameViews {
  const header = new Float64Array(buffer, 0, HEADER_SLOTS);
  const capacity = bufferCapacity(buffer);
  let offset = 8 * HEADER_SLOTS;
  const group = (): AtomArrays => {
    const col = () => {
      const a = new Float64Array(buffer, offset, capacity);
      offset += 8 * capacity;
      return a;
    };
    return { x: col(), y: col(), vx: col(), vy: col(), radius: col(), mass: col(), count: 0 };
  };
  const trapped = group();
  const escaped = group();
  trapped.count = header[HEADER.trappedCount];
  escaped.count = header[HEADER.escapedCount];
  return { buffer, header, trapped, escaped };
}

/** What the page asks of the game in the worker (applied in order, as on the main thread). */
export type Command =
  | { kind: "paused"; paused: boolean }
  | { kind: "height"; height: number }
  | { kind: "speed"; speed: number }
  | { kind: "step" }
  | { kind: "frames"; n: number }
  | { kind: "restart"; config: GameConfig }
  /** The physics' own switch to the won state (tests of the condensate). */
  | { kind: "forceWin" };

export type ToWorker =
  /** The first game (a config the page has checked); the worker makes the buffers. */
  | { type: "start"; config: GameConfig; core: Uint8Array<ArrayBuffer> }
  | { type: "command"; seq: number; command: Command }
  /** A display frame began: advance by the time since the last one; a drawn buffer back. */
  | { type: "vsync"; frameSeconds: number; buffer: ArrayBuffer | null }
  /** A buffer back without a display frame (frames arrived faster than they were drawn). */
  | { type: "give"; buffer: ArrayBuffer }
  /** Replay a golden trace's text with the engine the page uses (tests). */
  | { type: "replay"; id: number; text: string }
  /** The moves of the game so far (a recording at the win, issue 22). */
  | { type: "moves"; id: number }
  /** The verify panel's codes, replayed one by one (a worker of their own: closing the
   * panel terminates it). */
  | { type: "verify"; core: Uint8Array<ArrayBuffer>; codes: Decoded[] };

export type FromWorker =
  /** The worker's code runs (posted before anything else). */
  | { type: "hello" }
  | { type: "frame"; buffer: ArrayBuffer }
  | { type: "replayed"; id: number; text: string }
  | { type: "moves"; id: number; runs: Array<[number, number]> }
  /** The outcome of the verify message's codes[index]. */
  | { type: "verified"; index: number; checked: Checked }
  /** A message the worker could not handle (the page falls back to its own loop). */
  | { type: "failed"; message: string };
