#!/usr/bin/env python3
"""Reference optimum of problems/suite/tuned_mass_damper.yaml, computed without mbsopt.

The problem: a machine (m1 = 100 kg) on an undamped spring (k1 = 10 kN/m, 10 rad/s) carries an
absorber (m2 = 5 kg, mu = m2/m1 = 0.05) on a spring k and a damper c. A hammer blow gives the
machine 1 m/s while the absorber is at rest. Design k in [100, 1000] N/m and c in [1, 50] N s/m;
minimise the RMS of the machine's displacement x1 over [0, T], T = 6 pi s (30 of its periods).
No constraints.

How it is computed, independently of mbsopt: the motion is linear, M x'' + C x' + K x = 0 in
x = (x1, z), z = absorber - machine, with M = [[m1 + m2, m2], [m2, m2]], C = diag(0, c),
K = diag(k1, k), from x = 0, x' = (1, -1). mbsopt integrates it by trapezoidal Newmark (beta = 1/4,
gamma = 1/2) on N = ceil(T/h) = 9 425 equal steps of T/N (h = 2 ms; the last point is exactly T),
and takes the RMS by the trapezoidal rule over that grid. For a linear system that scheme is the
trapezoidal rule on y' = A y, y = (x, x'): y_{n+1} = Phi y_n with
Phi = (I - dt A/2)^-1 (I + dt A/2). So sum_{n=0}^{N} y_n y_n' = P - Phi^{N+1} P (Phi^{N+1})' with
P = Phi P Phi' + y0 y0' (the discrete Lyapunov equation, solved as its 16 x 16 Kronecker system by
Gaussian elimination, linear.gauss's, in complex arithmetic where a complex step passes through
it), and the squared RMS is dt (S_11 - x1(T)^2/2) / T (x1(0) = 0). That is mbsopt's discrete
problem in closed form, by other code. "check" compares it with a plain step-by-step trapezoidal
Newmark loop (accelerations, predictor and corrector, as mbsopt writes the scheme) at the scene's
start, and the Kronecker solves with another algorithm, Smith's doubling (P = sum_n Phi^n q Phi'^n,
2^j terms at a time; the continuous equation through its Cayley transform with shift w1).

The optimum: Nelder-Mead from the scene's start (in k/100 and c/10, the scene's scales; the method
of scipy.optimize.minimize's "Nelder-Mead" with bounds, ported step for step, xatol 1e-10 and
fatol 0), then Newton's method on the exact gradient (complex step, no cancellation) with the
Hessian from central differences of it, until its step is below 1e-13 relative (two steps from
Nelder-Mead's point). Nelder-Mead takes 242 evaluations; with fatol 0 it stops only when its three
values are equal to the last bit, so that count is the cost's round-off's (199 with numpy's
solves). Newton from Warburton's design ends at the same point to 5e-15 ("newton"). A scan of
10 x 10 designs over the bounds finds nothing lower, and the minimum is interior (the Hessian
positive definite).

Independent checks of the problem itself: the blow is an impulse on the machine, so the integral
of x1^2 over the infinite horizon in continuous time is, up to a constant, the variance that
Warburton's H2 optimum of the absorber minimises (white-noise force on the primary, its
displacement; G. B. Warburton, Earthquake Engineering and Structural Dynamics 10, 1982):
f = sqrt(1 + mu/2)/(1 + mu), zeta = sqrt(mu (1 + 3 mu/4)/(4 (1 + mu)(1 + mu/2))), k = m2 (f w1)^2,
c = 2 zeta m2 f w1. The script compares that with the numerical minimum of the infinite-horizon
integral (A Q + Q A' + y0 y0' = 0, its Kronecker system); finds the continuous-time optimum over
[0, T] (int_0^T y y' dt = Q - e^{AT} Q e^{A'T}, e^{AT} by scaling and squaring: A T / 2^s of norm
at most 1/2, its Taylor polynomial of degree 18, s squarings), minimised likewise; evaluates the
discrete RMS at that design, which shows how far the grid moves the cost; and the RMS at the
scene's start.

How far it can be trusted: the discrete problem's optimum to round-off. The Kronecker solves have a
condition number of about 1e5 (the modes decay by only 9e-4 and 1.3e-3 a step at the optimum), so
by that bound the cost is good to about 1e-11; in fact its round-off is a staircase of about 1e-14
relative (Phi's last bits, amplified by 1/(1 - |lambda|^2)), the Newmark loop agrees to 2e-14, and
Newton's two starts agree on the design to 5e-15. cost_relative is 1e-9, ten times the
simulation's Newton tolerance (1e-10), as in quarter_car. The minimum is quadratic: design_range
holds the designs whose RMS is within design_cost_band (1e-7) of the optimum, the extent of that
sublevel set along each variable, found exactly (the other variable minimised for each value,
Brent's method, scipy's brentq ported, for where that profile meets the band; the cost's
round-off leaves those ends uncertain by up to about 2e-11 relative). The horizon hardly matters
at the optimum: the modes decay at 0.47 and 0.64 per second in amplitude, so x1^2 beyond T is
6.4e-9 of the whole ("tail_fraction"), and the continuous optimum over [0, T] lies 1.9e-8 (k) and
1.2e-7 (c) relative from Warburton's (the tail it leaves out shrinks with c and grows with k), at
the same RMS to 6e-15. The grid raises the RMS by 4.9e-5 and moves the design by 2.3e-6 (k) and
3.6e-6 (c) relative (from Warburton's, 2.3e-6 and 3.4e-6), the scheme's O((omega h)^2), well
inside design_range (half-widths of 1.4e-4 and 6.3e-4 relative): Warburton's design costs only
3e-11 more on the grid.

Standard library only, and the same output from Python 3.6 to 3.13 at least (sums left to right,
not by sum(), which compensates floats from 3.12 on); about 2 s. Prints the JSON that
problems/suite/tuned_mass_damper.reference.json holds:
    python3 scripts/reference/tuned_mass_damper.py > problems/suite/tuned_mass_damper.reference.json
"""
import json
import math

