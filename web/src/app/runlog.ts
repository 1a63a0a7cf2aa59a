/**
 * Twin of Python's app/runlog.py (docs/twins.md).
 * "Save this run" (issue 48): the numbers of the run on screen as a CSV file a lab plot
 * reads: `evapcool lab`'s format (src/evapcool/lab/io.py: '# key: <json>' lines, then its
 * columns, one row a second of play or one a frame), what the page does not count written
 * nan, the settings and the replay code in the header.
 */
import { recordingOf } from "../game/replay";
import { encode } from "../game/replaycode";
import type { Game } from "../game/rules";
import { FPS } from "../game/engine";
import { RemoteGame, type GameLike } from "../runtime/remote";

/** evapcool lab's columns, in its order (labformat.py COLUMNS; tests/test_twins.py binds them). */
export const LAB_COLUMNS = [
  "frame",
  "n_trapped",
  "temperature",
  "critical_temperature",
  "trap_height",
  "total_energy",
  "pair_collisions",
  "wall_collisions",
  "escaped",
  "evaporated",
  "evaporated_energy",
  "excess_energy",
  "spilled",
  "spilled_energy",
  "phase_space_density",
  "won",
] as const;
const CSV_MAGIC = "# evapcool lab results";
/** Rows kept at most (lab/io.py's RECORDS_MAX). */
const ROWS_MAX = 100_000;

type Row = [number, number, number, number, number, number, number];

export class RunLog {
  private rows: Row[] = [];
  private generation = -1;
  private lastKey = -1;
  /** One row a frame (else one a second of play). */
  everyFrame = false;

  /** A drawn frame: a row when a new second (or frame) of play has begun. */
  record(g: GameLike): void {
    const s = g.sim;
    if (g.generation !== this.generation) {
      [this.rows, this.generation, this.lastKey] = [[], g.generation, -1];
    }
    const frame = Math.floor(s.time);
    const key = this.everyFrame ? frame : Math.floor(frame / FPS);
    if (key === this.lastKey || this.rows.length >= ROWS_MAX) return;
    this.lastKey = key;
    const escaped = s.nAtoms - s.nTrapped;
    const row: Row = [
      frame,
      s.nTrapped,
      s.temperature,
      s.criticalTemperature,
      g.trapHeight,
      escaped,
      g.won ? 1 : 0,
    ];
    this.rows.push(row);
  }

  get count(): number {
    return this.rows.length;
  }

  /** The CSV text, with the settings and the game's replay code (null if it has none). */
  csv(settings: Record<string, unknown>, code: string | null): string {
    const meta: Record<string, unknown> = {
      source: "evapcool page: Save this run",
      parameters: settings,
      rows: this.everyFrame ? "every frame" : "every second",
      replay_code: code,
      columns_not_counted_by_the_page: LAB_COLUMNS.filter((c) => !COUNTED.has(c)),
    };
    const lines = [
      CSV_MAGIC,
      ...Object.entries(meta).map(([k, v]) => `# ${k}: ${JSON.stringify(v)}`),
    ];
    lines.push(LAB_COLUMNS.join(","));
    for (const [frame, n, temp, tc, h, escaped, won] of this.rows) {
      const cells: Record<string, string> = {
        frame: String(frame),
        n_trapped: String(n),
        temperature: num(temp),
        critical_temperature: num(tc),
        trap_height: num(h),
        escaped: String(escaped),
        won: String(won),
      };
      lines.push(LAB_COLUMNS.map((c) => cells[c] ?? "nan").join(","));
    }
    return lines.join("\n") + "\n";
  }
}

const COUNTED = new Set([
  "frame",
  "n_trapped",
  "temperature",
  "critical_temperature",
  "trap_height",
  "escaped",
  "won",
]);
/** A float as Python's repr reads it back (always with a point or an exponent). */
const num = (x: number): string =>
  Number.isFinite(x) ? (Number.isInteger(x) ? `${x}.0` : String(x)) : "nan";

/** The replay code of the game so far (its moves, settings and seed), or null. */
export async function codeSoFar(g: GameLike): Promise<string | null> {
  try {
    const runs = g instanceof RemoteGame ? await g.moves() : (g as Game).moves();
    const seed = g.config.seed;
    if (seed === null) return null;
    return await encode(recordingOf(g.config, seed, runs, g.won, g.score));
  } catch {
    return null; // settings a code cannot hold (beyond REPLAY_ATOMS): the rows still go
  }
}

/** Offer the text as a download named `name`. */
export function download(name: string, text: string): void {
  const url = URL.createObjectURL(new Blob([text], { type: "text/csv" }));
  const a = document.createElement("a");
  a.href = url;
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(url), 10_000);
}
