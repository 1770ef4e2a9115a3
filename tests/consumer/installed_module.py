"""run_consumer.cmake's check of the installed Python module: imported from the package directory
given (the install prefix's, never the build tree's), it simulates the pendulum.
Usage: python3 installed_module.py PACKAGE_DIR"""
import sys

package_dir = sys.argv[1]
sys.path.insert(0, package_dir)
import mbsopt  # noqa: E402 (after the path is set)

assert mbsopt.__file__.startswith(package_dir + "/"), mbsopt.__file__
run = mbsopt.simulate("pendulum")
assert run.q.shape == (len(run.time), 1), run.q.shape
print(f"ok: the installed module {mbsopt.__file__} simulated {len(run.time)} time points")