from linear import gauss, total

MACHINE, ABSORBER = 100.0, 5.0          # kg     machine_mass.mass, absorber_mass.mass
MOUNT_K, MOUNT_C = 1.0e4, 0.0           # N/m, N s/m   mount.k, mount.c
MACHINE_V0, ABSORBER_V0 = 1.0, -1.0     # m/s    machine.v0, absorber.v0 (absorber - machine)
END_TIME, STEP = 18.84955592153876, 2.0e-3   # s   settings.end_time (6 pi), settings.step
STEPS = math.ceil(END_TIME / STEP)      # mbsopt's grid: equal steps of END_TIME / STEPS
DT = END_TIME / STEPS
K_LOWER, K_UPPER = 100.0, 1000.0        # N/m     tmd.k's bounds
C_LOWER, C_UPPER = 1.0, 50.0            # N s/m   tmd.c's bounds
K_START, C_START = 400.0, 5.0
SCALES = (100.0, 10.0)                  # the scene's scales of k and c
# The designs within this of the optimal RMS (relative): the optimizers stop on x (xtol_rel 1e-6),
# and at a quadratic minimum that leaves their cost up to about 1e-8 above it.
DESIGN_COST_BAND = 1e-7
Y0 = (0.0, 0.0, MACHINE_V0, ABSORBER_V0)   # (x1, z, x1', z')
Q0 = [[a * b for b in Y0] for a in Y0]     # y0 y0'


# Small dense matrices as lists of rows, real or complex (the complex step passes through them).
# Sums run left to right by total(): sum() compensates floats from Python 3.12 on, and this output
# records round-off (the Nelder-Mead count, the differences of "newton" and "check"), which must not
# depend on the python3 that runs it.

def identity(n):
    return [[1.0 if i == j else 0.0 for j in range(n)] for i in range(n)]


def product(a, b):
    columns = list(zip(*b))
    return [[total(x * y for x, y in zip(row, column)) for column in columns] for row in a]


def transpose(a):
    return [list(row) for row in zip(*a)]


def combine(alpha, a, beta, b):
    """alpha a + beta b."""
    return [[alpha * x + beta * y for x, y in zip(p, q)] for p, q in zip(a, b)]


def solve(a, b):
    """a^-1 b, column by column (Gaussian elimination with partial pivoting)."""
    return transpose([gauss(a, list(column)) for column in zip(*b)])


def kron(a, b):
    return [[x * y for x in row_a for y in row_b] for row_a in a for row_b in b]


def largest(a):
    return max(abs(x) for row in a for x in row)


