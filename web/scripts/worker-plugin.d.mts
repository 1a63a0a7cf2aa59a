import type { Plugin, PluginOption } from "vite";

/** The Vite plugin: `import code from "./NAME.worker?packed"` is the worker's script,
 * deflated, as base64 text. */
export function packedWorkers(options?: { plugins?: () => PluginOption[] }): Plugin;
