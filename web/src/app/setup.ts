/**
 * A teacher's setup from the address (issue 48): the trap's start height, controls shown but
 * locked, buttons left out, the theme and the sound; and the link to what is on screen
 * ("Copy link to this setup": the same setup when opened again). The option names are
 * link-options.json's.
 */
import { type ThemeName } from "../view/colors";
import type { ControlName } from "../view/geometry";
import type { FieldName, Settings } from "../game/settings";
import { activeTranslator, t } from "../i18n";
import type { PageParams } from "./params";
import { copyBySelection } from "./replays";

/** What a link may lock, and the settings row each locks (speed and trap: no row). */
export const LOCK_FIELDS: Readonly<Record<string, FieldName | null>> = {
  atoms: "n_atoms",
  radius: "radius",
  escape: "escape",
  "tc-law": "tc_law",
  speed: null,
  trap: null,
};
const SETTING_OF: Record<FieldName, keyof Settings> = {
  n_atoms: "nAtoms",
  radius: "radius",
  tc_law: "tcLaw",
  escape: "escape",
};

export type SetupParams = Pick<PageParams, "trap" | "lock" | "hide" | "theme" | "sound">;

export const NO_SETUP: SetupParams = { trap: null, lock: [], hide: [], theme: null, sound: null };

/** What the link's reader may not change, and what they do not see. */
export class Setup {
  readonly locked: ReadonlySet<string>;
  readonly hidden: ReadonlySet<string>;
  constructor(readonly params: SetupParams) {
    this.locked = new Set(params.lock);
    this.hidden = new Set(params.hide);
  }

  /** The settings row `field` is locked. */
  fieldLocked(field: FieldName): boolean {
    return [...this.locked].some((name) => LOCK_FIELDS[name] === field);
  }

  /** The settings a lock freezes, as this visit's overrides (what the address or saved gave). */
  frozen(run: Settings): Partial<Settings> {
    const out: Partial<Settings> = {};
    for (const name of this.locked) {
      const field = LOCK_FIELDS[name];
      if (field) Object.assign(out, { [SETTING_OF[field]]: run[SETTING_OF[field]] });
    }
    return out;
  }

  isHidden(name: ControlName): boolean {
    return this.hidden.has(name);
  }
}

/** The state on screen a link writes. */
export interface OnScreen {
  settings: Settings;
  seed: number | null;
  speed: number;
  trapHeight: number;
  theme: ThemeName;
  soundOn: boolean;
  setup: Setup;
}

/** The address of the setup on screen: this page with every option that makes it. */
export function linkFor(base: string, s: OnScreen): string {
  const q = new URLSearchParams();
  q.set("atoms", String(s.settings.nAtoms));
  q.set("radius", String(s.settings.radius));
  if (s.seed !== null) q.set("seed", String(s.seed));
  q.set("speed", String(s.speed));
  q.set("tc-law", s.settings.tcLaw);
  q.set("escape", s.settings.escape);
  q.set("lang", activeTranslator().locale);
  q.set("trap", String(Math.round(s.trapHeight)));
  if (s.setup.locked.size) q.set("lock", [...s.setup.locked].join(","));
  if (s.setup.hidden.size) q.set("hide", [...s.setup.hidden].join(","));
  q.set("theme", s.theme);
  q.set("sound", s.soundOn ? "on" : "off");
  // Commas stay readable in a link a teacher hands out.
  return `${base}?${q.toString().replace(/%2C/g, ",")}`;
}

/** Copy the link; the notice says so, or shows it to copy by hand. */
export async function copyLink(link: string, notify: (text: string) => void): Promise<void> {
  let copied = false;
  try {
    await navigator.clipboard.writeText(link);
    copied = true;
  } catch {
    copied = copyBySelection(link);
  }
  notify(copied ? t("link.copied") : t("link.by_hand", { link }));
}
