#!/usr/bin/env python3
"""Reference optimum of problems/suite/parallelogram_buffer.yaml, computed without mbsopt.

The problem: a parallelogram four-bar (crank and rocker of length L on pivots a distance H apart,
a coupler of length H) hangs under gravity and is struck, its crank turning at w0; a torsional
spring-damper (k, c) at the crank must hold the swing within a bound. Minimise the crank's peak
angular deceleration subject to the peak swing max |alpha| <= bound, over 0 <= t <= T.

How it is computed, independently of mbsopt (its loop closure, SVD, projections, integrator and
optimizers): the coupler of a parallelogram translates, so the loop has one degree of freedom,
the crank angle alpha, and the rocker turns with it. Its kinetic energy is J alpha'^2 / 2 with
J = I_crank + I_rocker (about their pivots) + m_coupler L^2, its potential -g S cos(alpha) with
S = m_crank c_crank + m_rocker c_rocker + m_coupler L (c the centres' distances from the pivots),
so that
    J alpha'' = -g S sin(alpha) - k alpha - c alpha'.
This equation is integrated by the classical Runge-Kutta method at a step of 1e-4 s (its error is
of order (omega h)^4, about 1e-13); the peaks are the largest samples. For each c, k is found by
bisection so that the swing peak is the bound (a stiffer spring swings less and decelerates
more, so the least feasible k is best: where the bound is active, or k's lower bound); the peak
deceleration is then minimised over c by golden-section search, and a coarse scan of the design
checks that no feasible design decelerates less.

How far it can be trusted: a sampled peak is off by at most (omega h)^2 / 8 of its value, 2e-7 at
h = 1e-4 (reference_relative). mbsopt's time grid (Newmark, h = 1 ms) moves the optimal cost by
O((omega h)^2) as well, (omega h)^2 / 8 at its step (cost_relative). design_range lists the
designs along the active bound whose cost is within design_cost_band (relative) of the optimum.

Standard library only; about two minutes. Prints the JSON that
problems/suite/parallelogram_buffer.reference.json holds:
    python3 scripts/reference/parallelogram_buffer.py > problems/suite/parallelogram_buffer.reference.json
"""
import json
import math

from impact import crossing, minimise, sampled_peak_error

CRANK = 0.4                          # m        crank_tip.translation.x (= rocker_tip.translation.x)
PIVOTS = 1.0                         # m        rocker_pivot.translation.y (= coupler_tip.translation.x)
BAR_MASS, BAR_CENTRE, BAR_IZZ = 0.8, 0.2, 0.010666666666666666   # crank_bar and rocker_bar
COUPLER_MASS = 2.0                   # kg       coupler_bar.mass
GRAVITY = 9.81                       # m/s^2    gravity.x, along the hanging bars
SPEED = 3.0                          # rad/s    crank.v0
BOUND = 0.3                          # rad      design.constraints.0.bound
END_TIME = 2.0                       # s        settings.end_time
STEP = 1.0e-3                        # s        settings.step (for the discretisation estimate only)
RK_STEP = 1.0e-4                     # s        the reference's own step
C_LOWER, C_UPPER = 0.1, 5.0          # N m s/rad  torsion.c's bounds
K_LOWER, K_UPPER = 1.0, 100.0        # N m/rad    torsion.k's bounds
DESIGN_COST_BAND = 1e-4

INERTIA = 2.0 * (BAR_IZZ + BAR_MASS * BAR_CENTRE ** 2) + COUPLER_MASS * CRANK ** 2
MOMENT = 2.0 * BAR_MASS * BAR_CENTRE + COUPLER_MASS * CRANK


def acceleration(k, c, alpha, rate):
    return -(GRAVITY * MOMENT * math.sin(alpha) + k * alpha + c * rate) / INERTIA


