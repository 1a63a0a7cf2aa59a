/**
 * The lecturer's ranked table: one row per student from the server's list of every entry
 * (best first), with how many games they sent and their best one.
 */
import type { LecturerEntry } from "./board";

/** A student's row: their best entry (its rank, atoms, frames) and their attempts. */
export interface StudentRow {
  best: LecturerEntry;
  attempts: number;
}

/** One row per student (by name: no two students of a class share one), in the order of
 * their best entries; the server sends entries best first, so the first seen is the best. */
export function studentRows(entries: readonly LecturerEntry[]): StudentRow[] {
  const rows = new Map<string, StudentRow>();
  for (const e of entries) {
    const had = rows.get(e.name);
    if (had) had.attempts += 1;
    else rows.set(e.name, { best: e, attempts: 1 });
  }
  return [...rows.values()];
}
