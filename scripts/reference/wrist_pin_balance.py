#!/usr/bin/env python3
"""Reference optimum of problems/suite/wrist_pin_balance.yaml, computed without mbsopt.

The problem: a centred slider-crank (crank R, rod L) turned at a constant OMEGA drives a ram of
mass M along a rail; a spring (stiffness k, rest position x0) pulls the ram towards x0. Choose k
and x0 to make the peak axial load of the wrist pin, max_t |F(t)| over half a turn from top to bottom
dead centre (the other half repeats it), least: a spring
that balances the ram's reciprocating inertia force. The ram's equation along the rail gives the
pin force the rod receives from the ram, F = -(M s'' + k (s - x0)), so the cost is the peak of an
affine function of (k, k x0): a discrete Chebyshev (minimax) problem. Its optimum lies on a kink of
the max, where the largest positive and negative loads balance; with k = M OMEGA^2 the spring
cancels the primary (cos theta) part of the inertia force and the secondary (cos 2 theta) part
remains, and the optimum stiffness lies near that value.

How it is computed, independently of mbsopt: the mechanism has no degree of freedom, so the ram's
position s, speed and acceleration are closed forms of theta = OMEGA t. mbsopt reports the pin load
of each time point t_n = n h from the multipliers of its Newton solution, whose acceleration is
the Newmark one, s''_n = (s_n - s_{n-1} - h s'_{n-1} - (1/2 - BETA) h^2 s''_{n-1}) / (BETA h^2),
with s_{n-1}, s'_{n-1}, s''_{n-1} the closed forms at t_{n-1} (a loop without a degree of freedom is
projected onto its exact rates at every point) and at t_0 the exact s''(0). This script evaluates
those numbers, so its problem is mbsopt's discrete one. For a given k the best x0 centres the load
between its extremes, (max g + min g) / (2 k) with g = M s'' + k s, leaving half their spread,
V(k) = (max g - min g) / 2: convex and piecewise linear in k. Its minimum by ternary search over
[K_LOWER, K_UPPER] to round-off; a scan of k confirms it.

How far it can be trusted: the loads are mbsopt's to its Newton tolerance (1e-10 relative on the
acceleration; measured 4e-9 N of 30 N at the start), so cost_relative = 1e-9. The cost rises
linearly away from the kink: design_range holds the designs whose peak is within design_cost_band
(relative) of the optimum.

Standard library only. Prints the JSON that problems/suite/wrist_pin_balance.reference.json holds:
    python3 scripts/reference/wrist_pin_balance.py > problems/suite/wrist_pin_balance.reference.json
"""
import json
import math

CRANK, ROD = 0.1, 0.4              # m       crank_pin.translation.x, conrod_end.translation.x
OMEGA = 2.0 * math.pi              # rad/s   the crank's motion: polynomial [0, 2 pi]
MASS = 5.0                         # kg      ram.mass
STEP, END_TIME, BETA = 1.0e-3, 0.5, 0.25
POINTS = round(END_TIME / STEP)
K_LOWER, K_UPPER = 0.0, 400.0      # N/m     balancer.k's bounds
X0_LOWER, X0_UPPER = 0.3, 0.6      # m       balancer.rest's bounds
K_START, X0_START = 100.0, 0.45
DESIGN_COST_BAND = 1e-6


def ram(theta):
    """s, s', s'' of the ram at crank angle theta (rates in time, the crank at OMEGA)."""
    w = OMEGA
    sin, cos = math.sin(theta), math.cos(theta)
    u = CRANK * sin
    root = math.sqrt(ROD * ROD - u * u)
    s = CRANK * cos + root
    v = -CRANK * w * (sin + cos * u / root)
    a = -CRANK * w * w * (cos + (CRANK * cos * cos - u * sin) / root + u * u * CRANK * cos * cos / root ** 3)
    return s, v, a


def grid():
    """(s_n, Newmark's s''_n) at the time points, as mbsopt's Newton solutions have them."""
    exact = [ram(OMEGA * n * STEP) for n in range(POINTS + 1)]
    points = [(exact[0][0], exact[0][2])]
    for n in range(1, POINTS + 1):
        s, _, _ = exact[n]
        s_, v_, a_ = exact[n - 1]
        points.append((s, (s - s_ - STEP * v_ - (0.5 - BETA) * STEP * STEP * a_) / (BETA * STEP * STEP)))
    return points


