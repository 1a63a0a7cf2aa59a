/**
 * The original applet's physical constants (SPEC section 1) and the model's fixed numbers
 * and codes (docs/model.md): the core's own, from its header core/evapcool_core.h through
 * the generated model.ts, as Python's physics/constants.py and world.py take them from
 * physics/model.py. The screen is the view's (view/screen.ts), the room physics/room.ts.
 */
import { ESCAPE_RULES, EVENT_NAMES, STATUS_NAMES } from "./model";

export * from "./model";

export type EscapeRule = (typeof ESCAPE_RULES)[number];
export type StatusName = (typeof STATUS_NAMES)[number];
export type EventName = (typeof EVENT_NAMES)[number];

/** One processed event: kind, atoms (j = -1 for solo events) and time in frames. */
export interface PhysicsEvent {
  kind: EventName;
  i: number;
  j: number;
  time: number;
}
