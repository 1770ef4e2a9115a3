#!/usr/bin/env python3
"""Runs driven by accuracy on the hard cases, each against its independent reference.

    scripts/hard_cases/check_accuracy.py [--mbsopt BINARY] [--scenes a,b] [--tolerances 1e-3,1e-5]
                                         [--t-end T] [--integrator NAME] [--out FILE.json]

For every scene of problems/scenes/hard/ (or --scenes) and every tolerance, runs
`mbsopt simulate SCENE --integrator NAME --accuracy TOL --output-step DT` (NAME: extrapolation unless
--integrator says; DT: the reference's spacing) and compares,
sensor by sensor, the largest true error at the reference's times with the largest error the run
estimated for that sensor. A run passes when

  - the estimate holds: true / estimated is at most RATIO_LIMIT and at least 1 / RATIO_LIMIT wherever the
    true error is above the floor of the comparison (FLOOR: the references' own accuracy, 1e-9, and the
    few ulps the CSV's 17 digits carry), and
  - the true error is below the tolerance (absolute, in the coordinates' units) with the safety factor
    SAFETY, measured on the reference's sensors (positions of points 1 m or more from their joints):
    |e| <= SAFETY * TOL * (1 + |y|).

Standard library only. Exit status 1 when a run fails either check, 2 on an error.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
HARD = os.path.join(ROOT, "problems", "scenes", "hard")
RATIO_LIMIT = 10.0  # a run driven by accuracy is within 10x of its estimate
SAFETY = 2.0        # docs/integrators.md: runs are accepted at half the tolerance; the estimate is within 2x
FLOOR = 1e-9        # below this the reference (DOP853 at 1e-13, published values to 1e-14) and round-off decide


def read_csv(path):
    """The column names (without the " [unit]" of mbsopt's headers) and the rows."""
    with open(path) as f:
        rows = list(csv.reader(f))
    header = [name.split(" [")[0] for name in rows[0]]
    return header, [[float(v) for v in row] for row in rows[1:]]


def reference_step(times):
    if len(times) < 2:
        return times[0]
    return times[1] - times[0]


def run(mbsopt, scene, tolerance, t_end, integrator):
    header, reference = read_csv(os.path.join(HARD, "reference", scene + ".csv"))
    times = [row[0] for row in reference if t_end is None or row[0] <= t_end + 1e-12]
    step = reference_step(times)
    with tempfile.TemporaryDirectory() as tmp:
        out_csv, out_json = os.path.join(tmp, "run.csv"), os.path.join(tmp, "run.json")
        command = [mbsopt, "simulate", os.path.join(HARD, scene + ".yaml"), "--integrator", integrator,
                   "--accuracy", repr(tolerance),
                   "--output-step", repr(step), "--out", out_csv, "--json", out_json]
        if t_end is not None:
            command += ["--t-end", repr(t_end)]
        done = subprocess.run(command, capture_output=True, text=True)
        if done.returncode != 0:
            return {"scene": scene, "tolerance": tolerance, "failed": done.stderr.strip() or done.stdout.strip()}
        run_header, rows = read_csv(out_csv)
        summary = json.load(open(out_json))
    by_time = {round(row[0] / step): row for row in rows}
    estimated = {s["name"]: s["estimated_error"] for s in summary["sensors"]}
    sensors = []
    for column, name in enumerate(header[1:], start=1):
        at = run_header.index(name)
        worst, scale = 0.0, 0.0
        for row in reference:
            if row[0] not in times:
                continue
            mine = by_time[round(row[0] / step)]
            worst = max(worst, abs(mine[at] - row[column]))
            scale = max(scale, abs(row[column]))
        sensors.append({"sensor": name, "true": worst, "estimated": estimated[name], "scale": scale})
    return {"scene": scene, "tolerance": tolerance, "sensors": sensors, "steps": summary["steps"],
            "order": summary["order"], "macro_step": summary.get("macro_step"),
            "wall_time_s": summary["wall_time_s"]}


def verdict(result):
    if "failed" in result:
        return ["the run failed: " + result["failed"]]
    problems = []
    tolerance = result["tolerance"]
    for s in result["sensors"]:
        true, estimated = s["true"], s["estimated"]
        if true > SAFETY * tolerance * (1.0 + s["scale"]):
            problems.append(f"{s['sensor']}: true error {true:.2g} above {SAFETY} x the tolerance")
        if true > FLOOR and not (estimated * RATIO_LIMIT >= true and true * RATIO_LIMIT >= estimated):
            problems.append(f"{s['sensor']}: true error {true:.2g} and estimate {estimated:.2g} are more than "
                            f"{RATIO_LIMIT:g}x apart")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--mbsopt", default=os.path.join(ROOT, "build", "release", "app", "mbsopt"))
    parser.add_argument("--scenes", default="andrews_squeezer,n_four_bar_2_flat,n_four_bar_a02,"
                                            "n_four_bar_a02_flat,pendulum_a01")
    parser.add_argument("--tolerances", default="1e-3,1e-4,1e-5,1e-6,1e-7,1e-8")
    parser.add_argument("--t-end", type=float, default=None, help="simulate only up to T (a shorter check)")
    parser.add_argument("--integrator", default="extrapolation", help="extrapolation, newmark or adaptive")
    parser.add_argument("--out", help="write every result as JSON")
    args = parser.parse_args()
    results, failed = [], 0
    print("| scene | tolerance | sensor | true error | estimated | true/estimated | steps | order | wall [s] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for scene in args.scenes.split(","):
        for tolerance in (float(t) for t in args.tolerances.split(",")):
            result = run(args.mbsopt, scene, tolerance, args.t_end, args.integrator)
            result["problems"] = verdict(result)
            results.append(result)
            failed += bool(result["problems"])
            if "failed" in result:
                print(f"| {scene} | {tolerance:g} | — | failed | | | | | |")
            else:
                worst = max(result["sensors"], key=lambda s: s["true"])
                ratio = worst["true"] / worst["estimated"] if worst["estimated"] > 0 else float("inf")
                print(f"| {scene} | {tolerance:g} | {worst['sensor']} | {worst['true']:.2g} | "
                      f"{worst['estimated']:.2g} | {ratio:.2f} | {result['steps']} | {result['order']} | "
                      f"{result['wall_time_s']:.3g} |")
            for problem in result["problems"]:
                print(f"  FAIL {scene} at {tolerance:g}: {problem}", file=sys.stderr)
            sys.stdout.flush()
    if args.out:
        with open(args.out, "w") as f:
            json.dump({"ratio_limit": RATIO_LIMIT, "safety": SAFETY, "floor": FLOOR, "results": results}, f, indent=1)
    print(f"{len(results) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (OSError, ValueError, KeyError) as error:
        print(f"check_accuracy.py: {error}", file=sys.stderr)
        sys.exit(2)
