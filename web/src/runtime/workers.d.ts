/** Vite bundles a `?worker&inline` import into the page: a constructor of that worker. */
declare module "*?worker&inline" {
  const WorkerConstructor: new (options?: { name?: string }) => Worker;
  export default WorkerConstructor;
}

/** A worker's script packed by scripts/worker-plugin.mjs: deflate-raw, as base64 text. */
declare module "*?packed" {
  const packed: string;
  export default packed;
}
