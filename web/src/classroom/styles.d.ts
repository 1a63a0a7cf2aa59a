// A class page's entry imports its stylesheet for the build (scripts/build-class.mjs writes
// it to its own file, which the server inlines with the page's hashes).
declare module "*.css";