def power(a, n):
    """a^n by repeated squaring (the order of numpy.linalg.matrix_power)."""
    z = result = None
    while n > 0:
        z = a if z is None else product(z, z)
        n, bit = divmod(n, 2)
        if bit:
            result = z if result is None else product(result, z)
    return result


def expm(a):
    """e^a by scaling and squaring: a / 2^s of norm at most 1/2 (the infinity norm of its real part),
    its Taylor polynomial of degree 18 by Horner's rule (truncation below 2e-23), then s squarings."""
    n = len(a)
    norm = max(total(abs(x.real) for x in row) for row in a)
    s = max(0, math.ceil(math.log2(norm / 0.5))) if norm > 0.0 else 0
    x = [[v / 2.0 ** s for v in row] for row in a]
    e = identity(n)
    for j in range(18, 0, -1):
        e = combine(1.0, identity(n), 1.0 / j, product(x, e))
    for _ in range(s):
        e = product(e, e)
    return e


def system(k, c):
    """A of y' = A y, y = (x1, z, x1', z'); complex where k or c is (the complex step)."""
    mass = [[MACHINE + ABSORBER, ABSORBER], [ABSORBER, ABSORBER]]
    damping = [[MOUNT_C, 0.0], [0.0, c]]
    stiffness = [[MOUNT_K, 0.0], [0.0, k]]
    position, velocity = solve(mass, stiffness), solve(mass, damping)
    return [[0.0, 0.0, 1.0, 0.0], [0.0, 0.0, 0.0, 1.0],
            [-position[0][0], -position[0][1], -velocity[0][0], -velocity[0][1]],
            [-position[1][0], -position[1][1], -velocity[1][0], -velocity[1][1]]]


def step_map(k, c):
    """Phi = (I - dt A/2)^-1 (I + dt A/2): trapezoidal Newmark's step for a linear system."""
    a = system(k, c)
    return solve(combine(1.0, identity(4), -DT / 2, a), combine(1.0, identity(4), DT / 2, a))


def unstack(vector, n):
    return [vector[i * n:(i + 1) * n] for i in range(n)]


def discrete_lyapunov(phi, q):
    """P = Phi P Phi' + q by its Kronecker system (I - Phi (x) Phi) vec P = vec q, rows stacked."""
    n = len(phi)
    return unstack(gauss(combine(1.0, identity(n * n), -1.0, kron(phi, phi)), [x for row in q for x in row]), n)


def continuous_lyapunov(a, q):
    """A Q + Q A' + q = 0 by its Kronecker system (A (x) I + I (x) A) vec Q = -vec q."""
    n = len(a)
    return unstack(gauss(combine(1.0, kron(a, identity(n)), 1.0, kron(identity(n), a)),
                         [-x for row in q for x in row]), n)


def doubling(phi, q):
    """P = Phi P Phi' + q by Smith's doubling, P = sum_n Phi^n q Phi'^n summed 2^j terms at a time:
    the check of the Kronecker solves, by another algorithm."""
    p, f = [row[:] for row in q], phi
    for _ in range(60):
        p = combine(1.0, p, 1.0, product(product(f, p), transpose(f)))
        f = product(f, f)
        if largest(f) < 1e-30:
            return p
    raise SystemExit("the doubling did not converge")


def continuous_doubling(a, q, shift):
    """A Q + Q A' + q = 0 through the Cayley transform Phi = (A - s I)^-1 (A + s I):
    Q = Phi Q Phi' + 2 s R q R', R = (A - s I)^-1, by Smith's doubling."""
    n = len(a)
    minus = combine(1.0, a, -shift, identity(n))
    phi = solve(minus, combine(1.0, a, shift, identity(n)))
    r = solve(minus, identity(n))
    return doubling(phi, [[2.0 * shift * x for x in row] for row in product(product(r, q), transpose(r))])


def first_of_sandwich(m, p):
    """(m p m')[0][0]."""
    return total(m[0][i] * p[i][j] * m[0][j] for i in range(len(p)) for j in range(len(p)))


def discrete_square(k, c):
    """The squared RMS of x1 on mbsopt's grid (trapezoidal weights), in closed form."""
    phi = step_map(k, c)
    p = discrete_lyapunov(phi, Q0)
    last = power(phi, STEPS)
    beyond = product(phi, last)
    squares = p[0][0] - first_of_sandwich(beyond, p)          # sum over n = 0 ... N of x1_n^2
    end = total(last[0][j] * Y0[j] for j in range(4))
    return DT * (squares - 0.5 * (Y0[0] * Y0[0] + end * end)) / END_TIME


