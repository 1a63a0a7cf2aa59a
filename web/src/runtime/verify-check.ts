/**
 * One pasted replay code checked: decoded in the page (verifier.ts; bounded: replaycode.ts
 * refuses a code as it unpacks past the longest game), then replayed with the game's rules,
 * in the verify panel's worker (physics.worker.ts) or the page's own loop where none runs.
 */
import { makeSimulation } from "../game/engine";
import { checkClaim, replay, ReplayError, type Recording, type Verdict } from "../game/replay";

/** One pasted code's outcome. */
export interface Checked {
  code: string;
  verdict: Verdict | null;
  edition: string;
  reason: string;
}

/** A code to replay (its recording), or its outcome already (it could not be decoded). */
export type Decoded = { code: string; recording: Recording } | Checked;

/** A code's refusal: the reason's protocol name (a ReplayError's), else the error's words. */
export function refused(code: string, err: unknown): Checked {
  const reason = err instanceof ReplayError ? err.reason : (err as Error).message;
  return { code, verdict: null, edition: "", reason };
}

/** The outcome of replaying a decoded code (the long part: up to 36 000 frames). */
export function replayed(item: Decoded): Checked {
  if (!("recording" in item)) return item;
  const { code, recording } = item;
  try {
    // decode checked the recording's fields (the worker need not carry those checks).
    const verdict = checkClaim(recording, replay(recording, makeSimulation));
    return { code, verdict, edition: recording.edition, reason: "" };
  } catch (err) {
    return refused(code, err);
  }
}
