#!/usr/bin/env python3
"""The expected wall time of a `mbsopt benchmark` sweep on N workers (threads or MPI worker ranks).

Reads OUT/summary.csv (one row per run, with its measured wall time) and replays the sweep's
dynamic dispatch: the runs in the command's order (Ipopt's first, then the rest), each handed to
whichever worker falls idle first. The makespan on N workers is then at least the longest run and at
least the total over N; the model assumes each run keeps its measured time (no shared memory
bandwidth or turbo effects) and adds `--overhead` seconds per run for starting it and writing its
record. Usage: scripts/benchmark_scaling.py results/benchmark [--overhead 0.01]
"""
import argparse
import csv
import heapq
import os


def makespan(times, workers):
    idle = [0.0] * workers
    heapq.heapify(idle)
    for t in times:
        heapq.heappush(idle, heapq.heappop(idle) + t)
    return max(idle)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("out", help="the sweep's directory (its summary.csv)")
    parser.add_argument("--overhead", type=float, default=0.01, help="seconds per run beyond its wall time")
    args = parser.parse_args()
    with open(os.path.join(args.out, "summary.csv"), newline="") as f:
        rows = [r for r in csv.DictReader(f) if r["wall_time_s"]]
    ipopt_first = [r for r in rows if r["optimizer"] == "ipopt"] + [r for r in rows if r["optimizer"] != "ipopt"]
    times = [float(r["wall_time_s"]) + args.overhead for r in ipopt_first]
    serial = sum(times)
    print(f"{len(times)} runs, {serial:.1f} s in all, the longest {max(times):.1f} s")
    print("workers  expected wall time [s]  speed-up  efficiency")
    for n in (1, 2, 4, 8, 16, 32, 64, 128):
        t = makespan(times, n)
        print(f"{n:7d}  {t:22.1f}  {serial / t:8.2f}  {serial / t / n:10.2f}")


if __name__ == "__main__":
    main()
