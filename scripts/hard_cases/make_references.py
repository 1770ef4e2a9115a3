#!/usr/bin/python3
"""Regenerates the hard-case suite's references (problems/scenes/hard/reference/*.csv) and the
generated N four-bar scenes, independently of mbsopt.

    /usr/bin/python3 scripts/hard_cases/make_references.py

Needs Debian's python3-scipy and python3-mpmath (scripts/install-deps.sh); call /usr/bin/python3
explicitly (a pyenv `python3` on PATH may lack numpy). Takes about 10 s.

Each CSV has the header `t,<sensor>,...` (sensor names of the scene) and values with 17 significant
digits. Every reference is checked here before it is written (the script stops on a failed check):
  pendulum_a01       closed form (Jacobi elliptic functions, mpmath at 30 digits); checked against a
                     DOP853 integration of the pendulum equation and the energy.
  n_four_bar_*       the one-degree-of-freedom ODE of the parallelogram branch, DOP853 at
                     rtol = atol = 1e-13; checked: its M and C against the kinetic and potential
                     energy of the 2N+1 bars summed bar by bar, energy conservation along the
                     solution, agreement with Radau at 1e-12, and (flat releases) equality with the
                     benchmark's motion shifted in time.
  andrews_squeezer   the published values at t = 0.03 s (Test Set for IVP Solvers); checked against
                     our own DOP853 integration of the published index-1 equations.
"""
import math
import os
import sys

import mpmath as mp
import numpy as np
from scipy.integrate import solve_ivp

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
sys.dont_write_bytecode = True  # no __pycache__ in the repository
import make_n_four_bar as nfb  # noqa: E402

ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENES = os.path.join(ROOT, "problems", "scenes", "hard")
REFERENCE = os.path.join(SCENES, "reference")
G = 9.81


def check(condition, what):
    print(("  ok    " if condition else "  FAIL  ") + what)
    if not condition:
        sys.exit(f"make_references.py: check failed: {what}")


def write_csv(name, columns, rows):
    path = os.path.join(REFERENCE, name + ".csv")
    with open(path, "w") as f:
        f.write(",".join(["t"] + columns) + "\n")
        for row in rows:
            f.write(",".join("%.16e" % float(v) for v in row) + "\n")
    size = os.path.getsize(path)
    check(size < 1_000_000, f"{os.path.relpath(path, ROOT)}: {len(rows)} rows, {size} bytes (< 1 MB)")


# ------------------------------------------------------------------ A01 pendulum
def pendulum_a01():
    print("pendulum_a01: closed form, mpmath at 30 digits")
    mp.mp.dps = 30
    k = mp.sin(mp.pi / 4)  # amplitude 90 degrees: k = sin(theta0/2)
    m = k * k
    kk = mp.ellipk(m)
    w0 = mp.sqrt(mp.mpf("9.81"))  # g/L, L = 1 m

    def point(t):
        s = k * mp.ellipfun("sn", kk - w0 * mp.mpf(t), m=m)  # sin(theta/2), theta from the downward vertical
        return 2 * s * mp.sqrt(1 - s * s), 2 * s * s - 1     # x = sin(theta), y = -cos(theta)

    times = [mp.mpf(i) / 2 for i in range(4001)]  # every 0.5 s up to 2000 s: the benchmark's 4000 output steps
    rows = []
    for t in times:
        x, y = point(t)
        rows.append((t, x, y))
    # checks: the start, the circle, the energy (from the derivative of the closed form), and a numerical
    # integration of theta'' = -g sin theta over the first 50 s.
    check(abs(rows[0][1] - 1) < 1e-25 and abs(rows[0][2]) < 1e-25, "starts at (1, 0)")
    check(max(abs(r[1] ** 2 + r[2] ** 2 - 1) for r in rows) < 1e-25, "stays on the unit circle")
    period = 4 * kk / w0
    check(abs(period - mp.mpf("2.3686")) < 1e-3, f"period 4K/w0 = {mp.nstr(period, 12)} s")
    energies = []
    for t in times[::40]:
        x, y = point(t)
        dx, dy = mp.diff(lambda u: point(u)[0], t), mp.diff(lambda u: point(u)[1], t)
        energies.append((dx * dx + dy * dy) / 2 + mp.mpf("9.81") * y)
    check(max(abs(e) for e in energies) < 1e-20, "energy 1/2 v^2 + g y = 0 (released at rest at y = 0)")
    sol = solve_ivp(lambda t, z: [z[1], -G * math.sin(z[0])], [0, 50], [math.pi / 2, 0.0], method="DOP853",
                    rtol=1e-13, atol=1e-13, dense_output=True)
    worst = 0.0
    for t, x, y in rows[:101]:
        th = sol.sol(float(t))[0]
        worst = max(worst, abs(math.sin(th) - float(x)), abs(-math.cos(th) - float(y)))
    check(worst < 1e-10, f"DOP853 of theta'' = -g sin(theta) agrees over 50 s within {worst:.1e} m")
    write_csv("pendulum_a01", ["p1_x", "p1_y"], rows)