def continuous_square(k, c):
    """(1/T) int_0^T x1^2 dt in continuous time, exactly."""
    a = system(k, c)
    q = continuous_lyapunov(a, Q0)
    e = expm([[x * END_TIME for x in row] for row in a])
    return (q[0][0] - first_of_sandwich(e, q)) / END_TIME


def infinite_square(k, c):
    """(1/T) int_0^inf x1^2 dt: the infinite horizon, over the same T so that it reads as an RMS."""
    return continuous_lyapunov(system(k, c), Q0)[0][0] / END_TIME


def newmark_square(k, c):
    """The squared RMS by a step-by-step trapezoidal Newmark loop (plain floats), for the check."""
    m = ((MACHINE + ABSORBER, ABSORBER), (ABSORBER, ABSORBER))
    damping = ((MOUNT_C, 0.0), (0.0, c))
    stiffness = ((MOUNT_K, 0.0), (0.0, k))

    def solve2(a, b):
        det = a[0][0] * a[1][1] - a[0][1] * a[1][0]
        return ((b[0] * a[1][1] - a[0][1] * b[1]) / det, (a[0][0] * b[1] - a[1][0] * b[0]) / det)

    def force(x, v):
        return tuple(-total(damping[i][j] * v[j] + stiffness[i][j] * x[j] for j in range(2)) for i in range(2))

    x, v = (Y0[0], Y0[1]), (Y0[2], Y0[3])
    a = solve2(m, force(x, v))
    iteration = tuple(tuple(m[i][j] + DT / 2 * damping[i][j] + DT * DT / 4 * stiffness[i][j] for j in range(2))
                      for i in range(2))
    square = 0.5 * x[0] ** 2
    for n in range(1, STEPS + 1):
        x_pred = tuple(x[i] + DT * v[i] + DT * DT / 4 * a[i] for i in range(2))
        v_pred = tuple(v[i] + DT / 2 * a[i] for i in range(2))
        a = solve2(iteration, force(x_pred, v_pred))
        x = tuple(x_pred[i] + DT * DT / 4 * a[i] for i in range(2))
        v = tuple(v_pred[i] + DT / 2 * a[i] for i in range(2))
        square += (0.5 if n == STEPS else 1.0) * x[0] ** 2
    return DT * square / END_TIME


def partial(f, x, j):
    """The exact derivative of f at x = (k, c) in variable j by the complex step."""
    delta = 1e-20 * abs(x[j])
    z = [complex(x[0]), complex(x[1])]
    z[j] = complex(x[j], delta)
    return f(z[0], z[1]).imag / delta


def gradient(f, x):
    return [partial(f, x, 0), partial(f, x, 1)]


def hessian(f, x):
    """Central differences of the exact gradient (symmetrised)."""
    h = [[0.0, 0.0], [0.0, 0.0]]
    for j in range(2):
        delta = 1e-5 * abs(x[j])
        up, down = [float(x[0]), float(x[1])], [float(x[0]), float(x[1])]
        up[j] += delta
        down[j] -= delta
        g_up, g_down = gradient(f, up), gradient(f, down)
        for i in range(2):
            h[i][j] = (g_up[i] - g_down[i]) / (2.0 * delta)
    return [[0.5 * (h[i][j] + h[j][i]) for j in range(2)] for i in range(2)]


def newton(f, x):
    """Newton's method on the gradient until its step is below 1e-13 relative."""
    x = [float(x[0]), float(x[1])]
    for steps in range(1, 21):
        dx = [-d for d in gauss(hessian(f, x), gradient(f, x))]
        x = [x[i] + dx[i] for i in range(2)]
        last = max(abs(dx[i]) / abs(x[i]) for i in range(2))
        if last < 1e-13:
            return x, steps, last
    raise SystemExit("Newton's method did not converge")