def peaks(k, c):
    """(max |alpha|, max |alpha''|) over the samples of a classical Runge-Kutta run from (0, SPEED)."""
    alpha, rate = 0.0, SPEED
    swing, deceleration = 0.0, abs(acceleration(k, c, alpha, rate))
    h = RK_STEP
    for _ in range(round(END_TIME / h)):
        k1a, k1r = rate, acceleration(k, c, alpha, rate)
        k2a, k2r = rate + 0.5 * h * k1r, acceleration(k, c, alpha + 0.5 * h * k1a, rate + 0.5 * h * k1r)
        k3a, k3r = rate + 0.5 * h * k2r, acceleration(k, c, alpha + 0.5 * h * k2a, rate + 0.5 * h * k2r)
        k4a, k4r = rate + h * k3r, acceleration(k, c, alpha + h * k3a, rate + h * k3r)
        alpha += h / 6.0 * (k1a + 2.0 * k2a + 2.0 * k3a + k4a)
        rate += h / 6.0 * (k1r + 2.0 * k2r + 2.0 * k3r + k4r)
        swing = max(swing, abs(alpha))
        deceleration = max(deceleration, abs(acceleration(k, c, alpha, rate)))
    return swing, deceleration


def stiffness_at(c):
    """The least feasible k for the damper c: the k whose swing peak is BOUND, by bisection (the swing
    falls as k grows), or the lower bound when that swings less already."""
    if peaks(K_LOWER, c)[0] <= BOUND:
        return K_LOWER
    return crossing(lambda k: -peaks(k, c)[0], -BOUND, K_LOWER, K_UPPER, iterations=45)


def deceleration_at(c):
    return peaks(stiffness_at(c), c)[1]


def main():
    grid = [C_LOWER + (C_UPPER - C_LOWER) * i / 12 for i in range(13)]
    best = min(grid, key=deceleration_at)
    step = (C_UPPER - C_LOWER) / 12
    c = minimise(deceleration_at, max(C_LOWER, best - step), min(C_UPPER, best + step))
    k = stiffness_at(c)
    swing, deceleration = peaks(k, c)
    # No feasible design of a coarse grid decelerates less.
    for kk in [K_LOWER + (K_UPPER - K_LOWER) * i / 20 for i in range(21)]:
        for cc in grid:
            s, d = peaks(kk, cc)
            if s <= BOUND and d < deceleration:
                raise SystemExit(f"k = {kk}, c = {cc} is feasible and decelerates less than the optimum found")
    band = deceleration * (1.0 + DESIGN_COST_BAND)
    c_low = crossing(deceleration_at, band, c, max(C_LOWER, c - 2 * step), iterations=40)
    c_high = crossing(deceleration_at, band, c, min(C_UPPER, c + 2 * step), iterations=40)
    k_ends = [stiffness_at(c_low), stiffness_at(c_high)]
    omega = math.sqrt((k + GRAVITY * MOMENT) / INERTIA)
    reference = {
        "problem": "parallelogram_buffer",
        "scene": "problems/suite/parallelogram_buffer.yaml",
        "command": "python3 scripts/reference/parallelogram_buffer.py > "
                   "problems/suite/parallelogram_buffer.reference.json",
        "method": "the loop reduced to its one degree of freedom (the coupler translates), integrated by "
                  "classical Runge-Kutta at 1e-4 s; the swing bound active (bisection in k), the damping by "
                  "golden-section search; a coarse scan checks that the bound is active",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"crank_tip.translation.x": CRANK, "rocker_tip.translation.x": CRANK,
                 "rocker_pivot.translation.y": PIVOTS, "coupler_tip.translation.x": PIVOTS,
                 "crank_bar.mass": BAR_MASS, "crank_bar.com.x": BAR_CENTRE, "crank_bar.Izz": BAR_IZZ,
                 "rocker_bar.mass": BAR_MASS, "rocker_bar.com.x": BAR_CENTRE, "rocker_bar.Izz": BAR_IZZ,
                 "coupler_bar.mass": COUPLER_MASS, "gravity.x": GRAVITY, "crank.q0": 0.0, "crank.v0": SPEED,
                 "rocker.q0": 0.0, "rocker.v0": SPEED, "torsion.rest": 0.0, "design.constraints.0.bound": BOUND,
                 "design.variables.0.lower": K_LOWER, "design.variables.0.upper": K_UPPER,
                 "design.variables.1.lower": C_LOWER, "design.variables.1.upper": C_UPPER,
                 "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"torsion.k": k, "torsion.c": c},
            "responses": {"max_abs_angular_deceleration": deceleration, "max_abs_swing": swing},
            "reduced_inertia": INERTIA,
            "gravity_moment": MOMENT,
        },
        "accuracy": {
            "reference_relative": sampled_peak_error(omega, RK_STEP),
            "cost_relative": sampled_peak_error(omega, STEP),
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"torsion.k": sorted(k_ends), "torsion.c": [c_low, c_high]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
