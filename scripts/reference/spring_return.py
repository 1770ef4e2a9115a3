#!/usr/bin/env python3
"""Reference optimum of problems/suite/spring_return.yaml, computed without mbsopt.

The problem: the hanging body of spring_preload, struck upwards, must be back at its start height
at the end, x(T) = 0 (an equality); the design is the spring's rest position r and the damper c.
Minimise the peak travel max_t |x(t)|.

How it is computed, independently of mbsopt: for a given c, x(T) is affine in the static position
x_e = r - m g / k (the closed-form response, scripts/reference/impact.py), so the equality gives r
explicitly. Along that curve a scan of c shows the peak travel falling as c grows: the damper's
upper bound is active at the optimum, and r follows from the equality there.

How far it can be trusted: the continuous-time optimum to ~1e-12. On mbsopt's time grid the peak
is sampled, off by at most (omega h)^2 / 8 (cost_relative), and the trapezoidal rule's period
error (omega h)^2 / 12 shifts the phase at T by omega_d T (omega h)^2 / 12, which moves x(T) by
|x'(T)| T (omega h)^2 / 12 and r by that over |dx(T)/dr|. design_range allows ten times that shift
for r, and c at its bound.

Standard library only. Prints the JSON that problems/suite/spring_return.reference.json holds:
    python3 scripts/reference/spring_return.py > problems/suite/spring_return.reference.json
"""
import json
import math

from hanging import END_TIME, GRAVITY, MASS, OMEGA, SAG, SPEED, STEP, STIFFNESS
from impact import peak_of, released, sampled_peak_error

R_LOWER, R_UPPER = -0.2, 0.4   # m        hanger.rest's bounds
C_LOWER, C_UPPER = 20.0, 150.0  # N s/m    hanger.c's bounds (the scene's damper is the design)
SAMPLES = 4000


def motion(c):
    sigma = c / (2.0 * MASS)
    return sigma, math.sqrt(OMEGA * OMEGA - sigma * sigma)


def rest_for(c):
    """The r with x(T) = 0: x(T) is affine in the static position."""
    sigma, omega_d = motion(c)
    at_zero = released(0.0, sigma, omega_d, SPEED, END_TIME)
    slope = released(1.0, sigma, omega_d, SPEED, END_TIME) - at_zero
    return SAG - at_zero / slope, slope


def travel(c, t):
    sigma, omega_d = motion(c)
    return released(rest_for(c)[0] - SAG, sigma, omega_d, SPEED, t)


def peak(c):
    return peak_of(lambda t: travel(c, t), 0.0, END_TIME, SAMPLES)


def main():
    scan = [C_LOWER + (C_UPPER - C_LOWER) * i / 130 for i in range(131)]
    peaks = [peak(c) for c in scan]
    if any(later >= earlier for earlier, later in zip(peaks, peaks[1:])):
        raise SystemExit("the peak does not fall along the equality: the damper's bound need not be active")
    c = C_UPPER
    rest, slope = rest_for(c)
    if not R_LOWER <= rest <= R_UPPER:
        raise SystemExit("the equality's r lies outside its bounds")
    sigma, omega_d = motion(c)
    rate = (released(rest - SAG, sigma, omega_d, SPEED, END_TIME + 1e-6) -
            released(rest - SAG, sigma, omega_d, SPEED, END_TIME - 1e-6)) / 2e-6
    shift = abs(rate) * END_TIME * (OMEGA * STEP) ** 2 / 12.0 / abs(slope)
    reference = {
        "problem": "spring_return",
        "scene": "problems/suite/spring_return.yaml",
        "command": "python3 scripts/reference/spring_return.py > problems/suite/spring_return.reference.json",
        "method": "closed-form response; the equality x(T) = 0 solved for r (affine), the peak along it scanned "
                  "in c: the damper's upper bound is active",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"body.mass": MASS, "hanger.k": STIFFNESS, "gravity.x": -GRAVITY, "lift.q0": 0.0, "lift.v0": SPEED,
                 "design.variables.0.lower": R_LOWER, "design.variables.0.upper": R_UPPER,
                 "design.variables.1.lower": C_LOWER, "design.variables.1.upper": C_UPPER,
                 "design.constraints.0.equals": 0.0, "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"hanger.rest": rest, "hanger.c": c},
            "responses": {"max_abs_travel": peak(c)},
            "static_position": rest - SAG,
            "peak_at_lower_damping": peaks[0],
        },
        "accuracy": {
            "cost_relative": sampled_peak_error(OMEGA, STEP),
            "rest_shift": shift,
            "design_range": {"hanger.rest": [rest - 10.0 * shift, rest + 10.0 * shift], "hanger.c": [c, c]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