# ------------------------------------------------------------------ A02 N four-bar
def bar_energies(n, q, qd):
    """T and V of the 2N+1 bars, summed bar by bar on the parallelogram branch (every rocker at q,
    every coupler horizontal), from each bar's centre velocity and angular velocity."""
    t = v = 0.0
    i_c = 1.0 / 12.0  # m L^2 / 12
    for i in range(n + 1):  # rockers: centre (i + cos q / 2, sin q / 2), angular velocity qd
        vc = 0.5 * qd
        t += 0.5 * vc * vc + 0.5 * i_c * qd * qd
        v += G * 0.5 * math.sin(q)
    for i in range(n):  # couplers: centre (i + cos q + 1/2, sin q), no rotation
        vc = qd
        t += 0.5 * vc * vc
        v += G * math.sin(q)
    return t, v


def reduced_solution(n, q0, v0, t_end, method="DOP853", tol=1e-13):
    m, c = nfb.reduced_coefficients(n)
    return solve_ivp(lambda t, z: [z[1], -G * c / m * math.cos(z[0])], [0, t_end], [q0, v0], method=method,
                     rtol=tol, atol=tol, dense_output=True)


def trapezoidal_error(n, q0, v0, h, t_end):
    """max |B0 - B0_ref| of the trapezoidal rule (Newmark 1/4, 1/2) applied to the reduced ODE: what an
    exact implementation of mbsopt's integrator can at best achieve at step h (for the README)."""
    m, c = nfb.reduced_coefficients(n)
    k = G * c / m
    ref = reduced_solution(n, q0, v0, t_end)
    q, v, a = q0, v0, -k * math.cos(q0)
    worst, near = 0.0, (math.inf, 0.0)
    for s in range(1, int(round(t_end / h)) + 1):
        qp, vp, an = q + h * v + 0.25 * h * h * a, v + 0.5 * h * a, a
        for _ in range(50):
            qq = qp + 0.25 * h * h * an
            dn = (an + k * math.cos(qq)) / (1 - k * math.sin(qq) * 0.25 * h * h)
            an -= dn
            if abs(dn) < 1e-15 * (1 + abs(an)):
                break
        q, v, a = qp + 0.25 * h * h * an, vp + 0.5 * h * an, an
        qr = ref.sol(s * h)[0]
        worst = max(worst, math.hypot(math.cos(q) - math.cos(qr), math.sin(q) - math.sin(qr)))
        distance = abs(math.remainder(q, math.pi))
        if distance < near[0]:
            near = (distance, s * h)
    return worst, near


def n_four_bar(name, n, flat, step, t_end, dt_out, rate=None):
    print(f"{name}: N = {n}, {'flat release' if flat else 'rockers vertical'}, DOP853 at 1e-13")
    with open(os.path.join(SCENES, name + ".yaml"), "w") as f:
        f.write(nfb.scene(n, flat, step, t_end, rate))
    m, c = nfb.reduced_coefficients(n)
    q0, v0 = (0.0, rate if rate is not None else nfb.flat_rate(n)) if flat else (math.pi / 2, -1.0)
    sol = reduced_solution(n, q0, v0, t_end)
    # the reduced M, C against the bars' energies, at a few states
    worst = 0.0
    for q, qd in ((0.3, -1.7), (2.0, 0.4), (-1.1, 5.0)):
        t, v = bar_energies(n, q, qd)
        worst = max(worst, abs(t - 0.5 * m * qd * qd), abs(v - G * c * math.sin(q)))
    check(worst < 1e-11, f"M = {m:.6g}, C = {c:.6g} equal the energies summed over the {2 * n + 1} bars")
    count = int(round(t_end / dt_out))
    times = np.array([i * dt_out for i in range(count + 1)])
    z = sol.sol(times)
    energy = 0.5 * m * z[1] ** 2 + G * c * np.sin(z[0])
    drift = np.max(np.abs(energy - energy[0])) / abs(energy[0])
    check(drift < 1e-11, f"energy conserved to {drift:.1e} (relative)")
    other = reduced_solution(n, q0, v0, t_end, method="Radau", tol=1e-12).sol(times)[0]
    diff = np.max(np.abs(other - z[0]))
    check(diff < 1e-8, f"Radau at 1e-12 agrees within {diff:.1e} rad")
    flats = int(np.floor(abs(z[0][-1] - q0) / math.pi + (0 if flat else 0.5)))
    print(f"        q(T) = {z[0][-1]:.6f} rad: {flats} passages through the flat configuration after t = 0")
    if flat and rate is None:  # the benchmark's motion shifted in time: q(t) = q_a02(t + t*), q_a02(t*) = 0
        bench = reduced_solution(n, math.pi / 2, -1.0, t_end + 2.0)
        tq = [0.0, 1.0]
        for _ in range(60):  # bisection for the first zero of q_a02 (q decreases from pi/2)
            mid = 0.5 * (tq[0] + tq[1])
            tq[0 if bench.sol(mid)[0] > 0 else 1] = mid
        shifted = bench.sol(times + tq[0])[0]
        diff = np.max(np.abs(shifted - z[0]))
        check(diff < 1e-8, f"equals the benchmark's motion shifted by {tq[0]:.12f} s within {diff:.1e} rad")
    for h in (2e-2, 1e-2, 5e-3) if n > 2 else (1e-2,):
        error, near = trapezoidal_error(n, q0, v0, h, t_end)
        print(f"        trapezoidal rule on this ODE at h = {h:g}: max |B0 error| = {error:.3e} m; closest step "
              f"to a flat configuration (after t = 0): {near[0]:.2e} rad at t = {near[1]:.4g} s")
    rows = [(t, math.cos(q), math.sin(q), n + math.cos(q), math.sin(q)) for t, q in zip(times, z[0])]
    write_csv(name, ["b0_x", "b0_y", "bn_x", "bn_y"], rows)


