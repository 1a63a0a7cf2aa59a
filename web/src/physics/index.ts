/**
 * The web edition's physics: the exact event-driven model of docs/model.md, the same events
 * as the Python engines (held to it by the golden traces in web/test/golden/).
 */
export { Simulation } from "./simulation";
export type { AtomSnapshot } from "./snapshot";
export type { SimulationOptions } from "./config";
export * from "./constants";
