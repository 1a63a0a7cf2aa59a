/**
 * The charts beside (or below) the scene: which are shown, a record per frame the
 * physics advanced, and drawing into the rectangles the layout gives.
 * Python's twin: `src/evapcool/app/charts.py` (docs/twins.md).
 */
import type { AtomArrays, SimLike } from "../game/sim";
import type { ChartsShown, Layout } from "../view/geometry";
import { EnergyPanel, PathPanel } from "../view/panels";

export class Charts {
  readonly energy = new EnergyPanel();
  readonly path = new PathPanel();
  showEnergy = false;
  showPath = false;
  private recordedTime = -1;
  private recordedGen = -1;

  get shown(): ChartsShown {
    return { energy: this.showEnergy, path: this.showPath };
  }

  /** Record the physics' state once per physics time (redrawn frames add nothing). */
  record(sim: SimLike, atoms: AtomArrays, generation: number): void {
    if (generation === this.recordedGen && sim.time === this.recordedTime) return;
    this.recordedGen = generation;
    this.recordedTime = sim.time;
    this.energy.record(sim, atoms, generation);
    this.path.record(sim, generation);
  }

  reset(): void {
    this.energy.reset();
    this.path.reset();
  }

  draw(ctx: CanvasRenderingContext2D, l: Layout): void {
    if (l.charts.energy) this.energy.draw(ctx, l.charts.energy);
    if (l.charts.path) this.path.draw(ctx, l.charts.path);
  }
}
