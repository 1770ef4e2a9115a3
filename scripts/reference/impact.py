"""What the reference scripts of problems/suite/ share: a body of mass m arriving at speed v0 on a
linear spring-damper (k, c), the closed-form response of m x'' + c x' + k x = 0 with x(0) = 0,
x'(0) = v0 and its peaks over [0, T]; the same oscillation about an offset equilibrium; the peak of
any smooth function over an interval; and the one-dimensional searches. Standard library only."""
import math

GOLDEN = (math.sqrt(5.0) - 1.0) / 2.0


class Impact:
    def __init__(self, mass, speed, end_time):
        self.mass, self.speed, self.end_time = mass, speed, end_time

    def response(self, k, c, t):
        """x, x', x'' at time t (under-, critically or over-damped)."""
        m, v0 = self.mass, self.speed
        omega = math.sqrt(k / m)
        zeta = c / (2.0 * math.sqrt(k * m))
        sigma = zeta * omega
        if zeta < 1.0:
            omega_d = omega * math.sqrt(1.0 - zeta * zeta)
            decay = math.exp(-sigma * t)
            s, co = math.sin(omega_d * t), math.cos(omega_d * t)
            x = v0 / omega_d * decay * s
            v = v0 * decay * (co - sigma / omega_d * s)
        elif zeta == 1.0:
            decay = math.exp(-omega * t)
            x = v0 * t * decay
            v = v0 * decay * (1.0 - omega * t)
        else:
            root = omega * math.sqrt(zeta * zeta - 1.0)
            r1, r2 = -sigma + root, -sigma - root
            e1, e2 = math.exp(r1 * t), math.exp(r2 * t)
            x = v0 * (e1 - e2) / (r1 - r2)
            v = v0 * (r1 * e1 - r2 * e2) / (r1 - r2)
        return x, v, -(k * x + c * v) / m

    def peak(self, f, start=0.0, samples=1000):
        """max over [start, end_time] of |f(t)|."""
        return peak_of(f, start, self.end_time, samples)

    def peaks(self, k, c):
        """(max |x|, max |x''|) over [0, end_time]."""
        return (self.peak(lambda t: self.response(k, c, t)[0]), self.peak(lambda t: self.response(k, c, t)[2]))


def released(offset, sigma, omega_d, speed, t):
    """x(t) of x'' + 2 sigma x' + omega^2 (x - offset) = 0 (under-damped, omega_d^2 = omega^2 -
    sigma^2) from x(0) = 0, x'(0) = speed: offset + exp(-sigma t) (A cos(omega_d t) + B sin(omega_d t))
    with A = -offset, B = (speed - sigma offset) / omega_d."""
    a, b = -offset, (speed - sigma * offset) / omega_d
    return offset + math.exp(-sigma * t) * (a * math.cos(omega_d * t) + b * math.sin(omega_d * t))


def largest_of(f, start, end, samples=1000):
    """max over [start, end] of f(t): the largest sample, refined between its neighbours by
    golden-section search (f smooth near its maximum, its samples dense enough to bracket it)."""
    times = [start + (end - start) * i / samples for i in range(samples + 1)]
    values = [f(t) for t in times]
    i = max(range(samples + 1), key=values.__getitem__)
    return golden_max(f, times[max(i - 1, 0)], times[min(i + 1, samples)])


def peak_of(f, start, end, samples=1000):
    """max over [start, end] of |f(t)|."""
    return largest_of(lambda t: abs(f(t)), start, end, samples)


def golden_argmax(f, lo, hi, iterations):
    """The point of [lo, hi] where f, unimodal there, is largest, by golden-section search."""
    a, b = lo, hi
    for _ in range(iterations):
        c1, c2 = b - GOLDEN * (b - a), a + GOLDEN * (b - a)
        if f(c1) > f(c2):
            b = c2
        else:
            a = c1
    return 0.5 * (a + b)


def golden_max(f, lo, hi):
    """max of f on [lo, hi] for f unimodal there."""
    return max(f(golden_argmax(f, lo, hi, 80)), f(lo), f(hi))


def minimise(f, lo, hi):
    """The point of [lo, hi] where f, unimodal there, is smallest."""
    return golden_argmax(lambda z: -f(z), lo, hi, 60)


def crossing(f, level, inside, outside, iterations=50):
    """The point between inside (f < level) and outside (f > level) where f = level, by bisection."""
    for _ in range(iterations):
        middle = 0.5 * (inside + outside)
        if f(middle) < level:
            inside = middle
        else:
            outside = middle
    return 0.5 * (inside + outside)


def sampled_peak_error(omega, step):
    """Bound on the relative difference between a peak of a response of frequency omega and its
    maximum over a time grid of the given step, Newmark's (average acceleration) period error
    (omega step)^2 / 12 included: (omega step)^2 / 8."""
    return (omega * step) ** 2 / 8.0
