#!/usr/bin/env python3
"""Reference optimum of problems/suite/quarter_car.yaml, computed without mbsopt.

The problem: a quarter-car (body 300 kg on a suspension spring k and damper c, over an axle of
40 kg on a tyre of 200 kN/m), moving about its static equilibrium, is kicked by a kerb: the axle
leaves at 2 m/s upwards, the body at rest. Design k and c; minimise the comfort cost, the RMS of
the body's vertical acceleration over 3 s, keeping the suspension travel within 18 mm.

How it is computed, independently of mbsopt: the motion is linear, M x'' + C x' + K x = 0 in
x = (axle height z_w, suspension travel z_r = z_b - z_w), with M = [[m_w + m_b, m_b], [m_b, m_b]],
C = diag(0, c), K = diag(k_t, k), and the body's acceleration -(k z_r + c z_r') / m_b. This
script integrates it by its own trapezoidal rule (Newmark with beta = 1/4, gamma = 1/2: the
scheme mbsopt uses, written here for this 2 x 2 system, one linear solve a step) on mbsopt's time
grid, and takes the RMS by the trapezoidal rule and the travel's maximum over the grid, as mbsopt
does. So it solves the same discrete problem as mbsopt, by other code. The travel falls as c
grows; for each k, regula falsi finds the c that meets the travel bound. Along that boundary a scan
of k shows one interior minimum, which golden-section search finds; beyond the bound's c the cost
only rises, so the bound is active.

How far it can be trusted: the discrete problem's optimum to round-off (regula falsi ends at 1e-13
relative), so cost_relative is 1e-9, ten times the simulation's Newton tolerance (1e-10). The cost is flat in k
along the bound: design_range holds the designs whose cost is within design_cost_band of the
optimum. A converged optimizer may exceed the travel bound by its feasibility tolerance (1e-6 m),
which lowers the cost by the bound's multiplier times that: feasibility_allowance. The continuous-
time problem differs by the scheme's O((omega h)^2) error: the script also integrates the optimum
with a ten times finer step and records both (continuous_cost).

Standard library only; about 10 s. Prints the JSON that problems/suite/quarter_car.reference.json
holds:
    python3 scripts/reference/quarter_car.py > problems/suite/quarter_car.reference.json
"""
import json
import math

from impact import crossing, minimise

BODY, AXLE, TYRE = 300.0, 40.0, 2.0e5   # kg, kg, N/m
KICK = 2.0                              # m/s   the axle's upward speed at t = 0
TRAVEL = 0.018                          # m     the suspension travel's bound
STEP, END_TIME = 1.0e-3, 3.0
K_LOWER, K_UPPER = 15.0e3, 60.0e3       # N/m     spring.k's bounds
C_LOWER, C_UPPER = 300.0, 5000.0        # N s/m   spring.c's bounds
K_START, C_START = 20.0e3, 1000.0
# The designs whose cost is within this of the optimum: the optimizers stop on x (xtol_rel 1e-6), and
# along this flat minimum that leaves their cost up to a few 1e-8 above it.
DESIGN_COST_BAND = 1e-7
FEASIBILITY = 1e-6      # m   the optimizers' feasibility tolerance (6-optimizers/optimizer.hpp)


def simulate(k, c, step=STEP):
    """The body's acceleration and the travel at every time point (trapezoidal Newmark)."""
    m = ((AXLE + BODY, BODY), (BODY, BODY))
    damping = ((0.0, 0.0), (0.0, c))
    stiffness = ((TYRE, 0.0), (0.0, k))

    def solve(a, b):
        det = a[0][0] * a[1][1] - a[0][1] * a[1][0]
        return ((b[0] * a[1][1] - a[0][1] * b[1]) / det, (a[0][0] * b[1] - a[1][0] * b[0]) / det)

    def force(x, v):
        return tuple(-sum(damping[i][j] * v[j] + stiffness[i][j] * x[j] for j in range(2)) for i in range(2))

    x, v = (0.0, 0.0), (KICK, -KICK)
    a = solve(m, force(x, v))
    iteration = tuple(tuple(m[i][j] + step / 2 * damping[i][j] + step * step / 4 * stiffness[i][j] for j in range(2))
                      for i in range(2))
    acceleration, travel = [(-k * x[1] - c * v[1]) / BODY], [x[1]]
    for _ in range(round(END_TIME / step)):
        x_pred = tuple(x[i] + step * v[i] + step * step / 4 * a[i] for i in range(2))
        v_pred = tuple(v[i] + step / 2 * a[i] for i in range(2))
        a = solve(iteration, force(x_pred, v_pred))
        x = tuple(x_pred[i] + step * step / 4 * a[i] for i in range(2))
        v = tuple(v_pred[i] + step / 2 * a[i] for i in range(2))
        acceleration.append((-k * x[1] - c * v[1]) / BODY)
        travel.append(x[1])
    return acceleration, travel


