// Recordings and replay codes in the page (issue 22): the same code format as the desktop's
// evapcool.game.replay, checked by replaying with the game's own rules.
import fc from "fast-check";
import { describe, expect, test } from "vitest";
import { forceWin, makeSimulation } from "../../src/game/engine";
import {
  DAMAGED,
  EDITED,
  OTHER_VERSION,
  recordingOf,
  ReplayError,
  verify,
  WRONG_SCORE,
  type Recording,
} from "../../src/game/replay";
import { crc32Hex, decode, encode } from "../../src/game/replaycode";
import { framesOf } from "../../src/game/moves";
import { Game } from "../../src/game/rules";

/** A ramp that wins: 5 px lower every 25 frames down to 100 (as the page tests play). */
function wonGame(seed: number): Recording {
  const game = new Game(makeSimulation, { seed });
  game.paused = false;
  for (let f = 0; f < 6000 && !game.won; f++) {
    if (f % 25 === 0 && game.trapHeight > 100) game.nudgeHeight(-5);
    game.runFrames(1);
  }
  expect(game.won).toBe(true);
  return recordingOf(game.config, seed, game.moves(), game.won, game.score);
}

async function reason(code: string): Promise<string> {
  try {
    verify(await decode(code), makeSimulation);
    return "verified";
  } catch (err) {
    return err instanceof ReplayError ? err.reason : `other: ${(err as Error).message}`;
  }
}

describe("a game is its whole frames' heights", () => {
  test("played at any display step, its recording replays to the same win, score, frames", () => {
    fc.assert(
      fc.property(
        fc.constantFrom(1 / 60, 0.37 / 30, 1 / 30, 1.7 / 30),
        fc.integer({ min: 0, max: 1000 }),
        (dt, seed) => {
          const game = new Game(makeSimulation, { seed });
          game.paused = false;
          for (let k = 0; game.wonAt === null && game.sim.time < 3000; k++) {
            if (k % 40 === 0 && game.trapHeight > 100) game.nudgeHeight(-5);
            game.update(dt);
          }
          const rec = recordingOf(game.config, seed, game.moves(), game.won, game.score);
          const v = verify(rec, makeSimulation);
          return v.won === game.won && v.frames === framesOf(game.moves());
        },
      ),
      { numRuns: 8 },
    );
  });
});

describe("replay codes", () => {
  const rec = wonGame(11);

  test("CRC-32 is zlib's", () => {
    expect(crc32Hex("123456789")).toBe("cbf43926");
    expect(crc32Hex("")).toBe("00000000");
  });

  test("a won game's code decodes to its recording and replays to its score", async () => {
    const code = await encode(rec);
    expect(code).toMatch(/^EC1\.[A-Za-z0-9_-]+\.[0-9a-f]{8}$/);
    expect(code.length).toBeLessThan(2000);
    const back = await decode(code);
    expect(back).toEqual(rec);
    const v = verify(back, makeSimulation);
    expect(v).toEqual({ won: true, score: rec.score, frames: rec.frames });
    expect(rec.frames).toBe(rec.moves.reduce((s, [, n]) => s + n, 0));
  });

  test("a forged score, an edited field, another version are each named", async () => {
    expect(await reason(await encode({ ...rec, score: rec.score + 1 }))).toBe(WRONG_SCORE);
    expect(await reason(await encode({ ...rec, frames: rec.frames + 1 }))).toBe(EDITED);
    expect(await reason(await encode({ ...rec, version: "0.0.9" }))).toBe(OTHER_VERSION);
    const code = await encode(rec);
    expect(await reason(code.replace(/^EC1/, "EC2"))).toBe(OTHER_VERSION);
    expect(await reason(code.slice(0, -3))).toBe(DAMAGED);
    expect(await reason("hello")).toBe(DAMAGED);
  });

  test("any one changed character of a code is caught", async () => {
    const code = await encode(rec);
    const alphabet = "ABCabc019_-.xyz";
    await fc.assert(
      fc.asyncProperty(
        fc.integer({ min: 0, max: code.length - 1 }),
        fc.constantFrom(...alphabet),
        async (at, ch) => {
          fc.pre(code[at] !== ch);
          const bad = code.slice(0, at) + ch + code.slice(at + 1);
          return (await reason(bad)) !== "verified";
        },
      ),
      { numRuns: 60 },
    );
  });
});

test("the win is seen at its frame's end, before a height asked in that frame applies", () => {
  // The replay's order (core/game.c): a knife cut made by that height cannot change the score.
  const games = [0, 1].map(() => new Game(makeSimulation, { seed: 3, escape: "knife" }));
  for (const game of games) {
    game.paused = false;
    game.update(0.5 / 30);
  }
  const [cut, kept] = games;
  expect(cut.setTrapHeight(25)).toBe(true); // held for the next frame: the knife cuts at t = 1
  for (const game of games) {
    forceWin(game.sim); // the gas condenses within this frame
    game.update(0.5 / 30);
  }
  expect(cut.wonAt).toBe(1 / 30);
  expect(kept.wonAt).toBe(1 / 30);
  expect(cut.sim.nTrapped).toBeLessThan(kept.sim.nTrapped);
  expect(cut.score).toBe(kept.sim.nTrapped);
  expect(kept.score).toBe(kept.sim.nTrapped);
});
