// The class pages' text and rows (web/src/classroom/board.ts, common.ts): what the projector
// and the lecturer's page say of a challenge and its leaderboard, without a browser.
import { describe, expect, it } from "vitest";
import {
  BOARD_COLUMNS,
  ChallengeClock,
  boardCells,
  boardRows,
  clock,
  entryCells,
  entryClass,
  rejectedText,
  replayHeading,
  settingsText,
  stateText,
  type Board,
  type BoardEntry,
  type ChallengeInfo,
  type LecturerEntry,
} from "../../src/classroom/board";
import { fill, refusalText } from "../../src/classroom/common";

/** Words as the server's catalog gives them (the English catalog's shapes). */
const WORDS = {
  rank: "Rank",
  name: "Name",
  score: "Score",
  frames: "Frames",
  waiting: "Waiting for a challenge",
  settings: "{n} atoms, radius {radius}, {escape}, seed {seed}",
  rim: "over the rim",
  tc_law: "Tc law",
  per_student: "{n} per student",
  open: "Open",
  closes_in: "closes in {time}",
  final: "Final results",
  refused: "Refused",
  replay: "Replay",
  summary: "{frames} frames, {runs} moves, {first} to {last}",
};

function challenge(over: Partial<ChallengeInfo> = {}): ChallengeInfo {
  return {
    id: 3,
    seed: 42,
    settings: { n_atoms: 49, radius: 12, escape: "rim", tc_exponent: 2 / 3 },
    attempts: null,
    open: true,
    closes_in: null,
    ...over,
  };
}

function entry(rank: number): BoardEntry {
  return { rank, name: `P${rank}`, score: 50 - rank, frames: 900 + rank, edition: "web" };
}

describe("fill", () => {
  it("fills the placeholders it has and leaves the others as written", () => {
    expect(fill("{a} and {b}", { a: 1 })).toBe("1 and {b}");
    expect(fill("{a}{a}", { a: "<b>" })).toBe("<b><b>");
  });
});

describe("settingsText", () => {
  it("names the settings, the escape in words and the law as a fraction", () => {
    expect(settingsText(WORDS, challenge())).toBe(
      "49 atoms, radius 12, over the rim, seed 42 · Tc law 2/3",
    );
  });

  it("shows another law's exponent, an unknown escape as sent, and the attempts", () => {
    const c = challenge({ attempts: 3 });
    c.settings = { ...c.settings, escape: "knife", tc_exponent: 0.75 };
    expect(settingsText(WORDS, c)).toBe(
      "49 atoms, radius 12, knife, seed 42 · Tc law 0.750 · 3 per student",
    );
    c.settings.tc_exponent = 0.4;
    expect(settingsText(WORDS, c)).toContain("Tc law 2/5");
  });
});

describe("clock and state", () => {
  it("says seconds as m:ss, rounded up, never negative", () => {
    expect([clock(0), clock(0.2), clock(59.5), clock(61), clock(-5)]).toEqual([
      "0:00",
      "0:01",
      "1:00",
      "1:01",
      "0:00",
    ]);
  });

  it("waits without a challenge, counts an open one down, is final when it ends", () => {
    expect(stateText(WORDS, null, 0)).toEqual(["", "Waiting for a challenge"]);
    expect(stateText(WORDS, challenge(), 99)).toEqual(["open", "Open"]);
    const timed = challenge({ closes_in: 90 });
    expect(stateText(WORDS, timed, 20)).toEqual(["open", "Open · closes in 1:10"]);
    expect(stateText(WORDS, timed, 90)).toEqual(["closed", "Final results"]);
    expect(stateText(WORDS, challenge({ open: false }), 0)).toEqual(["closed", "Final results"]);
  });

  it("counts from when the server's answer came, not from the clocks' difference", () => {
    const c = new ChallengeClock();
    expect(c.state(WORDS, 5000)[0]).toBe("");
    c.take(challenge({ closes_in: 10 }), 1_000_000);
    expect(c.state(WORDS, 1_004_000)).toEqual(["open", "Open · closes in 0:06"]);
    expect(c.state(WORDS, 1_010_000)[0]).toBe("closed");
  });
});

describe("the projector's board", () => {
  const entries = [1, 2, 3, 4, 5, 6, 7].map(entry);
  const board: Board = { open: true, info: challenge(), entries, rejected: 2, replay: null };
  const summary = { frames: 901, runs: 4, score: 49, first: "12", last: "3" };

  it("shows every row, or the top five while a replay with its code plays", () => {
    expect(boardRows(board)).toHaveLength(7);
    const codeless = { ...board, replay: { entry: 1, name: "P1", summary } };
    expect(boardRows(codeless)).toHaveLength(7);
    const playing = { ...board, replay: { entry: 1, name: "P1", code: "X", summary } };
    expect(boardRows(playing).map((e) => e.rank)).toEqual([1, 2, 3, 4, 5]);
  });

  it("puts a row's cells in the columns' order, names as given", () => {
    expect(BOARD_COLUMNS).toEqual(["rank", "name", "score", "frames"]);
    const hostile = { ...entry(1), name: "<img src=x onerror=alert(1)>" };
    expect(boardCells(hostile)).toEqual([1, "<img src=x onerror=alert(1)>", 49, 901]);
  });

  it("names no one in the debrief's anonymous mode (issue 36)", () => {
    const words = { ...WORDS, "debrief.anonymous_name": "Student {n}" };
    expect(boardCells({ ...entry(3), name: null }, words)).toEqual([3, "Student 3", 47, 903]);
    const anonymous = { entry: 1, name: null, summary };
    expect(replayHeading(words, anonymous, 2)).toBe(
      "Replay: Student 2 · 901 frames, 4 moves, 12 to 3",
    );
  });

  it("says the refused count and the replay's heading", () => {
    expect(rejectedText(WORDS, 2)).toBe("Refused: 2");
    expect(replayHeading(WORDS, { entry: 1, name: "Ada", summary })).toBe(
      "Replay: Ada · 901 frames, 4 moves, 12 to 3",
    );
  });
});

describe("the lecturer's entries", () => {
  const shown: LecturerEntry = { ...entry(2), name: "P2", entry: 8, hidden: false };
  const hidden: LecturerEntry = { ...entry(1), name: "P1", rank: null, entry: 9, hidden: true };

  it("gives a hidden entry no rank", () => {
    expect(entryCells(shown)).toEqual([2, "P2", 48, 902, "web"]);
    expect(entryCells(hidden)).toEqual(["", "P1", 49, 901, "web"]);
  });

  it("marks rows hidden and the one on the projector", () => {
    expect(entryClass(shown, 8)).toBe("showing");
    expect(entryClass(shown, null)).toBe("");
    expect(entryClass(hidden, 9)).toBe("hidden showing");
    expect(entryClass(hidden, undefined)).toBe("hidden");
  });

  it("says a refusal as its field and message", () => {
    const doc = { error: { field: "minutes", message: "must be at least 0.1" } };
    expect(refusalText(doc)).toBe("minutes: must be at least 0.1");
  });
});