def rms(samples, step=STEP):
    square = sum(y * y for y in samples) - 0.5 * (samples[0] ** 2 + samples[-1] ** 2)
    return math.sqrt(square * step / END_TIME)


def largest_travel(k, c):
    return max(abs(y) for y in simulate(k, c)[1])


def damper_for(k, bound=TRAVEL):
    """The c where the largest travel meets the bound (it falls as c grows), by the Illinois
    variant of regula falsi, the bracket kept."""
    lo, hi = C_LOWER, C_UPPER
    g_lo, g_hi = largest_travel(k, lo) - bound, largest_travel(k, hi) - bound
    if not g_lo > 0.0 > g_hi:
        raise SystemExit("the travel bound is not crossed within c's bounds at k = %g" % k)
    side = 0
    while hi - lo > 1e-13 * hi:
        c = (lo * g_hi - hi * g_lo) / (g_hi - g_lo)
        g = largest_travel(k, c) - bound
        if g == 0.0:
            return c
        if g > 0.0:
            lo, g_lo = c, g
            if side == 1:
                g_hi *= 0.5
            side = 1
        else:
            hi, g_hi = c, g
            if side == -1:
                g_lo *= 0.5
            side = -1
    return hi


def cost(k, c):
    return rms(simulate(k, c)[0])


def along_the_bound(k):
    """The cost at k with c on the travel bound."""
    return cost(k, damper_for(k))


def main():
    scan = [K_LOWER + (K_UPPER - K_LOWER) * i / 9 for i in range(10)]
    along = [along_the_bound(k) for k in scan]
    best = min(range(len(scan)), key=along.__getitem__)
    if not 0 < best < len(scan) - 1 or any(
            (later >= earlier) != (i >= best) for i, (earlier, later) in enumerate(zip(along, along[1:]))):
        raise SystemExit("the cost along the travel bound is not unimodal with an interior minimum")
    k = minimise(along_the_bound, scan[best - 1], scan[best + 1])
    c = damper_for(k)
    optimal = cost(k, c)
    # Above the bound's c the travel is met with room, and the cost only rises: the bound is active.
    if not optimal < cost(k, c * 1.001):
        raise SystemExit("more damping than the travel bound needs does not cost more")
    level = optimal * (1.0 + DESIGN_COST_BAND)
    k_range = [crossing(along_the_bound, level, k, scan[best - 1]), crossing(along_the_bound, level, k, scan[best + 1])]
    c_range = sorted(damper_for(x) for x in k_range)
    fine = simulate(k, c, STEP / 10)
    # The bound's multiplier, d(cost*)/d(bound) = dcost/dc dc/dbound at k* (the envelope theorem):
    # a converged optimizer may exceed the bound by FEASIBILITY, which lowers its cost by that much.
    delta = 1e-4 * TRAVEL
    multiplier = (cost(k, damper_for(k, TRAVEL + delta)) - cost(k, damper_for(k, TRAVEL - delta))) / (2.0 * delta)
    reference = {
        "problem": "quarter_car",
        "scene": "problems/suite/quarter_car.yaml",
        "command": "python3 scripts/reference/quarter_car.py > problems/suite/quarter_car.reference.json",
        "method": "the linear two-mass model integrated by its own trapezoidal rule on mbsopt's grid; c on the "
                  "travel bound by regula falsi for each k; the cost along it minimised in k by golden-section "
                  "search after a scan",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"body.mass": BODY, "axle.mass": AXLE, "tyre.k": TYRE, "tyre.c": 0.0, "wheel.v0": KICK,
                 "suspension.v0": -KICK, "spring.k": K_START, "spring.c": C_START,
                 "design.variables.0.lower": K_LOWER, "design.variables.0.upper": K_UPPER,
                 "design.variables.1.lower": C_LOWER, "design.variables.1.upper": C_UPPER,
                 "design.constraints.0.bound": TRAVEL, "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"spring.k": k, "spring.c": c},
            "responses": {"rms_body_acceleration": optimal, "max_abs_travel": TRAVEL},
            "cost_along_the_travel_bound": dict(zip(["%.0f" % x for x in scan], along)),
        },
        "continuous_cost": {"step": STEP / 10, "rms_body_acceleration": rms(fine[0], STEP / 10),
                            "max_abs_travel": max(abs(y) for y in fine[1])},
        "accuracy": {
            "cost_relative": 1e-9,
            "bound_multiplier": multiplier,
            # What the optimizers' feasibility tolerance allows each response to differ by.
            "feasibility_allowance": {"max_abs_travel": FEASIBILITY,
                                      "rms_body_acceleration": abs(multiplier) * FEASIBILITY},
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"spring.k": k_range, "spring.c": c_range},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
