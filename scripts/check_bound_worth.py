#!/usr/bin/env python3
"""Checks what `mbsopt optimize` says relaxing each active bound is worth against re-optimisation.

At a converged optimum, `mbsopt optimize` states, for every active constraint and bound, the
derivative of the optimal cost in that bound, from the optimizer's multipliers (result.json's
`bound_worth`). This script moves each such bound both ways and optimizes again from the same
start with the same optimizer, gradients and formulation: the central difference of the optimal
cost, CD(d) = (cost(B + d) - cost(B - d)) / 2d, is an independent measurement of that derivative.

Each re-optimised cost is first moved onto its constraints' bounds: an optimizer ends anywhere
within a constraint's tolerance, beyond the bound by up to it, where the cost is lower by the
derivative times the excess (up to tolerance_worth, what the tolerances are worth, which over 2d
would swamp a small derivative); the run's own stated derivative moves it back to first order.

How accurate the measurement is: CD(d) - CD(d/2) is 3/4 of CD(d)'s truncation error (c d^2) plus
the runs' remaining noise, which at d/2 weighs twice what it does at d; 4/3 |CD(d) - CD(d/2)| bounds
both. How accurate the stated figure is: it is the exact derivative of the problem on its time
grid at the reported point, where an extreme is read at one grid point; as the design moves, that
point moves along the grid, and the derivative with it (by 1e-4 to 1e-3 relative on a 1 ms grid,
falling with the step). The re-optimised runs at B - d, B - d/2, B + d/2, B + d state their own
derivatives: the line through them gives the derivative's smooth trend, and the stated figure's
accuracy is its distance from that trend at B plus the four's largest distance from their line (a
wrong figure, a unit or a sign, would be wrong at the neighbours too, and fail). The check passes
where the stated and the measured figures agree within the sum of the two.

Writes OUT/bound_worth.json and OUT/bound_worth.md (a table of stated against measured, with the
accuracy and the verdict) and exits 1 when a check fails. Uses the Release build unless --mbsopt names another.

    scripts/check_bound_worth.py tramway --out results/bound-worth/tramway
    scripts/check_bound_worth.py problems/suite/quarter_car.yaml --optimizer slsqp --out results/bound-worth/quarter_car
"""
import argparse
import json
import math
import os
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RELEASE = os.path.join(ROOT, "build", "release", "app", "mbsopt")
MBSOPT = RELEASE


def parameters(problem):
    """Every number of the scene by its dotted name, SI units (`mbsopt parameters`)."""
    listing = subprocess.run([MBSOPT, "parameters", problem], capture_output=True, text=True, check=True).stdout
    values = {}
    for line in listing.splitlines():
        name, value = line.split()[:2]
        values[name] = float(value)
    return values


def optimize(problem, choice, sets, directory, label):
    """The JSON record of `mbsopt optimize` with the overrides `sets` (name -> SI value)."""
    path = os.path.join(directory, label + ".json")
    command = [MBSOPT, "optimize", problem, "--json", path, "--jobs", "1", *choice]
    for name, value in sets.items():
        command += ["--set", "%s=%.17g" % (name, value)]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode not in (0, 2) or not os.path.exists(path):
        raise SystemExit("%s failed:\n%s" % (" ".join(command), run.stderr))
    with open(path) as f:
        record = json.load(f)
    if record["status"] != "converged":
        raise SystemExit("%s: %s (%s); the check needs converged runs" % (label, record["status"], record["message"]))
    return record


def cost(record):
    return record["cost_functional"]["final"]


def stated(record, worth):
    """The record's stated derivative for the bound `worth` names (None where it is not active there)."""
    for w in record["bound_worth"]:
        if w["parameter"] == worth["parameter"]:
            return w["d_cost_d_bound"]
    return None


def trend_distance(at_bound, neighbours):
    """How far the value at 0 lies from the least-squares line through the (x, y) neighbours, plus
    their own largest distance from it."""
    n = len(neighbours)
    mx = sum(x for x, _ in neighbours) / n
    my = sum(y for _, y in neighbours) / n
    sxx = sum((x - mx) ** 2 for x, _ in neighbours)
    slope = sum((x - mx) * (y - my) for x, y in neighbours) / sxx
    line = lambda x: my + slope * (x - mx)
    return abs(at_bound - line(0.0)) + max(abs(y - line(x)) for x, y in neighbours)


