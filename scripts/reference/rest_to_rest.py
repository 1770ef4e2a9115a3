#!/usr/bin/env python3
"""Reference optimum of problems/suite/rest_to_rest.yaml, computed without mbsopt.

The problem: a cart (mass M1) carries a payload (mass M2) on a spring-damper mount (K, C). A force
F(t) = sum_j A_j sin(j pi t / T), j = 1 ... 20, drives the cart along a rail. Choose the twenty
amplitudes A_j that move cart and payload by D in T and leave both at rest there (four equalities:
both positions D, both speeds zero at T, so no residual sway) with the least RMS of the cart's
acceleration over [0, T]: the gentlest rest-to-rest transfer of a flexible load, the classic
problem of input shaping, with its trade-off between a smooth drive and a payload left swaying.

How it is computed, independently of mbsopt: the system is linear and starts at rest, so the
trapezoidal Newmark map (beta = 1/4, gamma = 1/2, the scheme mbsopt integrates with) is linear in
the amplitudes: x_k = sum_j A_j x_{j,k} with x_{j,k} the response to sin(j pi t / T) alone. The
script integrates those twenty responses of the two-mass model in absolute coordinates with its own
trapezoidal rule (a constant change of coordinates commutes with the Newmark map, so mbsopt's
relative coordinates give the same numbers). The squared RMS is then a quadratic form A'QA
(trapezoidal weights, the quadrature mbsopt uses), the equalities are linear, C A = d, and the
optimum solves the KKT system [2Q C'; C 0][A; mu] = [0; d], by Gaussian elimination with partial
pivoting. No bound is active (checked).

How far it can be trusted: it is mbsopt's discrete problem solved exactly, to round-off (cost and
design to about 1e-12, measured by the residual of the KKT system), so cost_relative = 1e-9 covers
the Newton tolerance of mbsopt's own integration. The design is the unique minimiser of a strictly
convex quadratic on an affine set: design_range holds the amplitudes of the designs within
design_cost_band (relative) of the optimal cost, from the reduced Hessian's smallest eigenvalue.

Standard library only. Prints the JSON that problems/suite/rest_to_rest.reference.json holds:
    python3 scripts/reference/rest_to_rest.py > problems/suite/rest_to_rest.reference.json
"""
import json
import math

from linear import gauss

M1, M2 = 1.0, 0.5                 # kg      carriage.mass, payload.mass
K, C = 50.0, 0.2                  # N/m, N s/m   mount.k, mount.c
T, STEP = 2.0, 1.0e-3             # s       settings.end_time, settings.step
D = 1.0                           # m       the transfer
HARMONICS = 20
LOWER, UPPER = -20.0, 20.0        # N       every amplitude's bounds
START = [5.0] + [0.0] * (HARMONICS - 1)
DESIGN_COST_BAND = 1e-8


def response(j):
    """Per time point the cart's acceleration, and the final (x1, x2, v1, v2), for F = sin(j pi t / T)."""
    w = j * math.pi / T
    m = ((M1, 0.0), (0.0, M2))
    damping = ((C, -C), (-C, C))
    stiffness = ((K, -K), (-K, K))

    def solve(a, b):
        det = a[0][0] * a[1][1] - a[0][1] * a[1][0]
        return ((b[0] * a[1][1] - a[0][1] * b[1]) / det, (a[0][0] * b[1] - a[1][0] * b[0]) / det)

    def rhs(t, x, v):
        return tuple((math.sin(w * t) if i == 0 else 0.0) - sum(damping[i][l] * v[l] + stiffness[i][l] * x[l]
                                                                 for l in range(2)) for i in range(2))

    x, v = (0.0, 0.0), (0.0, 0.0)
    a = solve(m, rhs(0.0, x, v))
    iteration = tuple(tuple(m[i][l] + STEP / 2 * damping[i][l] + STEP * STEP / 4 * stiffness[i][l] for l in range(2))
                      for i in range(2))
    cart = [a[0]]
    steps = round(T / STEP)
    for n in range(1, steps + 1):
        t = n * STEP
        x_pred = tuple(x[i] + STEP * v[i] + STEP * STEP / 4 * a[i] for i in range(2))
        v_pred = tuple(v[i] + STEP / 2 * a[i] for i in range(2))
        a = solve(iteration, rhs(t, x_pred, v_pred))
        x = tuple(x_pred[i] + STEP * STEP / 4 * a[i] for i in range(2))
        v = tuple(v_pred[i] + STEP / 2 * a[i] for i in range(2))
        cart.append(a[0])
    return cart, (x[0], x[1], v[0], v[1])