# ------------------------------------------------------------------ Andrews' squeezer
ANDREWS_PUBLISHED = [  # Test Set for IVP Solvers, problem 'andrews', y(1..7) at t = 0.03 (PSIDE, 1e-14)
    0.1581077119629904e+2, -0.1575637105984298e+2, 0.4082224013073101e-1, -0.5347301163226948e+0,
    0.5244099658805304e+0, 0.5347301163226948e+0, 0.1048080741042263e+1]
ANDREWS_Y0 = [-0.0617138900142764496358948458001, 0.0, 0.455279819163070380255912382449,
              0.222668390165885884674473185609, 0.487364979543842550225598953530,
              -0.222668390165885884674473185609, 1.23054744454982119249735015568]


def andrews_rhs(t, y):
    """Hairer & Wanner II, VII.7 (7.4)-(7.11), index-1 form: [M G^T; G 0] [q''; l] = [f; -g''(q')]."""
    m1, m2, m3, m4, m5, m6, m7 = .04325, .00365, .02373, .00706, .07050, .00706, .05498
    i1, i2, i3, i4, i5, i6, i7 = 2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5
    xb, yb, xc, yc = -.03635, .03273, .014, .072
    d, da, e, ea, rr, ra = 28e-3, 115e-4, 2e-2, 1421e-5, 7e-3, 92e-5
    ss, sa, sb, sc, sd = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2
    ta, tb, u, ua, ub, zf, zt, fa = 2308e-5, 916e-5, 4e-2, 1228e-5, 449e-5, 2e-2, 4e-2, 1421e-5
    mom, c0, lo = 0.033, 4530.0, 0.07785
    q, qd = np.array(y[:7]), np.array(y[7:])
    be, th, ga, ph, de, om, ep = q
    bep, thp, gap, php, dep, omp, epp = qd
    sth, cth, sph, som = math.sin(th), math.cos(th), math.sin(ph), math.sin(om)
    mm = np.zeros((7, 7))
    mm[0, 0] = m1 * ra ** 2 + m2 * (rr ** 2 - 2 * da * rr * cth + da ** 2) + i1 + i2
    mm[1, 0] = mm[0, 1] = m2 * (da ** 2 - da * rr * cth) + i2
    mm[1, 1] = m2 * da ** 2 + i2
    mm[2, 2] = m3 * (sa ** 2 + sb ** 2) + i3
    mm[3, 3] = m4 * (e - ea) ** 2 + i4
    mm[4, 3] = mm[3, 4] = m4 * ((e - ea) ** 2 + zt * (e - ea) * sph) + i4
    mm[4, 4] = m4 * (zt ** 2 + 2 * zt * (e - ea) * sph + (e - ea) ** 2) + m5 * (ta ** 2 + tb ** 2) + i4 + i5
    mm[5, 5] = m6 * (zf - fa) ** 2 + i6
    mm[6, 5] = mm[5, 6] = m6 * ((zf - fa) ** 2 - u * (zf - fa) * som) + i6
    mm[6, 6] = m6 * ((zf - fa) ** 2 - 2 * u * (zf - fa) * som + u ** 2) + m7 * (ua ** 2 + ub ** 2) + i6 + i7
    xd = sd * math.cos(ga) + sc * math.sin(ga) + xb
    yd = sd * math.sin(ga) - sc * math.cos(ga) + yb
    lang = math.hypot(xd - xc, yd - yc)
    force = -c0 * (lang - lo) / lang
    fx, fy = force * (xd - xc), force * (yd - yc)
    ff = np.array([
        mom - m2 * da * rr * thp * (thp + 2 * bep) * sth,
        m2 * da * rr * bep ** 2 * sth,
        fx * (sc * math.cos(ga) - sd * math.sin(ga)) + fy * (sd * math.cos(ga) + sc * math.sin(ga)),
        m4 * zt * (e - ea) * dep ** 2 * math.cos(ph),
        -m4 * zt * (e - ea) * php * (php + 2 * dep) * math.cos(ph),
        -m6 * u * (zf - fa) * epp ** 2 * math.cos(om),
        m6 * u * (zf - fa) * omp * (omp + 2 * epp) * math.cos(om)])
    # constraints g(q) = sum of a * cos(c.q) + b * sin(c.q): rows as (a_cos, b_sin, c) terms
    terms = _andrews_constraint_terms(rr, d, ss, e, zt, zf, u)
    gq = np.zeros((6, 7))
    gdd = np.zeros(6)  # d2/ds2 g(q + s q') at s = 0
    for row, row_terms in enumerate(terms):
        for a, b, cvec in row_terms:
            cv = np.array(cvec, dtype=float)
            arg, rate = cv @ q, cv @ qd
            gq[row] += (-a * math.sin(arg) + b * math.cos(arg)) * cv
            gdd[row] += -(a * math.cos(arg) + b * math.sin(arg)) * rate * rate
    kkt = np.zeros((13, 13))
    kkt[:7, :7], kkt[:7, 7:], kkt[7:, :7] = mm, gq.T, gq
    sol = np.linalg.solve(kkt, np.concatenate([ff, -gdd]))
    return np.concatenate([qd, sol[:7]])


