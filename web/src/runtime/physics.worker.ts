/**
 * The physics worker: the game's rules (game/rules.ts) over the page's engine, advanced by
 * the wall time between the page's display frames, its state and atoms posted back in
 * frame buffers (worker-protocol.ts). Commands are applied in the order the page sent
 * them, between advances, exactly as the page's own loop applies input between frames.
 * A worker of the same code replays the verify panel's codes (off the page's thread).
 */
import { forceWin, makeSimulation, provideCore, replayGolden } from "../game/engine";
import { Game, LOSE_REASONS, MAX_WALL_STEP, type GameConfig } from "../game/rules";
import {
  bufferBytes,
  bufferCapacity,
  copyAtoms,
  frameViews,
  HEADER,
  type Command,
  type FromWorker,
  type ToWorker,
} from "./worker-protocol";
import { replayed, type Decoded } from "./verify-check";

/** Buffers going round: one drawn, one arriving, one being filled. */
const BUFFERS = 3;
/** One advance covers at most this many display frames of wall time (then the game slows). */
const FRAMES_PER_ADVANCE = 1.5;

interface WorkerScope {
  postMessage(message: FromWorker, transfer?: Transferable[]): void;
  onmessage: ((ev: MessageEvent<ToWorker>) => void) | null;
}
const scope = self as unknown as WorkerScope;

let game: Game | null = null;
let free: ArrayBuffer[] = [];
let capacity = 0;
let seq = 0;
let physicsMs = 0;
/** State changed since the last frame posted. */
let changed = false;
/** A display frame began since the last advance. */
let vsync = false;
let frameSeconds = 1 / 60;
let lastAdvance: number | null = null;
const tick = new MessageChannel();
let tickQueued = false;

function post(message: FromWorker, transfer: Transferable[] = []): void {
  scope.postMessage(message, transfer);
}

/** Buffers with room for n atoms in each group (new ones only when the atoms outgrow them). */
function makeRoom(n: number): void {
  if (n <= capacity) return;
  capacity = n;
  free = Array.from({ length: BUFFERS }, () => new ArrayBuffer(bufferBytes(n)));
}

function apply(command: Command): void {
  const g = game!;
  switch (command.kind) {
    case "paused":
      g.paused = command.paused;
      break;
    case "height":
      g.holdHeight(command.height);
      break;
    case "speed":
      g.speed = command.speed;
      break;
    case "step":
      g.step();
      break;
    case "frames": {
      const t0 = performance.now();
      g.runFrames(command.n);
      physicsMs = performance.now() - t0;
      break;
    }
    case "restart":
      makeRoom(command.config.nAtoms);
      g.restart(command.config);
      break;
    case "forceWin":
      forceWin(g.sim);
      break;
  }
}

