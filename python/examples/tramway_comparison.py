#!/usr/bin/env python3
"""The tramway comparison from Python: every optimizer on the paper's formulation (the integral of
the violations, positive_part) and on the grid maximum, with adjoint gradients; a table of their
results and, per formulation, a plot of the cost's own functional (max |a_lat|) against the budget
spent (simulation-equivalents), with matplotlib. Run from the repository after the build:

    python3 python/examples/tramway_comparison.py [--optimizers sdcc,slsqp] [--out tramway_comparison.png]

(after scripts/main.sh, which registers the module with python3; otherwise prefix the command with
PYTHONPATH=build/release/python). The runs that converge feasible reach the optimum, 2.18936 m/s²
(README, "Optimising the tramway"); MMA and CCSAQ do not move on the paper's formulation.
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files, no display
import matplotlib.pyplot as plt

import mbsopt
import numpy

TITLES = {"positive_part": "∫⟨φ⟩dt (the paper's)", "grid_max": "max over the time grid"}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--optimizers", default=",".join(mbsopt.optimizers()),
                        help="comma-separated, of " + ", ".join(mbsopt.optimizers()) + " (default: all)")
    parser.add_argument("--formulations", default="positive_part,grid_max",
                        help="comma-separated, of " + ", ".join(mbsopt.formulations()))
    parser.add_argument("--out", default="tramway_comparison.png", help="the figure (PNG)")
    args = parser.parse_args()
    formulations = args.formulations.split(",")
    print(f"mbsopt {mbsopt.__version__}")
    print(f"{'formulation':14} {'optimizer':10} {'status':10} {'max |a_lat| [m/s²]':>19} "
          f"{'sim.-equivalents':>17} {'feasible':>9}")
    figure, axes = plt.subplots(1, len(formulations), figsize=(7 * len(formulations), 5), squeeze=False)
    for formulation, axis in zip(formulations, axes[0]):
        for optimizer in args.optimizers.split(","):
            run = mbsopt.optimize("tramway", optimizer=optimizer, formulation=formulation)
            print(f"{formulation:14} {optimizer:10} {run.status.name:10} {run.cost_functional:19.6f} "
                  f"{run.simulation_equivalents:17.0f} {'yes' if run.feasible else 'no':>9}")
            known = ~numpy.isnan(run.history.cost_functional)  # records that say which point they were
            axis.plot(run.history.simulation_equivalents[known], run.history.cost_functional[known], marker="o",
                      markersize=3, label=f"{optimizer} ({run.status.name})")
        axis.set_xlabel("simulation-equivalents")
        axis.set_ylabel(f"{run.cost_name} [{run.cost_unit}]")
        axis.set_title(f"tramway, {TITLES.get(formulation, formulation)}, adjoint gradients")
        axis.grid(True)
        axis.legend()
    figure.tight_layout()
    figure.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