def _andrews_constraint_terms(rr, d, ss, e, zt, zf, u):
    # indices: beta 0, theta 1, gamma 2, phi 3, delta 4, omega 5, epsilon 6 (constants dropped)
    be, beth = [1, 0, 0, 0, 0, 0, 0], [1, 1, 0, 0, 0, 0, 0]
    ga, phde, de = [0, 0, 1, 0, 0, 0, 0], [0, 0, 0, 1, 1, 0, 0], [0, 0, 0, 0, 1, 0, 0]
    omep, ep = [0, 0, 0, 0, 0, 1, 1], [0, 0, 0, 0, 0, 0, 1]
    x_e = [(rr, 0, be), (-d, 0, beth)]  # rr cos(beta) - d cos(beta + theta)
    y_e = [(0, rr, be), (0, -d, beth)]
    return [
        x_e + [(0, -ss, ga)], y_e + [(ss, 0, ga)],
        x_e + [(0, -e, phde), (-zt, 0, de)], y_e + [(e, 0, phde), (0, -zt, de)],
        x_e + [(-zf, 0, omep), (0, -u, ep)], y_e + [(0, -zf, omep), (u, 0, ep)]]


def andrews_squeezer():
    print("andrews_squeezer: published values at t = 0.03 s, checked by our own integration")
    sol = solve_ivp(andrews_rhs, [0, 0.03], ANDREWS_Y0 + [0.0] * 7, method="DOP853", rtol=1e-12, atol=1e-12)
    ours = sol.y[:7, -1]
    diff = max(abs(a - b) for a, b in zip(ours, ANDREWS_PUBLISHED))
    check(diff < 1e-6, f"DOP853 of the index-1 equations at 1e-12 agrees within {diff:.1e} rad")
    write_csv("andrews_squeezer", ["beta", "theta", "gamma", "phi", "delta", "omega", "epsilon"],
              [[0.03] + ANDREWS_PUBLISHED])


def main():
    os.makedirs(REFERENCE, exist_ok=True)
    pendulum_a01()
    n_four_bar("n_four_bar_a02", 40, False, 2e-2, 20.0, 0.02)
    n_four_bar("n_four_bar_a02_flat", 40, True, 2e-2, 20.0, 0.02)
    # the rate puts the step ending at t = 0.48 s 5.1e-6 rad from the flat configuration q = -pi
    n_four_bar("n_four_bar_2_flat", 2, True, 1e-2, 0.56, 0.01, rate=-5.40403)
    andrews_squeezer()


if __name__ == "__main__":
    main()
