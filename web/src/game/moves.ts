/** A game's moves: the trap height held in each whole physics frame (issue 22). */

/** The held height of each whole frame, run-length coded (the game feeds it). */
export class MoveRecorder {
  runs: Array<[number, number]> = [];
  frames = 0;

  frame(height: number): void {
    this.frames += 1;
    const last = this.runs[this.runs.length - 1];
    if (last && last[0] === height) last[1] += 1;
    else this.runs.push([height, 1]);
  }
}

/** The frames of run-length coded moves. */
export function framesOf(runs: ReadonlyArray<readonly [number, number]>): number {
  return runs.reduce((sum, [, n]) => sum + n, 0);
}

/** The height of every frame of run-length coded moves, in order. */
export function heightsOf(runs: Array<[number, number]>): number[] {
  return runs.flatMap(([h, n]) => Array<number>(n).fill(h));
}
