/**
 * Recordings of games, replay codes and verification by replay (twin of
 * evapcool/game/replay.py, issue 22): a game is its settings, seed and the trap height held
 * in each whole physics frame; a replay code is that recording as
 * `EC1.<base64url(zlib(json))>.<crc32 hex>`, read and written by both editions.
 */
import { version } from "../../package.json";
import { SEED_PORTABLE_MAX, START_GENERATOR, type EscapeRule } from "./engine";
import {
  Game,
  HEIGHT_MAX,
  HEIGHT_MIN,
  clampHeight,
  type GameConfig,
  type SimFactory,
} from "./rules";
import type { GameSim } from "./sim";
import { framesOf } from "./moves";
import { REPLAY_ATOMS, REPLAY_FRAMES_MAX, REPLAY_RADIUS } from "../limits";

export const CODE_PREFIX = "EC1";
export const FORMAT_VERSION = 1;
export const EDITION_VERSION: string = version;
/** Longest game a recording may hold (frames): 20 minutes of play at 30 frames/s. */
export const MAX_FRAMES = REPLAY_FRAMES_MAX;
export const MAX_CODE_CHARS = 200_000;
/** The longest a run [height,frames], comma, can be written: a height as JSON writes a float
 * (at most 24 characters, "1.2345678901234567e-100"), frames of at most 5 digits. */
const RUN_CHARS = 32;
/** The longest recording's JSON: one run per frame of the longest game, and its other fields.
 * A code unpacking to more is refused as it unpacks, before it is all in memory. */
export const MAX_JSON_BYTES = MAX_FRAMES * RUN_CHARS + 4096;

/** Why a code or recording is rejected (the reasons both editions give). */
export const DAMAGED = "damaged";
export const EDITED = "edited";
export const OTHER_VERSION = "other version";
export const WRONG_SCORE = "does not replay to the claimed score";

export class ReplayError extends RangeError {
  constructor(
    readonly reason: string,
    readonly detail: string,
  ) {
    super(`${reason}: ${detail}`);
  }
}

/** The settings a recording was played with (the JSON names of the Python edition). */
export interface ReplaySettings {
  n_atoms: number;
  radius: number;
  escape: EscapeRule;
  tc_exponent: number;
}

export interface Recording {
  settings: ReplaySettings;
  seed: number;
  /** [height, frames] runs: the height held during that many whole frames. */
  moves: Array<[number, number]>;
  won: boolean;
  score: number;
  frames: number;
  edition: "desktop" | "web";
  version: string;
  start_generator: number;
  format: number;
}

export function settingsOf(config: GameConfig): ReplaySettings {
  return {
    n_atoms: config.nAtoms,
    radius: config.radius,
    escape: config.escape,
    tc_exponent: config.tcExponent,
  };
}

export function configOf(s: ReplaySettings, seed: number): Partial<GameConfig> {
  return { nAtoms: s.n_atoms, radius: s.radius, escape: s.escape, tcExponent: s.tc_exponent, seed };
}

/** The recording of a game played in the page. */
export function recordingOf(
  config: GameConfig,
  seed: number,
  runs: Array<[number, number]>,
  won: boolean,
  score: number | null,
): Recording {
  const moves = runs.map(([h, n]) => [h, n] as [number, number]);
  return {
    settings: settingsOf(config),
    seed,
    moves,
    won,
    score: won ? (score ?? 0) : 0,
    frames: framesOf(moves),
    edition: "web",
    version: EDITION_VERSION,
    start_generator: START_GENERATOR,
    format: FORMAT_VERSION,
  };
}

/** What a replay gave: won, score (atoms at the win, else 0), frames played. */
export interface Verdict {
  won: boolean;
  score: number;
  frames: number;
}

/** Play the recording headless with the game's rules: hold each frame's height for one whole
 * frame; stop at the win or at the end of the moves (the core's replay, core/game.c). */
export function replay(rec: Recording, factory: SimFactory): Verdict {
  const sim = startOf(rec, factory);
  // The slider's clamp, as Game.setTrapHeight applies it.
  const runs = rec.moves.map(([h, n]) => [clampHeight(h), n] as const);
  const frames = sim.replay(runs, Math.min(framesOf(rec.moves), 2 ** 31 - 1));
  const score = sim.score;
  return { won: score !== null, score: score ?? 0, frames };
}

/** The start of a recording's game, as a (re)start of the game makes it (trap at 400). */
export function startOf(rec: Recording, factory: SimFactory): GameSim {
  return new Game(factory, configOf(rec.settings, rec.seed)).sim;
}

/** The replayed result if it is the one claimed, else ReplayError(WRONG_SCORE). */
export function verify(rec: Recording, factory: SimFactory): Verdict {
  checkRecording(rec);
  return checkClaim(rec, replay(rec, factory));
}

/** The replayed result if it is the one the recording claims, else ReplayError(WRONG_SCORE). */
export function checkClaim(rec: Recording, got: Verdict): Verdict {
  if (got.won !== rec.won || got.score !== rec.score || got.frames !== rec.frames)
    throw new ReplayError(
      WRONG_SCORE,
      `claimed won=${rec.won} score=${rec.score} frames=${rec.frames}, ` +
        `replayed won=${got.won} score=${got.score} frames=${got.frames}`,
    );
  return got;
}

/** ReplayError(EDITED) naming the first field out of its limits or inconsistent. */
export function checkRecording(rec: Recording, maxFrames = MAX_FRAMES): void {
  const s = rec.settings;
  const total = framesOf(rec.moves);
  const problems: Array<[boolean, string]> = [
    [
      !(s.n_atoms >= REPLAY_ATOMS.low && s.n_atoms <= REPLAY_ATOMS.high),
      `settings.n_atoms must be ${REPLAY_ATOMS.low}..${REPLAY_ATOMS.high}`,
    ],
    [
      !(s.radius >= REPLAY_RADIUS.low && s.radius <= REPLAY_RADIUS.high),
      `settings.radius must be ${REPLAY_RADIUS.low}..${REPLAY_RADIUS.high}`,
    ],
    [s.escape !== "rim" && s.escape !== "knife", "settings.escape must be rim or knife"],
    [!(s.tc_exponent > 0 && s.tc_exponent <= 2), "settings.tc_exponent must be in (0, 2]"],
    [!(rec.seed >= 0 && rec.seed <= SEED_PORTABLE_MAX), "seed must be 0..2^53-1"],
    [rec.edition !== "desktop" && rec.edition !== "web", "edition must be desktop or web"],
    [rec.moves.some(([, n]) => n < 1), "moves: each run needs frames >= 1"],
    [
      rec.moves.some(([h]) => !(h >= HEIGHT_MIN && h <= HEIGHT_MAX)),
      `moves: heights must be ${HEIGHT_MIN}..${HEIGHT_MAX}`,
    ],
    [total > maxFrames, `moves: at most ${maxFrames} frames`],
    [rec.frames !== total, "frames must equal the moves' frames"],
    [!(rec.score >= 0 && rec.score <= s.n_atoms), "score must be 0..n_atoms"],
    [!rec.won && rec.score !== 0, "score must be 0 without a win"],
  ];
  for (const [bad, message] of problems) if (bad) throw new ReplayError(EDITED, message);
}