/** Fill a free buffer with the game's state and post it (or wait for one to come back). */
function publish(): void {
  const buffer = free.pop();
  if (!buffer) return;
  const g = game!;
  const sim = g.sim;
  const v = frameViews(buffer);
  const h = v.header;
  copyAtoms(sim.trapped(), v.trapped);
  copyAtoms(sim.escaped(), v.escaped);
  h[HEADER.seq] = seq;
  h[HEADER.generation] = g.generation;
  h[HEADER.time] = sim.time;
  h[HEADER.nAtoms] = sim.nAtoms;
  h[HEADER.nTrapped] = sim.nTrapped;
  h[HEADER.nEscaped] = v.escaped.count; // counted by the copy above, not again
  h[HEADER.trapHeight] = sim.trapHeight;
  h[HEADER.rimHalfWidth] = sim.rimHalfWidth;
  h[HEADER.curvature] = sim.curvature;
  h[HEADER.gravity] = sim.gravity;
  h[HEADER.temperature] = sim.temperature;
  h[HEADER.initialTemperature] = sim.initialTemperature;
  h[HEADER.criticalTemperature] = sim.criticalTemperature;
  h[HEADER.tcExponent] = sim.tcExponent;
  h[HEADER.won] = sim.won ? 1 : 0;
  h[HEADER.winRule] = sim.winRule ? 1 : 0;
  h[HEADER.collisionCount] = sim.collisionCount;
  h[HEADER.originLift] = sim.originLift;
  h[HEADER.roomLeft] = sim.room.left;
  h[HEADER.roomRight] = sim.room.right;
  h[HEADER.roomBelow] = sim.room.below;
  h[HEADER.roomAbove] = sim.room.above;
  h[HEADER.wonAt] = g.wonAt ?? NaN;
  h[HEADER.trappedCount] = v.trapped.count;
  h[HEADER.escapedCount] = v.escaped.count;
  h[HEADER.capacity] = capacity;
  h[HEADER.physicsMs] = physicsMs;
  // The game's answers, here only: the page reads them (runtime/remote.ts). The score is
  // the one the core fixed at the win's frame (atoms may still leave after it).
  h[HEADER.score] = g.score ?? NaN;
  h[HEADER.allEscaped] = g.allEscaped ? 1 : 0;
  h[HEADER.tooFew] = LOSE_REASONS.indexOf(g.tooFewAtoms());
  changed = false;
  post({ type: "frame", buffer }, [buffer]);
}

/** Advance by the wall time since the last advance (at most FRAMES_PER_ADVANCE frames of it). */
function advance(): void {
  const g = game!;
  const now = performance.now();
  const wall = lastAdvance === null ? 0 : (now - lastAdvance) / 1000;
  lastAdvance = now;
  if (g.paused) return;
  const t0 = performance.now();
  const before = g.sim.time;
  g.update(Math.min(wall, FRAMES_PER_ADVANCE * frameSeconds, MAX_WALL_STEP));
  physicsMs = performance.now() - t0;
  if (g.sim.time !== before) changed = true;
}

/** Run once the messages queued so far are handled: advance if a display frame began. */
function queueTick(): void {
  if (tickQueued) return;
  tickQueued = true;
  tick.port2.postMessage(null);
}

tick.port1.onmessage = () => {
  tickQueued = false;
  if (!game) return;
  if (vsync) {
    vsync = false;
    advance();
  }
  if (changed) publish();
};

function start(config: GameConfig): void {
  makeRoom(config.nAtoms);
  game = new Game(makeSimulation, config);
  changed = true;
  publish();
}

function receive(msg: ToWorker): void {
  switch (msg.type) {
    case "start":
      if (msg.core.length) provideCore(msg.core);
      start(msg.config);
      break;
    case "command":
      apply(msg.command);
      seq = msg.seq;
      changed = true;
      queueTick();
      break;
    case "give":
      if (bufferCapacity(msg.buffer) >= capacity) free.push(msg.buffer);
      queueTick();
      break;
    case "vsync":
      frameSeconds = msg.frameSeconds;
      if (msg.buffer && bufferCapacity(msg.buffer) >= capacity) free.push(msg.buffer);
      vsync = true;
      queueTick();
      break;
    case "replay":
      post({ type: "replayed", id: msg.id, text: replayGolden(msg.text) });
      break;
    case "moves":
      post({ type: "moves", id: msg.id, runs: game ? game.moves() : [] });
      break;
    case "verify":
      if (msg.core.length) provideCore(msg.core);
      verifyCodes(msg.codes);
      break;
  }
}

/** Each code's outcome as it comes (the page terminates this worker to stop). */
function verifyCodes(codes: Decoded[]): void {
  codes.forEach((item, index) => post({ type: "verified", index, checked: replayed(item) }));
}

scope.onmessage = (ev) => {
  try {
    receive(ev.data);
  } catch (err) {
    post({ type: "failed", message: `${(err as Error).name}: ${(err as Error).message}` });
  }
};

post({ type: "hello" });
