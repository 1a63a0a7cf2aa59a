import { describe, expect, it } from "vitest";
import { studentRows } from "../src/classroom/students";
import type { LecturerEntry } from "../src/classroom/board";

function entry(entry: number, name: string, score: number, rank: number | null): LecturerEntry {
  return { entry, name, score, frames: 100 * entry, edition: "web", hidden: false, rank };
}

describe("studentRows", () => {
  it("keeps each student's first (best) entry and counts their games", () => {
    const rows = studentRows([
      entry(3, "Mia", 30, 1),
      entry(1, "Finn", 25, 2),
      entry(2, "Mia", 20, null),
      entry(4, "Mia", 10, null),
    ]);
    expect(rows.map((r) => [r.best.name, r.best.entry, r.attempts])).toEqual([
      ["Mia", 3, 3],
      ["Finn", 1, 1],
    ]);
  });

  it("is empty for no entries", () => {
    expect(studentRows([])).toEqual([]);
  });
});
