/**
 * Replay codes (twin of evapcool/game/replay.py's encode/decode): `EC1.<payload>.<crc>`,
 * payload = URL-safe base64 (no padding) of zlib(compact JSON), crc = CRC-32 of the payload
 * text in 8 hex digits, so a damaged code is told apart from an edited one or another
 * version's. zlib through the browser's CompressionStream("deflate").
 */
import { shown } from "../limits";
import { START_GENERATOR } from "./engine";
import {
  checkRecording,
  CODE_PREFIX,
  DAMAGED,
  EDITED,
  EDITION_VERSION,
  FORMAT_VERSION,
  MAX_CODE_CHARS,
  MAX_JSON_BYTES,
  OTHER_VERSION,
  ReplayError,
  type Recording,
} from "./replay";

const CRC_TABLE = (() => {
  const table = new Uint32Array(256);
  for (let n = 0; n < 256; n++) {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    table[n] = c >>> 0;
  }
  return table;
})();

/** CRC-32 (zlib's) of an ASCII text, 8 hex digits. */
export function crc32Hex(text: string): string {
  let c = 0xffffffff;
  for (let i = 0; i < text.length; i++) c = CRC_TABLE[(c ^ text.charCodeAt(i)) & 0xff] ^ (c >>> 8);
  return ((c ^ 0xffffffff) >>> 0).toString(16).padStart(8, "0");
}

async function through(bytes: Uint8Array, stream: GenericTransformStream): Promise<Uint8Array> {
  const out = new Blob([bytes as BlobPart]).stream().pipeThrough(stream);
  return new Uint8Array(await new Response(out).arrayBuffer());
}

/** Compressed bytes fed at a time: deflate unpacks at most ~1 000 x, so each piece unpacks
 * to a megabyte at most before the count below can stop it. */
const INFLATE_PIECE = 1024;

/** zlib's inflate of bytes, refused (DAMAGED) as soon as it passes limit bytes. */
export async function inflateAtMost(
  bytes: Uint8Array<ArrayBuffer>,
  limit: number,
): Promise<Uint8Array> {
  const stream = new DecompressionStream("deflate");
  const writer = stream.writable.getWriter();
  const reader = stream.readable.getReader();
  const feed = (async () => {
    for (let at = 0; at < bytes.length; at += INFLATE_PIECE) {
      await writer.ready;
      void writer.write(bytes.subarray(at, at + INFLATE_PIECE)).catch(() => {});
    }
    await writer.close();
  })();
  feed.catch(() => {}); // a broken stream is reported by the reader
  const chunks: Uint8Array[] = [];
  let size = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    size += value.length;
    if (size > limit) {
      await reader.cancel().catch(() => {});
      await writer.abort().catch(() => {});
      throw new ReplayError(DAMAGED, `unpacks to more than ${limit} bytes`);
    }
    chunks.push(value);
  }
  await feed;
  const out = new Uint8Array(size);
  let at = 0;
  for (const c of chunks) {
    out.set(c, at);
    at += c.length;
  }
  return out;
}