def nelder_mead(f, x0, lower, upper, xatol, fatol, maxiter, maxfev):
    """Nelder-Mead with its vertices clipped to the bounds: the algorithm, coefficients, initial
    simplex and stopping test of scipy.optimize.minimize(method="Nelder-Mead", bounds=...), whose
    sequence of operations this follows. The minimum and the number of evaluations."""
    n = len(x0)
    clip = lambda x: [min(max(x[i], lower[i]), upper[i]) for i in range(n)]
    x0 = clip(x0)
    sim = [x0[:]]
    for k in range(n):
        y = x0[:]
        y[k] = 1.05 * y[k] if y[k] != 0 else 0.00025
        sim.append(y)
    sim = [clip(x) for x in sim]
    calls = 0

    def func(x):
        nonlocal calls
        calls += 1
        return f(x)

    fsim = [func(x) for x in sim]

    def order():
        ranked = sorted(range(n + 1), key=fsim.__getitem__)     # stable, as numpy's argsort of so few
        return [sim[i] for i in ranked], [fsim[i] for i in ranked]

    sim, fsim = order()
    iterations = 1
    while calls < maxfev and iterations < maxiter:
        if (max(abs(sim[j][i] - sim[0][i]) for j in range(1, n + 1) for i in range(n)) <= xatol
                and max(abs(fsim[0] - fsim[j]) for j in range(1, n + 1)) <= fatol):
            break
        xbar = [total(sim[j][i] for j in range(n)) / n for i in range(n)]
        worst = sim[-1]
        xr = clip([2 * xbar[i] - 1 * worst[i] for i in range(n)])
        fxr = func(xr)
        shrink = False
        if fxr < fsim[0]:
            xe = clip([3 * xbar[i] - 2 * worst[i] for i in range(n)])
            fxe = func(xe)
            if fxe < fxr:
                sim[-1], fsim[-1] = xe, fxe
            else:
                sim[-1], fsim[-1] = xr, fxr
        elif fxr < fsim[-2]:
            sim[-1], fsim[-1] = xr, fxr
        else:
            if fxr < fsim[-1]:
                xc = clip([1.5 * xbar[i] - 0.5 * worst[i] for i in range(n)])
                fxc = func(xc)
                if fxc <= fxr:
                    sim[-1], fsim[-1] = xc, fxc
                else:
                    shrink = True
            else:
                xcc = clip([0.5 * xbar[i] + 0.5 * worst[i] for i in range(n)])
                fxcc = func(xcc)
                if fxcc < fsim[-1]:
                    sim[-1], fsim[-1] = xcc, fxcc
                else:
                    shrink = True
            if shrink:
                for j in range(1, n + 1):
                    sim[j] = clip([sim[0][i] + 0.5 * (sim[j][i] - sim[0][i]) for i in range(n)])
                    fsim[j] = func(sim[j])
        iterations += 1
        sim, fsim = order()
    return sim[0], calls


def brentq(f, xa, xb, xtol, rtol=4 * 2.220446049250313e-16, maxiter=200):
    """A root of f between xa and xb (f of opposite signs there) by Brent's method: scipy's brentq
    (scipy/optimize/Zeros/brentq.c), step for step."""
    xpre, xcur = xa, xb
    xblk = fblk = spre = scur = 0.0
    fpre, fcur = f(xpre), f(xcur)
    if fpre == 0.0:
        return xpre
    if fcur == 0.0:
        return xcur
    if math.copysign(1.0, fpre) == math.copysign(1.0, fcur):
        raise SystemExit("brentq: no sign change")
    for _ in range(maxiter):
        if fpre != 0.0 and fcur != 0.0 and math.copysign(1.0, fpre) != math.copysign(1.0, fcur):
            xblk, fblk = xpre, fpre
            spre = scur = xcur - xpre
        if abs(fblk) < abs(fcur):
            xpre, xcur, xblk = xcur, xblk, xcur
            fpre, fcur, fblk = fcur, fblk, fcur
        delta = (xtol + rtol * abs(xcur)) / 2
        sbis = (xblk - xcur) / 2
        if fcur == 0.0 or abs(sbis) < delta:
            return xcur
        if abs(spre) > delta and abs(fcur) < abs(fpre):
            if xpre == xblk:
                stry = -fcur * (xcur - xpre) / (fcur - fpre)          # interpolate
            else:
                dpre = (fpre - fcur) / (xpre - xcur)                   # extrapolate
                dblk = (fblk - fcur) / (xblk - xcur)
                stry = -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            if 2 * abs(stry) < min(abs(spre), 3 * abs(sbis) - delta):
                spre, scur = scur, stry                                # good short step
            else:
                spre = scur = sbis                                     # bisect
        else:
            spre = scur = sbis                                         # bisect
        xpre, fpre = xcur, fcur
        xcur += scur if abs(scur) > delta else (delta if sbis > 0 else -delta)
        fcur = f(xcur)
    raise SystemExit("brentq did not converge")


