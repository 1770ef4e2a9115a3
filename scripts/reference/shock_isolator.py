#!/usr/bin/env python3
"""Reference optimum of problems/suite/shock_isolator.yaml, computed without mbsopt.

The problem (Sevin and Pilkey's velocity-shock isolator, the classic of dynamic response
optimisation): a body of mass m arrives at speed v0 on a linear spring-damper buffer (k, c) and
must stop within the stroke D. Minimise the peak deceleration max_t |x''(t)| subject to
max_t |x(t)| <= D over 0 <= t <= T, with the buffer's k and c as the design.

How it is computed, independently of mbsopt's integrator, sensors and optimizers:
- the response is the closed form of the damped oscillator with x(0) = 0, x'(0) = v0
  (under-, critically or over-damped), and x'' = -(k x + c x') / m;
- a peak over [0, T] is the largest of a dense sample, refined by golden-section search on the
  closed form (to ~1e-12 s);
- with the damping ratio zeta fixed, x scales as v0/omega and x'' as v0 omega (omega = sqrt(k/m)),
  so the peak deceleration falls as the stroke grows: at the optimum the stroke bound is active.
  For each zeta, omega is found by bisection so that the stroke peak is D; the peak deceleration
  along that curve is minimised over zeta by a coarse scan followed by golden-section search.

How far it can be trusted: the continuous-time optimum is found to ~1e-10 relative. mbsopt solves
the problem on a time grid (Newmark, average acceleration, step h) and takes maxima over the grid;
both differ from continuous time by O((omega h)^2): the period by (omega h)^2 / 12 and a sampled
peak by at most (omega h)^2 / 8 of its value. That bound is reported as cost_relative. The cost is
flat in zeta along the active stroke bound, so the design is known far less precisely than the
cost: design_range lists the designs along that curve whose peak deceleration is within
design_cost_band (relative) of the optimum.

Standard library only. Prints the JSON that problems/suite/shock_isolator.reference.json holds:
    python3 scripts/reference/shock_isolator.py > problems/suite/shock_isolator.reference.json
"""
import json
import math

from impact import Impact, crossing, minimise, sampled_peak_error

MASS = 1000.0          # kg       vehicle.mass
SPEED = 2.0            # m/s      stroke.v0 (from stroke.q0 = 0, the spring's rest, no gravity)
STROKE = 0.2           # m        design.constraints.0.bound, the travel
END_TIME = 2.0         # s        settings.end_time
STEP = 1.0e-3          # s        settings.step (for the discretisation estimate only)
DESIGN_COST_BAND = 1e-4

IMPACT = Impact(MASS, SPEED, END_TIME)
peaks = IMPACT.peaks


def design_at(zeta):
    """k and c with damping ratio zeta whose stroke peak is STROKE, found by bisection in omega."""
    lo, hi = 1e-2, 1e3
    for _ in range(64):
        omega = math.sqrt(lo * hi)
        if peaks(MASS * omega * omega, 2.0 * zeta * MASS * omega)[0] > STROKE:
            lo = omega
        else:
            hi = omega
    omega = math.sqrt(lo * hi)
    return MASS * omega * omega, 2.0 * zeta * MASS * omega


def deceleration_at(zeta):
    return peaks(*design_at(zeta))[1]


def main():
    # A coarse scan first, so that the golden section starts in the bracket of the global minimum.
    grid = [0.05 * i for i in range(2, 20)]
    best = min(grid, key=deceleration_at)
    zeta = minimise(deceleration_at, best - 0.05, best + 0.05)
    k, c = design_at(zeta)
    travel, deceleration = peaks(k, c)
    omega = math.sqrt(k / MASS)
    band = deceleration * (1.0 + DESIGN_COST_BAND)
    zeta_low = crossing(deceleration_at, band, zeta, zeta - 0.2)
    zeta_high = crossing(deceleration_at, band, zeta, zeta + 0.2)
    low, high = design_at(zeta_low), design_at(zeta_high)
    reference = {
        "problem": "shock_isolator",
        "scene": "problems/suite/shock_isolator.yaml",
        "command": "python3 scripts/reference/shock_isolator.py > problems/suite/shock_isolator.reference.json",
        "method": "closed-form response of the damped oscillator; peaks by dense sampling and golden-section "
                  "refinement; the stroke bound active, the damping ratio by golden-section search",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"vehicle.mass": MASS, "stroke.q0": 0.0, "stroke.v0": SPEED, "buffer.rest": 0.0, "gravity.x": 0.0,
                 "design.constraints.0.bound": STROKE, "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"buffer.k": k, "buffer.c": c},
            "responses": {"max_abs_deceleration": deceleration, "max_abs_travel": travel},
            "damping_ratio": zeta,
            "natural_frequency": omega,
            "over_limiting_performance": deceleration / (SPEED * SPEED / (2.0 * STROKE)),
        },
        "accuracy": {
            "cost_relative": sampled_peak_error(omega, STEP),
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"buffer.k": sorted([low[0], high[0]]), "buffer.c": sorted([low[1], high[1]])},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