function toBase64Url(bytes: Uint8Array): string {
  let bin = "";
  for (const b of bytes) bin += String.fromCharCode(b);
  return btoa(bin).replace(/\+/g, "-").replace(/\//g, "_").replace(/=+$/, "");
}

function fromBase64Url(text: string): Uint8Array<ArrayBuffer> {
  if (!/^[A-Za-z0-9_-]*$/.test(text)) throw new Error("not URL-safe base64");
  const b64 = text.replace(/-/g, "+").replace(/_/g, "/");
  const bin = atob(b64 + "=".repeat((4 - (b64.length % 4)) % 4));
  return Uint8Array.from(bin, (ch) => ch.charCodeAt(0));
}

/** The replay code of a recording. */
export async function encode(rec: Recording): Promise<string> {
  const text = JSON.stringify(rec);
  const packed = await through(new TextEncoder().encode(text), new CompressionStream("deflate"));
  const payload = toBase64Url(packed);
  return `${CODE_PREFIX}.${payload}.${crc32Hex(payload)}`;
}

/** The recording of a replay code; ReplayError with the reason it is not a valid one. */
export async function decode(raw: string): Promise<Recording> {
  const code = raw.trim();
  if (code.length > MAX_CODE_CHARS)
    throw new ReplayError(DAMAGED, `longer than ${MAX_CODE_CHARS} characters`);
  const parts = code.split(".");
  if (parts.length !== 3)
    throw new ReplayError(DAMAGED, "not of the form EC1.<payload>.<checksum>");
  const [prefix, payload, crc] = parts;
  if (prefix !== CODE_PREFIX) {
    if (/^EC\d+$/.test(prefix)) throw new ReplayError(OTHER_VERSION, `code version ${prefix}`);
    throw new ReplayError(DAMAGED, "does not start with EC1.");
  }
  if (crc !== crc32Hex(payload)) throw new ReplayError(DAMAGED, "checksum does not match");
  let doc: unknown;
  try {
    const bytes = await inflateAtMost(fromBase64Url(payload), MAX_JSON_BYTES);
    doc = JSON.parse(new TextDecoder("utf-8", { fatal: true }).decode(bytes));
  } catch (err) {
    if (err instanceof ReplayError) throw err;
    throw new ReplayError(DAMAGED, `cannot unpack (${shortMessage(err)})`);
  }
  return fromJson(doc);
}

/** An error's message as a refusal quotes it: its first 80 characters. */
function shortMessage(err: unknown): string {
  const text = err instanceof Error ? err.message : String(err);
  return text.length > 80 ? `${text.slice(0, 79)}…` : text;
}

const isNum = (x: unknown): x is number => typeof x === "number" && Number.isFinite(x);
const isInt = (x: unknown): x is number => isNum(x) && Number.isInteger(x);

/** A recording from its JSON document; ReplayError (edited / other version) if not one. */
export function fromJson(doc: unknown): Recording {
  if (typeof doc !== "object" || doc === null || Array.isArray(doc))
    throw new ReplayError(EDITED, "not a recording object");
  const d = doc as Record<string, unknown>;
  // Each value quoted shortened: a refusal is a line, whatever the code holds.
  if (d.format !== FORMAT_VERSION)
    throw new ReplayError(OTHER_VERSION, `format ${shown(d.format)}`);
  if (d.start_generator !== START_GENERATOR)
    throw new ReplayError(OTHER_VERSION, `start generator ${shown(d.start_generator)}`);
  if (d.version !== EDITION_VERSION)
    throw new ReplayError(OTHER_VERSION, `edition version ${shown(d.version)}`);
  const s = (d.settings ?? {}) as Record<string, unknown>;
  const moves = Array.isArray(d.moves) ? d.moves : null;
  const fields =
    isInt(s.n_atoms) && isNum(s.radius) && isNum(s.tc_exponent) && typeof s.escape === "string";
  const runsOk = moves?.every(
    (m) => Array.isArray(m) && m.length === 2 && isNum(m[0]) && isInt(m[1]),
  );
  if (!fields || !runsOk || !isInt(d.seed) || !isInt(d.score) || !isInt(d.frames))
    throw new ReplayError(EDITED, "bad field");
  if (typeof d.won !== "boolean" || (d.edition !== "desktop" && d.edition !== "web"))
    throw new ReplayError(EDITED, "bad field (won, edition)");
  const rec: Recording = {
    settings: {
      n_atoms: s.n_atoms as number,
      radius: s.radius as number,
      escape: s.escape as Recording["settings"]["escape"],
      tc_exponent: s.tc_exponent as number,
    },
    seed: d.seed,
    moves: (moves as Array<[number, number]>).map(([h, n]) => [h, n]),
    won: d.won,
    score: d.score,
    frames: d.frames,
    edition: d.edition,
    version: d.version,
    start_generator: START_GENERATOR,
    format: FORMAT_VERSION,
  };
  checkRecording(rec);
  return rec;
}
