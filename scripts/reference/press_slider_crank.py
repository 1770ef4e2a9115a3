#!/usr/bin/env python3
"""Reference optimum of problems/suite/press_slider_crank.yaml, computed without mbsopt.

The problem: an offset slider-crank (crank r, rod l = 0.4 m, rail offset e) turned at a constant
2 pi rad/s drives a press ram through its working half turn, theta = 2 pi t from 0 to pi. The ram
must arrive at the die, s(pi) = sqrt(l^2 - e^2) - r = D (an equality); the rod may lean at most
PHI_MAX from the rail (transmission). Design r and e (two geometric variables: the crank pin's
offset and the rail's height); minimise the ram's peak acceleration over the half turn.

How it is computed, independently of mbsopt: the mechanism has no degree of freedom, so the ram's
position, speed and acceleration are closed forms of theta (below, from s = r cos theta +
sqrt(l^2 - u^2), u = r sin theta - e). The equality gives r as a function of e. On theta in [0, pi],
u runs over [-e, r - e], so the rod's largest lean is asin(max(e, r - e) / l), PHI_MAX where
e = l sin(PHI_MAX) (r - e stays below it). A scan of e along the equality shows the peak falling as
e grows: the optimum is the vertex where the lean constraint meets the equality.

How far it can be trusted: the responses are evaluated at mbsopt's time points t_k = k h, where a
kinematic loop's positions, rates and accelerations are those of the closure (no integration
error: the integrator closes b, its rate and its acceleration at each point); the grid maximum is
then the same numbers to the closure's tolerance. cost_relative is set to 1e-9, ten times the
Newton tolerance (1e-10 relative) of the closure; the design is a vertex of two closed forms, exact
to round-off. A converged optimizer may exceed the lean bound by its feasibility tolerance (1e-6
rad), which lowers the cost by the bound's multiplier times that: feasibility_allowance.

Standard library only. Prints the JSON that problems/suite/press_slider_crank.reference.json holds:
    python3 scripts/reference/press_slider_crank.py > problems/suite/press_slider_crank.reference.json
"""
import json
import math

ROD = 0.4                 # m        conrod_end.translation.x
SPEED = 2.0 * math.pi     # rad/s    the crank's motion: polynomial [0, 2 pi]
DIE = 0.3                 # m        the ram's position at the end, s(pi)
PHI_MAX = 0.3             # rad      the rod's largest lean
STEP, END_TIME = 1.0e-3, 0.5
FEASIBILITY = 1e-6              # rad  the optimizers' feasibility tolerance (6-optimizers/optimizer.hpp)
POINTS = round(END_TIME / STEP)
R_LOWER, R_UPPER = 0.05, 0.15  # m   crank_pin.translation.x's bounds
E_LOWER, E_UPPER = 0.0, 0.2    # m   rail.translation.y's bounds
R_START, E_START = 0.1, 0.02   # m   the scene's values


def ram(r, e, theta):
    """s, s', s'' of the ram at crank angle theta (rates in time, the crank at SPEED)."""
    w = SPEED
    sin, cos = math.sin(theta), math.cos(theta)
    u = r * sin - e
    root = math.sqrt(ROD * ROD - u * u)
    s = r * cos + root
    v = -r * w * (sin + cos * u / root)
    a = -r * w * w * (cos + (r * cos * cos - u * sin) / root + u * u * r * cos * cos / root ** 3)
    return s, v, a


def crank_for(e):
    """The r with s(pi) = DIE."""
    return math.sqrt(ROD * ROD - e * e) - DIE


def peak(r, e):
    return max(abs(ram(r, e, SPEED * k * STEP)[2]) for k in range(POINTS + 1))


def lean(r, e):
    return max(abs(math.asin((r * math.sin(SPEED * k * STEP) - e) / ROD)) for k in range(POINTS + 1))


def main():
    e = ROD * math.sin(PHI_MAX)
    r = crank_for(e)
    if not (R_LOWER <= r <= R_UPPER and E_LOWER <= e <= E_UPPER):
        raise SystemExit("the vertex lies outside the bounds")
    if not abs(lean(r, e) - PHI_MAX) < 1e-15:
        raise SystemExit("the lean constraint is not the one met at the vertex")
    scan = [e * i / 200 for i in range(201)]
    peaks = [peak(crank_for(x), x) for x in scan]
    if any(later >= earlier for earlier, later in zip(peaks, peaks[1:])):
        raise SystemExit("the peak does not fall along the equality up to the lean constraint")
    # The lean bound's multiplier, d(cost*)/d(PHI_MAX): along the equality e = l sin(PHI_MAX) moves the
    # vertex by l cos(PHI_MAX) per radian. A converged optimizer may lean FEASIBILITY further, which
    # lowers its cost by that much.
    delta = 1e-6
    multiplier = (peak(crank_for(e + delta), e + delta) - peak(crank_for(e - delta), e - delta)) / (2.0 * delta) * \
        ROD * math.cos(PHI_MAX)
    conrod = math.asin(E_START / ROD)  # the rod's angle to the rail at theta = 0 (u = -e): the scene's q0
    s0, v0, _ = ram(R_START, E_START, 0.0)
    rod_rate = -R_START * SPEED / (ROD * math.cos(conrod))  # d/dt of -asin(u / l) at theta = 0
    reference = {
        "problem": "press_slider_crank",
        "scene": "problems/suite/press_slider_crank.yaml",
        "command": "python3 scripts/reference/press_slider_crank.py > problems/suite/press_slider_crank.reference.json",
        "method": "closed-form kinematics at the time points; r from the equality s(pi) = D, the peak along it "
                  "scanned in e: the vertex with the rod's lean constraint",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"conrod_end.translation.x": ROD, "crank.motion.polynomial.1": SPEED,
                 "crank_pin.translation.x": R_START, "rail.translation.y": E_START,
                 "conrod.q0": conrod, "conrod.v0": rod_rate - SPEED, "slider.q0": s0, "slider.v0": v0,
                 "design.variables.0.lower": R_LOWER, "design.variables.0.upper": R_UPPER,
                 "design.variables.1.lower": E_LOWER, "design.variables.1.upper": E_UPPER,
                 "design.constraints.0.bound": PHI_MAX, "design.constraints.1.equals": DIE,
                 "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"crank_pin.translation.x": r, "rail.translation.y": e},
            "responses": {"max_abs_slider_a": peak(r, e), "max_abs_rod_angle_deg": math.degrees(PHI_MAX)},
            "peak_without_offset": peaks[0],
        },
        "accuracy": {
            "cost_relative": 1e-9,
            "bound_multiplier": multiplier,
            # What the optimizers' feasibility tolerance allows each response to differ by.
            "feasibility_allowance": {"max_abs_rod_angle_deg": math.degrees(FEASIBILITY),
                                      "max_abs_slider_a": abs(multiplier) * FEASIBILITY},
            "design_range": {"crank_pin.translation.x": [r, r], "rail.translation.y": [e, e]},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
