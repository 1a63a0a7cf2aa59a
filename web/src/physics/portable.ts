/**
 * Arithmetic with the same last bit in every language (issue 22.1), twin of
 * src/evapcool/physics/portable.py: IEEE 754 rounds + - * / and sqrt exactly; Math.pow,
 * exp, log, sin and cos are each engine's own. What decides a start, an event or the win
 * uses only this.
 */

/** Square roots taken at most: x^(2^-60) is 1 in double precision for any x > 0 here. */
const MAX_ROOTS = 60;

/** x^p for x >= 0 and 0 < p <= 10 from products and square roots only (see portable.py). */
export function power(x: number, p: number): number {
  if (x === 0) return 0;
  const whole = Math.floor(p);
  let result = 1;
  for (let k = 0; k < whole; k++) result *= x;
  let frac = p - whole;
  let root = x;
  for (let k = 0; k < MAX_ROOTS && frac !== 0; k++) {
    root = Math.sqrt(root);
    frac *= 2;
    if (frac >= 1) {
      result *= root;
      frac -= 1;
    }
  }
  return result;
}
