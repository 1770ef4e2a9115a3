#!/usr/bin/env python3
"""Reference optimum of problems/suite/spring_preload.yaml, computed without mbsopt.

The problem: a body of mass m hangs on a vertical spring-damper (k, c) under gravity g and is
struck upwards, x'(0) = v0 at x(0) = 0. Choose the spring's rest position r (its preload) to
minimise the peak travel max_t |x(t)| over 0 <= t <= T. The body oscillates about its static
position x_e = r - m g / k: raising r raises the upward peak and lowers the downward one, so the
optimum is where the two are equal, on the kink of the max, with a slope of each sign on either
side. Undamped the optimum is x_e = 0 (peak v0 / omega); with damping the downward peak comes
later and smaller, and x_e moves below 0.

How it is computed, independently of mbsopt: the closed-form response
    x(t) = x_e + exp(-sigma t) (A cos(omega_d t) + B sin(omega_d t)),  A = -x_e,
    B = (v0 - sigma x_e) / omega_d
(under-damped); the peaks of x and of -x by dense sampling and golden-section refinement
(scripts/reference/impact.py); r by bisection on (upward peak) = (downward peak); a scan of the
bounds confirms that no other r has a lower peak.

How far it can be trusted: the continuous-time optimum to ~1e-12 relative. On mbsopt's time grid
both peaks are sampled, each off by at most (omega h)^2 / 8 of its value (the Newmark period error
included), which moves the cost at the crossing by at most as much (cost_relative). The cost rises
linearly on both sides: design_range lists the r whose peak is within design_cost_band (relative)
of the optimum.

Standard library only. Prints the JSON that problems/suite/spring_preload.reference.json holds:
    python3 scripts/reference/spring_preload.py > problems/suite/spring_preload.reference.json
"""
import json

from hanging import DATA, OMEGA, SAG, STEP, extreme
from impact import crossing, sampled_peak_error

LOWER, UPPER = -0.2, 0.4       # m   the design variable's bounds
DESIGN_COST_BAND = 1e-4


def peak(rest):
    return max(extreme(rest, 1.0), extreme(rest, -1.0))


def main():
    up_minus_down = lambda r: extreme(r, 1.0) - extreme(r, -1.0)
    if not (up_minus_down(LOWER) < 0.0 < up_minus_down(UPPER)):
        raise SystemExit("the two peaks do not cross within the bounds")
    rest = crossing(up_minus_down, 0.0, LOWER, UPPER, iterations=60)
    best = peak(rest)
    scan = [LOWER + (UPPER - LOWER) * i / 600 for i in range(601)]
    lowest = min(scan, key=peak)
    if peak(lowest) < best:
        raise SystemExit(f"the scan found a lower peak at r = {lowest}: the crossing is not the optimum")
    band = best * (1.0 + DESIGN_COST_BAND)
    # Below the kink the downward peak decides (it falls as r rises), above it the upward one.
    low = crossing(lambda r: extreme(r, -1.0), band, rest, LOWER, iterations=60)
    high = crossing(lambda r: extreme(r, 1.0), band, rest, UPPER, iterations=60)
    width = 1e-4
    reference = {
        "problem": "spring_preload",
        "scene": "problems/suite/spring_preload.yaml",
        "command": "python3 scripts/reference/spring_preload.py > problems/suite/spring_preload.reference.json",
        "method": "closed-form response of the damped oscillator about its static position; the upward and "
                  "downward peaks equal (bisection), checked against a scan of the bounds",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {**DATA, "design.variables.0.lower": LOWER, "design.variables.0.upper": UPPER},
        "optimum": {
            "design": {"hanger.rest": rest},
            "responses": {"max_abs_travel": best},
            "static_position": rest - SAG,
            # d(peak)/dr on either side of the kink, over 1e-4 m.
            "slope_below": (peak(rest) - peak(rest - width)) / width,
            "slope_above": (peak(rest + width) - peak(rest)) / width,
        },
        "accuracy": {
            "cost_relative": sampled_peak_error(OMEGA, STEP),
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"hanger.rest": [low, high]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
