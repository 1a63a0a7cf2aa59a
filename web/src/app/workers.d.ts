/** Vite bundles a `?worker&inline` import into the page: a constructor of that worker. */
declare module "*?worker&inline" {
  const WorkerConstructor: new (options?: { name?: string }) => Worker;
  export default WorkerConstructor;
}