def positive_definite(h):
    return h[0][0] > 0.0 and h[0][0] * h[1][1] - h[0][1] * h[1][0] > 0.0


def minimum(f, start):
    """Nelder-Mead from start in the scaled variables, polished by Newton's method."""
    u, evaluations = nelder_mead(lambda u: f(u[0] * SCALES[0], u[1] * SCALES[1]),
                                 [start[0] / SCALES[0], start[1] / SCALES[1]],
                                 [K_LOWER / SCALES[0], C_LOWER / SCALES[1]], [K_UPPER / SCALES[0], C_UPPER / SCALES[1]],
                                 xatol=1e-10, fatol=0.0, maxiter=5000, maxfev=10000)
    x, steps, last = newton(f, [u[0] * SCALES[0], u[1] * SCALES[1]])
    if not (K_LOWER < x[0] < K_UPPER and C_LOWER < x[1] < C_UPPER) or not positive_definite(hessian(f, x)):
        raise SystemExit("the minimum is not an interior one")
    return x, {"nelder_mead_evaluations": evaluations, "steps": steps, "last_step_relative": last}


def profile(f, i, t, x):
    """min over the other variable of f with variable i at t (Newton's method from x's)."""
    j = 1 - i
    y = float(x[j])

    def derivative(y, step=0.0):
        point = [0.0, 0.0]
        point[i] = t
        point[j] = y + step
        return partial(f, point, j)

    for _ in range(50):
        delta = 1e-5 * abs(y)
        dy = -derivative(y) / ((derivative(y, delta) - derivative(y, -delta)) / (2.0 * delta))
        y += dy
        if abs(dy) < 1e-13 * abs(y):
            break
    point = [0.0, 0.0]
    point[i], point[j] = t, y
    return f(*point)


def design_range(f, x, optimal):
    """The extent of {RMS <= optimal RMS (1 + band)} along each variable: where the profile of the
    squared RMS meets that level on each side, bracketed from the quadratic model."""
    level = optimal ** 2 * (1.0 + DESIGN_COST_BAND) ** 2
    h = hessian(f, x)
    det = h[0][0] * h[1][1] - h[0][1] * h[1][0]
    inverse_diagonal = (h[1][1] / det, h[0][0] / det)
    ranges = []
    for i in range(2):
        guess = math.sqrt(2.0 * (level - optimal ** 2) * inverse_diagonal[i])

        def excess(t):
            return profile(f, i, t, x) - level

        ends = []
        for side in (-1.0, 1.0):
            far = x[i] + side * 2.0 * guess
            if not excess(far) > 0.0:
                raise SystemExit("the band's level is not bracketed")
            ends.append(brentq(excess, float(x[i]), far, xtol=1e-14 * abs(x[i])))
        ranges.append(sorted(ends))
    return ranges


def warburton():
    mu = ABSORBER / MACHINE
    w1 = math.sqrt(MOUNT_K / MACHINE)
    f = math.sqrt(1.0 + mu / 2.0) / (1.0 + mu)
    zeta = math.sqrt(mu * (1.0 + 3.0 * mu / 4.0) / (4.0 * (1.0 + mu) * (1.0 + mu / 2.0)))
    return f, zeta, ABSORBER * (f * w1) ** 2, 2.0 * zeta * ABSORBER * f * w1


