#!/usr/bin/env python3
"""Reference optimum of problems/suite/train_couplers.yaml, computed without mbsopt.

The problem: 20 cars of 1000 kg on straight track, coupled by spring-dampers (k = 100 kN/m,
c = 2 kN s/m) whose rest lengths r_2 ... r_20 are the design. The first car is pushed off at 1 m/s,
the others stand, every gap at 10 m. Nineteen equalities fix where each gap ends after 5 s,
g_i(5 s) = 10 m + 0.01 m ((i mod 3) - 1); the cost is the last car's peak acceleration.

How it is computed, independently of mbsopt: in absolute positions x_i the motion is linear,
m x_i'' = F_(i+1) - F_i with F_i = k (x_i - x_(i-1) - r_i) + c (x_i' - x_(i-1)'), a tridiagonal
system. This script integrates it by its own trapezoidal rule (Newmark, beta = 1/4, gamma = 1/2,
the scheme mbsopt uses, invariant under the constant change from gaps to positions), solving the
constant tridiagonal iteration matrix by the Thomas algorithm, on mbsopt's time grid. The final
gaps are affine in the rest lengths, g(T) = g(T; r0) + A (r - r0): twenty runs give A, column by
column, and Gaussian elimination solves the nineteen equalities. They fix the design: the feasible
set is one point, and the cost is the last car's largest acceleration on the grid there.

How far it can be trusted: the discrete problem's optimum to round-off (a run at the design meets
the equalities to about 1e-12 m), so cost_relative is 1e-9, ten times the simulation's Newton
tolerance (1e-10).

Standard library only; under 2 s. Prints the JSON that problems/suite/train_couplers.reference.json
holds:
    python3 scripts/reference/train_couplers.py > problems/suite/train_couplers.reference.json
"""
import json

from linear import gauss

CARS, MASS = 20, 1000.0           # kg
STIFFNESS, DAMPING = 1.0e5, 2000.0  # N/m, N s/m   couplerI.k, couplerI.c
GAP, PUSH = 10.0, 1.0             # m, m/s       the gaps and the first car's speed at t = 0
REST_LOWER, REST_UPPER = 9.0, 11.0
STEP, END_TIME = 1.0e-3, 5.0


def target(i):
    """The equality on gap i (car i behind car i - 1 by it), i = 2 ... CARS."""
    return GAP + 0.01 * ((i % 3) - 1)