def main():
    responses = [response(j) for j in range(1, HARMONICS + 1)]
    points = len(responses[0][0])
    weights = [STEP / 2 if k in (0, points - 1) else STEP for k in range(points)]
    q = [[sum(weights[k] * responses[i][0][k] * responses[j][0][k] for k in range(points)) / T
          for j in range(HARMONICS)] for i in range(HARMONICS)]
    c = [[responses[j][1][row] for j in range(HARMONICS)] for row in range(4)]
    d = [D, D, 0.0, 0.0]
    n = HARMONICS + 4
    kkt = [[0.0] * n for _ in range(n)]
    for i in range(HARMONICS):
        for j in range(HARMONICS):
            kkt[i][j] = 2.0 * q[i][j]
        for row in range(4):
            kkt[i][HARMONICS + row] = c[row][i]
            kkt[HARMONICS + row][i] = c[row][i]
    solution = gauss(kkt, [0.0] * HARMONICS + d)
    amplitudes = solution[:HARMONICS]
    residual = max(abs(sum(kkt[i][j] * solution[j] for j in range(n)) - ([0.0] * HARMONICS + d)[i]) for i in range(n))
    if residual > 1e-9:
        raise SystemExit(f"the KKT system is solved only to {residual}")
    if not all(LOWER < a < UPPER for a in amplitudes):
        raise SystemExit("an amplitude lies on a bound")
    square = sum(amplitudes[i] * q[i][j] * amplitudes[j] for i in range(HARMONICS) for j in range(HARMONICS))
    cost = math.sqrt(square)
    start_square = sum(START[i] * q[i][j] * START[j] for i in range(HARMONICS) for j in range(HARMONICS))
    # Designs within the band: cost² ≤ (1 + band)² cost*² on the affine set, whose amplitudes differ
    # from the optimum by at most sqrt(((1 + band)² − 1) cost*² / λ_min) with λ_min the smallest
    # eigenvalue of Q on the null space of C; bounded below by that of Q itself (Rayleigh quotients),
    # found by inverse iteration.
    vector = [1.0] * HARMONICS
    for _ in range(200):
        vector = gauss(q, vector)
        norm = math.sqrt(sum(v * v for v in vector))
        vector = [v / norm for v in vector]
    smallest = sum(vector[i] * q[i][j] * vector[j] for i in range(HARMONICS) for j in range(HARMONICS))
    radius = math.sqrt(((1.0 + DESIGN_COST_BAND) ** 2 - 1.0) * square / smallest)
    names = [f"drive.value.harmonics.{j}.amplitude" for j in range(HARMONICS)]
    data = {"carriage.mass": M1, "payload.mass": M2, "mount.k": K, "mount.c": C, "settings.end_time": T,
            "settings.step": STEP, "design.constraints.0.equals": D, "design.constraints.1.equals": D,
            "design.constraints.2.equals": 0.0, "design.constraints.3.equals": 0.0}
    for j in range(HARMONICS):
        data[f"drive.value.harmonics.{j}.amplitude"] = START[j]
        data[f"drive.value.harmonics.{j}.angular_frequency"] = (j + 1) * math.pi / T
        data[f"design.variables.{j}.lower"] = LOWER
        data[f"design.variables.{j}.upper"] = UPPER
    reference = {
        "problem": "rest_to_rest",
        "scene": "problems/suite/rest_to_rest.yaml",
        "command": "python3 scripts/reference/rest_to_rest.py > problems/suite/rest_to_rest.reference.json",
        "method": "the linear two-mass model's trapezoidal Newmark responses to each harmonic (its own integration), "
                  "the squared RMS as a quadratic form and the four equalities as linear ones, the KKT system "
                  "solved by Gaussian elimination",
        "data": data,
        "optimum": {
            "design": dict(zip(names, amplitudes)),
            "responses": {"rms_cart_a": cost},
            "rms_at_the_start": math.sqrt(start_square),
            "kkt_residual": residual,
        },
        "accuracy": {
            "cost_relative": 1e-9,
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {name: [a - radius, a + radius] for name, a in zip(names, amplitudes)},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
