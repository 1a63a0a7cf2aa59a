/**
 * Key-value storage (the page's localStorage, or a Map in tests) that never throws:
 * a browser with storage switched off, full or forbidden gives notices, not a crash.
 * A stored value that cannot be used is set aside under another key, never deleted.
 */
import { t } from "../i18n";

/** The part of the Web Storage API we use (localStorage fits it). */
export interface KeyValue {
  getItem(key: string): string | null;
  setItem(key: string, value: string): void;
  removeItem(key: string): void;
}

export const PREFIX = "evapcool.";

/** A KeyValue in memory: for tests, and the fallback when localStorage is unusable. */
export class MemoryStore implements KeyValue {
  readonly map = new Map<string, string>();
  getItem(key: string): string | null {
    return this.map.get(key) ?? null;
  }
  setItem(key: string, value: string): void {
    this.map.set(key, value);
  }
  removeItem(key: string): void {
    this.map.delete(key);
  }
}

/** "YYYY-MM-DD HH:MM:SS" in local time (the desktop's DATE_FORMAT). */
export function formatDate(d: Date): string {
  const p = (v: number) => String(v).padStart(2, "0");
  return (
    `${d.getFullYear()}-${p(d.getMonth() + 1)}-${p(d.getDate())} ` +
    `${p(d.getHours())}:${p(d.getMinutes())}:${p(d.getSeconds())}`
  );
}

/** Read a key; null if absent or unreadable (a notice says why in the second case). */
export function readKey(kv: KeyValue, key: string, notices: string[]): string | null {
  try {
    return kv.getItem(key);
  } catch (err) {
    notices.push(t("page.storage_unreadable", { problem: reason(err) }));
    return null;
  }
}

/** Write a key; false (and a notice naming what) if the browser refuses. */
export function writeKey(
  kv: KeyValue,
  key: string,
  value: string,
  what: "scores" | "settings",
  notices: string[],
): boolean {
  try {
    kv.setItem(key, value);
    return true;
  } catch (err) {
    notices.push(t("page.cannot_save", { what, problem: reason(err) }));
    return false;
  }
}

/**
 * Move a bad value to `<key>.corrupt-<date>` (a numbered suffix if that exists) and
 * remove it from `key`; returns the new key, or null if the browser refused.
 */
export function setAside(
  kv: KeyValue,
  key: string,
  value: string,
  now = new Date(),
): string | null {
  const stamp = formatDate(now).replace(" ", "T").replace(/:/g, "-");
  let target = `${key}.corrupt-${stamp}`;
  try {
    for (let k = 2; kv.getItem(target) !== null; k++) target = `${key}.corrupt-${stamp}-${k}`;
    kv.setItem(target, value);
    kv.removeItem(key);
    return target;
  } catch {
    return null;
  }
}

export function reason(err: unknown): string {
  if (err instanceof Error) return err.name === "Error" ? err.message : err.name;
  return String(err);
}