def simulate(rest):
    """The gaps at the end and the last car's acceleration at every time point, for the rest
    lengths rest[i] of couplers i = 2 ... CARS (rest[0], rest[1] unused)."""
    n, h = CARS, STEP
    # The tridiagonal K and C (chain Laplacians) and S = M + h/2 C + h^2/4 K: diagonal and off-diagonal.
    def laplacian(coefficient):
        diagonal = [coefficient * ((1 if i > 0 else 0) + (1 if i < n - 1 else 0)) for i in range(n)]
        return diagonal, [-coefficient] * (n - 1)
    k_diagonal, k_off = laplacian(STIFFNESS)
    c_diagonal, c_off = laplacian(DAMPING)
    s_diagonal = [MASS + h / 2 * c_diagonal[i] + h * h / 4 * k_diagonal[i] for i in range(n)]
    s_off = [h / 2 * c_off[i] + h * h / 4 * k_off[i] for i in range(n - 1)]
    # Thomas factorization of the symmetric tridiagonal S.
    pivot, factor = [s_diagonal[0]], []
    for i in range(1, n):
        factor.append(s_off[i - 1] / pivot[i - 1])
        pivot.append(s_diagonal[i] - factor[-1] * s_off[i - 1])

    def solve(b):
        y = list(b)
        for i in range(1, n):
            y[i] -= factor[i - 1] * y[i - 1]
        x = [0.0] * n
        x[n - 1] = y[n - 1] / pivot[n - 1]
        for i in range(n - 2, -1, -1):
            x[i] = (y[i] - s_off[i] * x[i + 1]) / pivot[i]
        return x

    # The rest lengths' constant forces: coupler i (between cars i - 1 and i, 0-based i - 2 and i - 1)
    # pushes car i forward by k r_i and car i - 1 back.
    preload = [0.0] * n
    for i in range(2, n + 1):
        preload[i - 1] += STIFFNESS * rest[i]
        preload[i - 2] -= STIFFNESS * rest[i]

    def force(x, v):
        out = list(preload)
        for i in range(n):
            out[i] -= k_diagonal[i] * x[i] + c_diagonal[i] * v[i]
            if i > 0:
                out[i] -= k_off[i - 1] * x[i - 1] + c_off[i - 1] * v[i - 1]
            if i < n - 1:
                out[i] -= k_off[i] * x[i + 1] + c_off[i] * v[i + 1]
        return out

    x = [GAP * i for i in range(n)]
    v = [PUSH] + [0.0] * (n - 1)
    a = [f / MASS for f in force(x, v)]
    last = [a[-1]]
    for _ in range(round(END_TIME / h)):
        x_pred = [x[i] + h * v[i] + h * h / 4 * a[i] for i in range(n)]
        v_pred = [v[i] + h / 2 * a[i] for i in range(n)]
        a = solve(force(x_pred, v_pred))
        x = [x_pred[i] + h * h / 4 * a[i] for i in range(n)]
        v = [v_pred[i] + h / 2 * a[i] for i in range(n)]
        last.append(a[-1])
    return [None, None] + [x[i - 1] - x[i - 2] for i in range(2, n + 1)], last


def main():
    couplers = range(2, CARS + 1)
    start = [None, None] + [GAP] * (CARS - 1)
    base, _ = simulate(start)
    columns = []
    for j in couplers:
        shifted = list(start)
        shifted[j] += 1.0
        gaps, _ = simulate(shifted)
        columns.append([gaps[i] - base[i] for i in couplers])
    matrix = [[columns[c][r] for c in range(len(columns))] for r in range(len(columns))]
    change = gauss(matrix, [target(i) - base[i] for i in couplers])
    rest = [None, None] + [GAP + d for d in change]
    if not all(REST_LOWER <= rest[i] <= REST_UPPER for i in couplers):
        raise SystemExit("a rest length lies outside its bounds")
    gaps, last = simulate(rest)
    miss = max(abs(gaps[i] - target(i)) for i in couplers)
    if not miss < 1e-10:
        raise SystemExit("the design misses the equalities by %g m" % miss)
    reference = {
        "problem": "train_couplers",
        "scene": "problems/suite/train_couplers.yaml",
        "command": "python3 scripts/reference/train_couplers.py > problems/suite/train_couplers.reference.json",
        "method": "the linear train in absolute positions integrated by its own trapezoidal rule (Thomas "
                  "algorithm); the final gaps affine in the rest lengths, the nineteen equalities solved by "
                  "Gaussian elimination: the feasible set is one point",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": dict([("settings.end_time", END_TIME), ("settings.step", STEP), ("car1.v0", PUSH), ("car2.v0", -PUSH)] +
                     [("body%d.mass" % i, MASS) for i in range(1, CARS + 1)] +
                     [("coupler%d.k" % i, STIFFNESS) for i in couplers] +
                     [("coupler%d.c" % i, DAMPING) for i in couplers] +
                     [("car%d.q0" % i, GAP) for i in couplers] +
                     [("design.constraints.%d.equals" % (i - 2), target(i)) for i in couplers]),
        "optimum": {
            "design": dict(("coupler%d.rest" % i, rest[i]) for i in couplers),
            "responses": {"max_abs_last_car_acceleration": max(abs(y) for y in last)},
            "equality_miss": miss,
        },
        "accuracy": {
            "cost_relative": 1e-9,
            "design_range": dict(("coupler%d.rest" % i, [rest[i] - 1e-9, rest[i] + 1e-9]) for i in couplers),
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
