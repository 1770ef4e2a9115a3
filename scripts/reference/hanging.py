"""The hanging body of problems/suite/spring_preload.yaml and spring_floor.yaml: 100 kg on a
vertical spring-damper (10 kN/m, 200 N·s/m) under gravity, struck upwards at 1 m/s from x = 0; its
travel for a spring rest position r in closed form, and its extremes over [0, T]. Standard library
only."""
import math

from impact import largest_of, released

MASS = 100.0           # kg       body.mass
STIFFNESS = 1.0e4      # N/m      hanger.k
DAMPING = 200.0        # N s/m    hanger.c
GRAVITY = 9.81         # m/s^2    -gravity.x (the axis points up)
SPEED = 1.0            # m/s      lift.v0 (from lift.q0 = 0)
END_TIME = 2.0         # s        settings.end_time
STEP = 1.0e-3          # s        settings.step (for the discretisation estimate only)
SAMPLES = 2000

OMEGA = math.sqrt(STIFFNESS / MASS)
SIGMA = DAMPING / (2.0 * MASS)
OMEGA_D = math.sqrt(OMEGA * OMEGA - SIGMA * SIGMA)
SAG = MASS * GRAVITY / STIFFNESS  # the static position's offset below the spring's rest

# The scene's numbers these computations assume, by their dotted names (mbsopt parameters).
DATA = {"body.mass": MASS, "hanger.k": STIFFNESS, "hanger.c": DAMPING, "gravity.x": -GRAVITY, "lift.q0": 0.0,
        "lift.v0": SPEED, "settings.end_time": END_TIME, "settings.step": STEP}


def travel(rest, t):
    return released(rest - SAG, SIGMA, OMEGA_D, SPEED, t)


def extreme(rest, sign):
    """max over [0, T] of sign * x(t): the highest point (sign = +1) or minus the lowest (-1), at
    least 0 (x(0) = 0)."""
    return largest_of(lambda t: max(0.0, sign * travel(rest, t)), 0.0, END_TIME, SAMPLES)
