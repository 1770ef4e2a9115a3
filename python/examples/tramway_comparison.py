#!/usr/bin/env python3
"""The tramway comparison from Python: every optimizer on the grid maximum with adjoint gradients,
a table of their results and a plot of the cost's own functional (max |a_lat|) against the budget
spent (simulation-equivalents), with matplotlib. Run from the repository after the build:

    PYTHONPATH=build/release/python python3 python/examples/tramway_comparison.py [--out tramway_comparison.png]
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files, no display
import matplotlib.pyplot as plt

import mbsopt


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="tramway_comparison.png", help="the figure (PNG)")
    args = parser.parse_args()
    print(f"mbsopt {mbsopt.__version__}")
    print(f"{'optimizer':10} {'status':15} {'max |a_lat| [m/s²]':>20} {'sim.-equivalents':>17} {'feasible':>9}")
    figure, axis = plt.subplots(figsize=(8, 5))
    for optimizer in mbsopt.optimizers():
        run = mbsopt.optimize("tramway", optimizer=optimizer, formulation="grid_max")
        cost = run["cost_functional"]
        print(f"{optimizer:10} {run['status']:15} {cost['final']:20.6f} {run['simulation_equivalents']:17.0f} "
              f"{'yes' if run['feasible'] else 'no':>9}")
        points = [(h["simulation_equivalents"], h["cost_functional"]) for h in run["history"]
                  if h["cost_functional"] is not None]
        axis.plot(*zip(*points), marker="o", markersize=3, label=optimizer)
    axis.set_xlabel("simulation-equivalents")
    axis.set_ylabel(f"{cost['name']} [{cost['unit']}]")
    axis.set_title("tramway, grid maximum, adjoint gradients")
    axis.grid(True)
    axis.legend()
    figure.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
