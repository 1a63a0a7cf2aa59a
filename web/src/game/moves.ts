/** A game's moves: the trap height held in each whole physics frame (issue 22), run-length
 * coded [height, frames] as the core records them (core/play.c). */

/** The frames of run-length coded moves. */
export function framesOf(runs: ReadonlyArray<readonly [number, number]>): number {
  return runs.reduce((sum, [, n]) => sum + n, 0);
}
