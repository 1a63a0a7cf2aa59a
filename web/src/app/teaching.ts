/**
 * Twin of Python's app/teaching.py (docs/twins.md).
 * What a teacher's link and the class add to the page (issue 48), as one room: the setup's
 * locks and hidden buttons, the theme, the sound, the run's numbers ("Save this run"), the
 * scene in one sentence (key D) and the link to what is on screen.
 */
import { activeTranslator, t } from "../i18n";
import { useTheme, type ThemeName } from "../view/colors";
import type { ControlName } from "../view/geometry";
import type { Action } from "./bindings";
import { SceneWatch } from "./describe";
import type { SettingsEditor } from "./options";
import type { PagePrefs } from "./prefs";
import type { GameLike } from "../runtime/remote";
import { codeSoFar, download, RunLog } from "./runlog";
import { copyLink, linkFor, Setup } from "./setup";
import { Sound, type Heard } from "./sound";

export interface TeachingHost {
  readonly game: GameLike;
  readonly options: SettingsEditor;
  notify(text: string): void;
  say(text: string): void;
  redraw(): void;
}

/** The button whose hiding also takes its action away. */
const BUTTON_OF: Partial<Record<Action, ControlName>> = {
  pause: "pause",
  restart: "restart",
  step: "step",
  slower: "slower",
  faster: "faster",
  autopilot: "autopilot",
  energy: "chart",
  path: "path",
  help: "help",
  table: "table",
  clear: "table",
  settings: "settings",
  fullscreen: "fullscreen",
};
/** The lock that takes an action away. */
const LOCK_OF: Partial<Record<Action, string>> = {
  faster: "speed",
  slower: "speed",
  lower: "trap",
  raise: "trap",
  autopilot: "trap",
};

export class Teaching {
  readonly sound: Sound;
  readonly log = new RunLog();
  readonly watch = new SceneWatch();
  theme: ThemeName = "dark";
  /** Sound can play here: no Web Audio, or a context that would not run, says it cannot. A
   * browser cannot tell a muted device (docs/teach.md). */
  audible = typeof AudioContext === "function";
  /** The theme and sound the address asked for (this visit only, until settings are saved). */
  private askedTheme: ThemeName | null;
  private askedSound: boolean | null;

  constructor(
    private readonly host: TeachingHost,
    readonly setup: Setup,
    /** Class mode: sound off unless chosen. */
    readonly inClass: boolean,
  ) {
    this.askedTheme = setup.params.theme;
    this.askedSound = setup.params.sound;
    // The settings screen shows what the address chose (kept only if saved there).
    const o = host.options;
    const p = { ...o.prefs, theme: this.askedTheme ?? o.prefs.theme };
    if (this.askedSound !== null) p.sound = this.askedSound;
    o.prefs = o.prefsDraft = p;
    this.sound = new Sound(this.soundOn(p), p.volume);
    this.log.everyFrame = p.everyFrame;
    this.applyTheme(p);
  }

  private soundOn(p: PagePrefs): boolean {
    return this.askedSound ?? p.sound ?? (!this.inClass && this.audible);
  }

  private applyTheme(p: PagePrefs): void {
    this.theme = this.askedTheme ?? p.theme;
    useTheme(this.theme);
    document.documentElement.dataset.theme = this.theme;
  }

  /** The settings screen saved new preferences: they beat the address from now on. */
  prefsChanged(p: PagePrefs): void {
    this.askedTheme = null;
    this.askedSound = null;
    this.applyTheme(p);
    this.sound.set(this.soundOn(p), p.volume);
    this.log.everyFrame = p.everyFrame;
    this.host.redraw();
  }

  /** The action is taken away by the link (hidden or locked): said once, true. */
  blocked(action: Action): boolean {
    const button = BUTTON_OF[action];
    if (button && this.setup.isHidden(button)) return true;
    const lock = LOCK_OF[action];
    if (lock && this.setup.locked.has(lock)) {
      this.host.notify(
        t("link.locked", { name: t(lock === "trap" ? "controls.trap_height" : "link.speed") }),
      );
      return true;
    }
    return false;
  }

  /** A drawn frame: the sound, the run's rows, the scene watch. */
  frame(): void {
    const g = this.host.game;
    this.log.record(g);
    this.watch.frame(g);
    if (this.sound.attached) this.sound.frame(this.heard());
  }

  /** What the sound follows now. */
  heard(): Heard {
    const g = this.host.game;
    const s = g.sim;
    return {
      nTrapped: s.nTrapped,
      temperature: s.temperature,
      criticalTemperature: s.criticalTemperature,
      trapHeight: g.trapHeight,
      won: g.won,
      lost: g.score === null && !g.won && g.tooFewAtoms() !== null,
      generation: g.generation,
    };
  }

  /** A first key or tap: browsers start sound only after one. */
  wake(): void {
    if (this.sound.attached || !this.sound.on || !this.audible) return;
    try {
      const ctx = new AudioContext();
      this.sound.attach(ctx);
      // After a gesture (this one) a context runs unless there is no output to run on.
      const check = () => ctx.state === "running" || this.silent();
      ctx.resume().then(check, () => this.silent());
    } catch {
      this.silent();
    }
  }

  /** No audio output here: the sound is off (the settings show it off by default). */
  private silent(): void {
    this.audible = false;
    this.sound.set(false, this.sound.volume);
    this.host.redraw();
  }

  toggleMute(): void {
    // No audio output here: M says the sound stays muted (the docs say why).
    this.sound.set(!this.sound.on && this.audible, this.sound.volume);
    this.wake();
    this.host.say(t(this.sound.on ? "sound.unmuted" : "sound.muted"));
  }

  describe(): void {
    this.host.say(this.watch.sentence(this.host.game));
  }

  /** The address of what is on screen. */
  link(): string {
    const g = this.host.game;
    const base = location.href.split(/[?#]/)[0];
    return linkFor(base, {
      settings: this.host.options.runSettings(),
      seed: g.config.seed,
      speed: g.speed,
      trapHeight: g.trapHeight,
      theme: this.theme,
      soundOn: this.sound.on,
      setup: this.setup,
    });
  }

  copyLink(): void {
    void copyLink(this.link(), (text) => this.host.notify(text));
  }

  /** The run's CSV (what "Save this run" downloads). */
  async runCsv(): Promise<string> {
    const g = this.host.game;
    const s = this.host.options.runSettings();
    const settings = {
      n_atoms: g.config.nAtoms,
      radius: g.config.radius,
      tc_law: s.tcLaw,
      tc_exponent: g.config.tcExponent,
      escape: g.config.escape,
      seed: g.config.seed,
      speed: g.speed,
      language: activeTranslator().locale,
      link: this.link(),
    };
    return this.log.csv(settings, await codeSoFar(g));
  }

  async saveRun(): Promise<void> {
    const text = await this.runCsv();
    const seed = this.host.game.config.seed ?? 0;
    download(`evapcool-run-${seed}.csv`, text);
    this.host.notify(t("run.saved", { n: this.log.count }));
  }
}
