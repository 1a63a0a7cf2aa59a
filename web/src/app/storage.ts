/**
 * Where the page keeps scores and settings: the browser's localStorage, or memory.
 * Python's twin: `src/evapcool/app/storage.py` (docs/twins.md).
 */
import { t } from "../i18n";
import { MemoryStore, reason, type KeyValue } from "../game/store";

const NO_STORAGE = (problem: string) => t("page.no_storage", { problem });

/** localStorage if it works here, else a store for this visit only (with a notice why). */
export function pageStorage(notices: string[]): KeyValue {
  try {
    const ls = window.localStorage;
    const probe = "evapcool.probe";
    ls.setItem(probe, "1");
    ls.removeItem(probe);
    return ls;
  } catch (err) {
    notices.push(NO_STORAGE(reason(err)));
    return new MemoryStore();
  }
}

/** Storage seen through a read-only window (loading twice must not set aside twice). */
export class ReadOnly implements KeyValue {
  constructor(private readonly kv: KeyValue) {}
  getItem(key: string): string | null {
    return this.kv.getItem(key);
  }
  setItem(): void {
    throw new Error("read only");
  }
  removeItem(): void {
    throw new Error("read only");
  }
}