def cost_at_bounds(record):
    """The optimal cost of a run moved onto its constraints' bounds: a converged point may lie beyond
    an active bound by up to its tolerance, where the cost is lower by the derivative times that. Each
    run's own stated derivative moves it back (first order; its error is that derivative's error
    times the excess, far below the difference measured)."""
    value = cost(record)
    verdicts = {v["name"]: v for v in record["constraints"]}
    for worth in record["bound_worth"]:
        v = verdicts.get(worth["name"])
        if worth["kind"] != "constraint" or v is None:
            continue
        bound = v.get("bound", v.get("equals"))
        value -= worth["d_cost_d_bound"] * (v["value"] - bound)  # the bound it met is value; move it to bound
    return value


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("problem", help="a scene with a design section, or a built-in name (tramway)")
    parser.add_argument("--optimizer", default="sdcc")
    parser.add_argument("--formulation", default="", help="default: the problem's own")
    parser.add_argument("--relative-step", type=float, default=0.01,
                        help="d: each bound moves by this fraction of itself (of its variable's scale where it is 0), "
                             "then by half of it")
    parser.add_argument("--set", action="append", default=[], metavar="NAME=VALUE",
                        help="a number of the scene for every run (as mbsopt's --set), e.g. settings.step=2.5e-4")
    parser.add_argument("--out", required=True, help="directory for bound_worth.json and bound_worth.md")
    parser.add_argument("--mbsopt", default=RELEASE, help="the mbsopt program (default: the Release build's)")
    args = parser.parse_args()
    global MBSOPT
    MBSOPT = args.mbsopt
    if not os.access(MBSOPT, os.X_OK):
        raise SystemExit("%s is not built (cmake --build --preset release)" % MBSOPT)
    os.makedirs(args.out, exist_ok=True)
    choice = ["--optimizer", args.optimizer] + (["--formulation", args.formulation] if args.formulation else [])
    for setting in args.set:
        choice += ["--set", setting]
    numbers = parameters(args.problem)
    with tempfile.TemporaryDirectory() as scratch:
        nominal = optimize(args.problem, choice, {}, scratch, "nominal")
        if not nominal["bound_worth"]:
            raise SystemExit("the optimum states no active bound: nothing to check")
        rows = []
        for worth in nominal["bound_worth"]:
            name = worth["parameter"]
            bound = numbers[name]
            prefix = name.rsplit(".", 1)[0]
            scale = abs(bound) if bound != 0.0 else numbers.get(prefix + ".scale", 1.0)
            step = args.relative_step * scale
            # The stated derivative is per reported unit (deg for an angle); the bound moves in SI.
            unit = math.pi / 180.0 if worth["unit"] == "deg" else 1.0
            differences, along = [], []
            for d in (step, step / 2):
                up = optimize(args.problem, choice, {name: bound + d}, scratch, "%s=%.10g" % (name, bound + d))
                down = optimize(args.problem, choice, {name: bound - d}, scratch, "%s=%.10g" % (name, bound - d))
                differences.append((cost_at_bounds(up) - cost_at_bounds(down)) / (2 * d / unit))
                along += [(s * d, stated(r, worth)) for s, r in ((1, up), (-1, down)) if stated(r, worth) is not None]
            stated_value = worth["d_cost_d_bound"]
            measured = differences[0]
            measurement_accuracy = 4.0 / 3.0 * abs(differences[0] - differences[1])
            # Where the bound is not active at all four neighbours, there is no trend to read.
            stated_accuracy = trend_distance(stated_value, along) if len(along) == 4 else 0.0
            accuracy = measurement_accuracy + stated_accuracy
            rows.append({"bound": worth["name"], "kind": worth["kind"], "parameter": name, "unit": worth["unit"],
                         "value": worth["bound"], "stated": stated_value, "stated_at_the_neighbours": along,
                         "stated_accuracy": stated_accuracy, "central_differences": differences,
                         "steps_si": [step, step / 2], "measured": measured,
                         "measurement_accuracy": measurement_accuracy, "accuracy": accuracy,
                         "agrees": abs(stated_value - measured) <= accuracy})
    record = {"problem": args.problem, "command": " ".join(sys.argv), "optimizer": args.optimizer,
              "formulation": nominal["formulation"], "cost": nominal["cost_functional"],
              "tolerance_worth": nominal["tolerance_worth"], "checks": rows,
              "units": "stated, measured, accuracy: the optimal cost's change (cost_functional.unit) per unit of the "
                       "bound (unit; SI for a design variable's bound)"}
    with open(os.path.join(args.out, "bound_worth.json"), "w") as f:
        json.dump(record, f, indent=2)
        f.write("\n")
    cost_unit = nominal["cost_functional"]["unit"]
    lines = ["# What relaxing each active bound is worth: %s, %s on %s" % (args.problem, args.optimizer, nominal["formulation"]),
             "",
             "`%s`" % " ".join(["scripts/check_bound_worth.py"] + sys.argv[1:]),
             "",
             "Optimal %s = %.8g %s. Derivatives of the optimal cost in each bound, %s per unit of the bound: stated "
             "by the optimizer's multipliers, measured by re-optimisation (the central difference over ±d, d = %g of "
             "the bound, its accuracy from the difference over ±d/2); the script's docstring says how each accuracy "
             "is estimated." % (nominal["cost_functional"]["name"], cost(nominal), cost_unit, cost_unit, args.relative_step),
             "",
             "| bound | kind | value | stated | its accuracy | measured | its accuracy | agrees |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        value = "%.8g" % r["value"] + ("" if r["unit"] in ("", "SI") else " " + r["unit"])
        lines.append("| %s | %s | %s | %.6g | %.2g | %.6g | %.2g | %s |" % (
            r["bound"], r["kind"].replace("_", " "), value, r["stated"], r["stated_accuracy"], r["measured"],
            r["measurement_accuracy"], "yes" if r["agrees"] else "NO"))
    with open(os.path.join(args.out, "bound_worth.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0 if all(r["agrees"] for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