def main():
    # The scan: no design of the box is lower, and its best is not on a bound.
    ks = [K_LOWER + (K_UPPER - K_LOWER) * i / 9 for i in range(10)]
    cs = [C_LOWER + (C_UPPER - C_LOWER) * i / 9 for i in range(10)]
    scan = [[discrete_square(k, c) for c in cs] for k in ks]

    x, convergence = minimum(discrete_square, [K_START, C_START])
    optimal = math.sqrt(discrete_square(*x))
    if min(min(row) for row in scan) < optimal ** 2:
        raise SystemExit("the scan found a lower design")

    f, zeta, k_w, c_w = warburton()
    again = newton(discrete_square, [k_w, c_w])[0]
    infinite, _ = minimum(infinite_square, [K_START, C_START])
    finite, _ = minimum(continuous_square, [K_START, C_START])
    a = system(*finite)
    e = expm([[v * END_TIME for v in row] for row in a])
    q = continuous_lyapunov(a, Q0)
    tail = first_of_sandwich(e, q) / q[0][0]

    closed, loop = math.sqrt(discrete_square(K_START, C_START)), math.sqrt(newmark_square(K_START, C_START))
    phi, a_start = step_map(K_START, C_START), system(K_START, C_START)
    p_own, p_doubling = discrete_lyapunov(phi, Q0), doubling(phi, Q0)
    c_own, c_doubling = continuous_lyapunov(a_start, Q0), continuous_doubling(a_start, Q0, math.sqrt(MOUNT_K / MACHINE))

    k_range, c_range = design_range(discrete_square, x, optimal)
    reference = {
        "problem": "tuned_mass_damper",
        "scene": "problems/suite/tuned_mass_damper.yaml",
        "command": "python3 scripts/reference/tuned_mass_damper.py > problems/suite/tuned_mass_damper.reference.json",
        "method": "mbsopt's discrete problem in closed form: the trapezoidal Newmark map of the linear two-mass "
                  "model on mbsopt's grid, the sum of the states' squares from its discrete Lyapunov equation, "
                  "the trapezoidal RMS; minimised by Nelder-Mead and Newton's method on complex-step gradients; "
                  "Warburton's H2 optimum and the continuous-time optimum (Lyapunov equation, matrix exponential) "
                  "as checks of the problem",
        # The scene's numbers this computation assumes, by their dotted names (mbsopt parameters).
        "data": {"machine_mass.mass": MACHINE, "absorber_mass.mass": ABSORBER, "mount.k": MOUNT_K,
                 "mount.c": MOUNT_C, "machine.v0": MACHINE_V0, "absorber.v0": ABSORBER_V0,
                 "tmd.k": K_START, "tmd.c": C_START,
                 "design.variables.0.lower": K_LOWER, "design.variables.0.upper": K_UPPER,
                 "design.variables.1.lower": C_LOWER, "design.variables.1.upper": C_UPPER,
                 "settings.end_time": END_TIME, "settings.step": STEP},
        "optimum": {
            "design": {"tmd.k": x[0], "tmd.c": x[1]},
            "responses": {"rms_x1": optimal},
            "grid": {"steps": STEPS, "step": DT},
            "newton": dict(convergence, from_warburton_relative=max(abs(again[i] - x[i]) / abs(x[i]) for i in range(2))),
            "start": {"tmd.k": K_START, "tmd.c": C_START, "rms_x1": closed,
                      "continuous_rms_x1": math.sqrt(continuous_square(K_START, C_START))},
            "warburton": {
                "f": f, "zeta": zeta, "tmd.k": k_w, "tmd.c": c_w,
                "rms_x1": math.sqrt(discrete_square(k_w, c_w)),
                "continuous_rms_x1": math.sqrt(continuous_square(k_w, c_w)),
                "infinite_horizon_minimum": {"tmd.k": infinite[0], "tmd.c": infinite[1],
                                             "rms_x1": math.sqrt(infinite_square(*infinite))},
            },
            "continuous_finite_horizon": {
                "tmd.k": finite[0], "tmd.c": finite[1],
                "rms_x1": math.sqrt(continuous_square(*finite)),
                "discrete_rms_x1": math.sqrt(discrete_square(*finite)),
                "tail_fraction": tail,
            },
            "cost_on_a_scan": {"tmd.k": ks, "tmd.c": cs, "rms_x1": [[math.sqrt(s) for s in row] for row in scan]},
        },
        "check": {
            "tmd.k": K_START, "tmd.c": C_START,
            "rms_x1_closed_form": closed, "rms_x1_newmark_loop": loop,
            "relative_difference": abs(closed - loop) / loop,
            "doubling_discrete_lyapunov_relative": largest(combine(1.0, p_own, -1.0, p_doubling)) / largest(p_doubling),
            "doubling_continuous_lyapunov_relative": largest(combine(1.0, c_own, -1.0, c_doubling)) / largest(c_doubling),
        },
        "accuracy": {
            "cost_relative": 1e-9,
            "design_cost_band": DESIGN_COST_BAND,
            "design_range": {"tmd.k": k_range, "tmd.c": c_range},
        },
    }
    print(json.dumps(reference, indent=2))


if __name__ == "__main__":
    main()
