/** Vite bundles a `?worker&inline` import into the page: a constructor of that worker. */
declare module "*?worker&inline" {
  const WorkerConstructor: new (options?: { name?: string }) => Worker;
  export default WorkerConstructor;
}

/** A worker's script packed by scripts/worker-plugin.mjs: `unpack` gives its bytes back. */
declare module "*?packed" {
  const packed: string;
  export default packed;
}

/** Bytes packed as text by the build (scripts/packing.mjs); throws without DecompressionStream. */
declare module "virtual:evapcool-unpack" {
  export function unpack(text: string): Promise<Uint8Array<ArrayBuffer>>;
}
