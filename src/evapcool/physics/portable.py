"""Arithmetic with the same last bit in every language (issue 22.1).

IEEE 754 rounds + - * / and sqrt exactly, so Python, TypeScript and C agree on them bit
for bit; pow, exp, log, sin and cos are left to each platform's library and may not.
What decides a start, an event or the win uses only this module (twin: `core_power` in
core/start.c, which the compiled core's Tc table and the page use).
"""

from __future__ import annotations

import math

#: Square roots taken at most: x^(2^-60) is 1.0 in double precision for any x > 0 here.
_MAX_ROOTS = 60


def power(x: float, p: float) -> float:
    """x^p for x >= 0 and 0 < p <= 10 from products and square roots only.

    p = whole + sum of b_k 2^-k (its binary digits, exact for a double): x^p is x^whole
    times the x^(2^-k) of the digits set, x^(2^-k) by k nested square roots. Within a few
    units in the last place of the true power, and the same bits everywhere.
    """
    if x == 0.0:
        return 0.0
    whole = math.floor(p)
    result = 1.0
    for _ in range(int(whole)):
        result *= x
    frac = p - whole
    root = x
    for _ in range(_MAX_ROOTS):
        if frac == 0.0:
            break
        root = math.sqrt(root)
        frac *= 2.0
        if frac >= 1.0:
            result *= root
            frac -= 1.0
    return result
