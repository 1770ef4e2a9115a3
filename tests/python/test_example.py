"""The examples a user copies, run as a user runs them (ctest gives the module's directory on
PYTHONPATH, EXAMPLE naming python/examples/tramway_comparison.py, README naming README.md and
PYTHON_PAGE docs/python.md): in the example, SDCC and SLSQP, two independent algorithms, both
converge feasible on the paper's formulation of the tramway and agree on its optimum, and the
figure is written; every ```python block of the README and of the Python page runs."""
import os
import re
import subprocess
import sys
import tempfile
import unittest

EXAMPLE = os.environ["EXAMPLE"]
PAGES = [os.environ["README"], os.environ["PYTHON_PAGE"]]


class TramwayComparisonExample(unittest.TestCase):
    def test_two_optimizers_reach_the_same_optimum_and_the_figure_is_written(self):
        with tempfile.TemporaryDirectory() as directory:
            figure = os.path.join(directory, "comparison.png")
            run = subprocess.run([sys.executable, EXAMPLE, "--optimizers", "sdcc,slsqp",
                                  "--formulations", "positive_part", "--out", figure],
                                 capture_output=True, text=True, cwd=directory)
            self.assertEqual(run.returncode, 0, run.stderr)
            with open(figure, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        rows = {line.split()[1]: line.split() for line in run.stdout.splitlines()
                if line.startswith("positive_part")}
        self.assertEqual(sorted(rows), ["sdcc", "slsqp"], run.stdout)
        for optimizer, (_, _, status, cost, _, feasible) in rows.items():
            self.assertEqual((status, feasible), ("converged", "yes"), optimizer)
        # The yaw limits are met to 1e-4 of their bound (the verdicts' tolerance), so two feasible
        # stationary points of one optimum may differ by that order relative in the cost.
        sdcc, slsqp = (float(rows[name][3]) for name in ("sdcc", "slsqp"))
        self.assertAlmostEqual(sdcc, slsqp, delta=1e-4 * sdcc)


class ReadmeBlocks(unittest.TestCase):
    def test_every_python_block_of_the_readme_and_the_python_page_runs(self):
        blocks = []
        for page in PAGES:
            with open(page) as f:
                found = re.findall(r"^```python\n(.*?)^```$", f.read(), flags=re.M | re.S)
            self.assertGreater(len(found), 0, page)
            blocks += found
        for block in blocks:
            with self.subTest(block=block.splitlines()[0]), tempfile.TemporaryDirectory() as directory:
                run = subprocess.run([sys.executable, "-c", block], capture_output=True, text=True, cwd=directory)
                self.assertEqual(run.returncode, 0, run.stderr)


if __name__ == "__main__":
    unittest.main()
