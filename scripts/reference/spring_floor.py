#!/usr/bin/env python3
"""Reference optimum of problems/suite/spring_floor.yaml, computed without mbsopt.

The problem: the hanging body of spring_preload, struck upwards, must not sink more than 40 mm
below its start: min_t x(t) >= -0.04 m (a constraint on a minimum, `of: min`). Choose the spring's
rest position r to make the highest point max_t x(t) (`of: max`) as low as possible. Raising r
lifts the whole oscillation, the highest and the lowest point alike, so the optimum is the lowest
r that keeps the floor: the constraint is active.

How it is computed, independently of mbsopt: the closed-form response (scripts/reference/impact.py);
the lowest and the highest point by dense sampling refined by golden-section search; r by
bisection on min x = -0.04 m; a scan of the bounds checks that both extremes rise with r.

How far it can be trusted: the continuous-time optimum to ~1e-12. On mbsopt's time grid each
extreme is off by at most (omega h)^2 / 8 of its value (cost_relative); at the active floor that
moves r by as much of the lowest point's magnitude, over d(min x)/dr = 1, which design_range allows
ten times over.

Standard library only. Prints the JSON that problems/suite/spring_floor.reference.json holds:
    python3 scripts/reference/spring_floor.py > problems/suite/spring_floor.reference.json
"""
import json

from hanging import DATA, OMEGA, STEP, extreme
from impact import crossing, sampled_peak_error

FLOOR = -0.04          # m        design.constraints.0.bound
LOWER, UPPER = -0.2, 0.4       # m   the design variable's bounds


def lowest(rest):
    return -extreme(rest, -1.0)


def main():
    scan = [LOWER + (UPPER - LOWER) * i / 300 for i in range(301)]
    highs, lows = [extreme(r, 1.0) for r in scan], [lowest(r) for r in scan]
    # The highest point may be the start, x(0) = 0, while the body sags, and the lowest the start
    # when it hangs high: neither falls with r.
    if any(b < a for a, b in zip(highs, highs[1:])) or any(b < a for a, b in zip(lows, lows[1:])):
        raise SystemExit("the extremes do not both rise with r")
    if not (lowest(LOWER) < FLOOR < lowest(UPPER)):
        raise SystemExit("the floor is not reached within the bounds")
    # min x rises with r: the lowest r with min x >= FLOOR, by bisection.
    rest = crossing(lowest, FLOOR, LOWER, UPPER, iterations=60)
    bound = sampled_peak_error(OMEGA, STEP)
    reference = {
        "problem": "spring_floor",
        "scene": "problems/suite/spring_floor.yaml",
        "command": "python3 scripts/reference/spring_floor.py > problems/suite/spring_floor.reference.json",
        "method": "closed-form response; the floor min x = -0.04 m active (bisection in r), both extremes "
                  "rising with r (a scan of the bounds)",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {**DATA, "design.constraints.0.bound": FLOOR, "design.variables.0.lower": LOWER,
                 "design.variables.0.upper": UPPER},
        "optimum": {
            "design": {"hanger.rest": rest},
            # mbsopt reports the largest |x|: the highest point here, above the floor's 40 mm.
            "responses": {"max_abs_travel": max(extreme(rest, 1.0), -lowest(rest))},
            "highest": extreme(rest, 1.0),
            "lowest": lowest(rest),
        },
        "accuracy": {
            "cost_relative": bound,
            "design_range": {"hanger.rest": [rest - 10.0 * bound * abs(FLOOR), rest + 10.0 * bound * abs(FLOOR)]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