POINTS_SA = grid()


def loads(k, x0):
    return [-(MASS * a + k * (s - x0)) for s, a in POINTS_SA]


def spread(k):
    """V(k) and the best x0 for k."""
    g = [MASS * a + k * s for s, a in POINTS_SA]
    return 0.5 * (max(g) - min(g)), 0.5 * (max(g) + min(g)) / k


def peak(k, x0):
    return max(abs(f) for f in loads(k, x0))


def main():
    low, high = K_LOWER, K_UPPER
    for _ in range(300):  # V is convex: ternary search down to round-off
        a, b = low + (high - low) / 3.0, high - (high - low) / 3.0
        if spread(a)[0] <= spread(b)[0]:
            high = b
        else:
            low = a
    k = 0.5 * (low + high)
    best, x0 = spread(k)
    if not (K_LOWER < k < K_UPPER and X0_LOWER < x0 < X0_UPPER):
        raise SystemExit("the optimum lies on a bound")
    if abs(peak(k, x0) - best) > 1e-12 * best:
        raise SystemExit("the centred x0 does not give the spread")
    scan = [K_LOWER + (K_UPPER - K_LOWER) * i / 4000 for i in range(1, 4001)]
    if min(spread(x)[0] for x in scan) < best:
        raise SystemExit("the scan found a lower peak: the search did not find the optimum")
    # The designs within the band: V(k) <= band on an interval of k, and for each such k the x0
    # with every |load| <= band. Their projections, sampled along the interval and at its ends.
    band = best * (1.0 + DESIGN_COST_BAND)
    slope_below = (spread(k)[0] - spread(k - 1e-3)[0]) / 1e-3
    slope_above = (spread(k + 1e-3)[0] - spread(k)[0]) / 1e-3
    k_low, k_high = k - (band - best) / -slope_below, k + (band - best) / slope_above
    x0_low, x0_high = math.inf, -math.inf
    for i in range(201):
        kk = k_low + (k_high - k_low) * i / 200
        g = [MASS * a + kk * s for s, a in POINTS_SA]
        x0_low = min(x0_low, (max(g) - band) / kk)
        x0_high = max(x0_high, (min(g) + band) / kk)
    start = peak(K_START, X0_START)
    reference = {
        "problem": "wrist_pin_balance",
        "scene": "problems/suite/wrist_pin_balance.yaml",
        "command": "python3 scripts/reference/wrist_pin_balance.py > problems/suite/wrist_pin_balance.reference.json",
        "method": "closed-form kinematics and the Newmark accelerations of mbsopt's Newton solutions at the time "
                  "points; the discrete Chebyshev problem in (k, k x0) by ternary search on its convex spread, "
                  "checked by a scan",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"crank_pin.translation.x": CRANK, "conrod_end.translation.x": ROD,
                 "crank.motion.polynomial.1": OMEGA, "ram.mass": MASS, "balancer.k": K_START,
                 "balancer.c": 0.0, "balancer.rest": X0_START, "slider.q0": CRANK + ROD, "slider.v0": 0.0,
                 "conrod.q0": 0.0, "conrod.v0": -OMEGA * (1.0 + CRANK / ROD),
                 "design.variables.0.lower": K_LOWER, "design.variables.0.upper": K_UPPER,
                 "design.variables.1.lower": X0_LOWER, "design.variables.1.upper": X0_UPPER,
                 "settings.end_time": END_TIME, "settings.step": STEP, "settings.beta": BETA},
        "optimum": {
            "design": {"balancer.k": k, "balancer.rest": x0},
            "responses": {"max_abs_pin_x": best},
            "peak_at_the_start": start,
            "peak_without_spring": max(abs(MASS * a) for _, a in POINTS_SA),
            "primary_balance_stiffness": MASS * OMEGA * OMEGA,
            "slope_below": slope_below,
            "slope_above": slope_above,
        },
        "accuracy": {
            "cost_relative": 1e-9,
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"balancer.k": [k_low, k_high], "balancer.rest": [x0_low, x0_high]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
