"""The Python module against the command line on the same problems (run by ctest with the module's
directory on PYTHONPATH and MBSOPT_EXECUTABLE naming the program): the same records, trajectories
and errors, and exact gradients that agree with each other."""
import csv
import json
import math
import os
import random
import re
import subprocess
import tempfile
import threading
import unittest

import numpy

import mbsopt

EXECUTABLE = os.environ["MBSOPT_EXECUTABLE"]
SOURCE = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def command(*arguments):
    return subprocess.run([EXECUTABLE, *arguments], capture_output=True, text=True)


class ModuleAgainstTheCommandLine(unittest.TestCase):
    def test_optimize_gives_the_record_of_mbsopt_optimize(self):
        # The same run in both (the results do not depend on the gradients' threads): the same
        # designs, status and history to the bit; the tramway's optimum, 2.189373 m/s² on its grid
        # (README), to what the constraints' tolerances are worth there.
        run = mbsopt.optimize("tramway", optimizer="sdcc", gradient="adjoint", jobs=1)
        record = run.record()
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "result.json")
            self.assertEqual(command("optimize", "tramway", "--jobs", "1", "--json", path).returncode, 0)
            with open(path) as f:
                expected = json.load(f)
        for key in ("status", "design", "cost", "responses", "constraints", "feasible", "simulations",
                    "gradient_evaluations", "iterations", "cost_functional", "variables"):
            self.assertEqual(record[key], expected[key], key)
        self.assertEqual([h["design"] for h in record["history"]], [h["design"] for h in expected["history"]])
        self.assertEqual(record["reported_iterate"]["point"], "final")
        self.assertAlmostEqual(record["cost_functional"]["final"], 2.189373, delta=record["tolerance_worth"])
        # The object says the same as its record, in Python's types: enums, numpy arrays, verdicts.
        self.assertEqual(run.status, mbsopt.Status.converged)
        self.assertEqual(run.status.name, expected["status"])
        self.assertEqual(run.reported, mbsopt.ReportedPoint.final)
        self.assertIsInstance(run.design, numpy.ndarray)
        self.assertEqual(run.design.tolist(), expected["design"])
        self.assertEqual(run.variables, [v["parameter"] for v in expected["variables"]])
        self.assertEqual(run.cost_functional, expected["cost_functional"]["final"])
        self.assertEqual(run.feasible, expected["feasible"])
        self.assertEqual([(c.name, c.value, c.met) for c in run.constraints],
                         [(c["name"], c["value"], c["met"]) for c in expected["constraints"]])
        self.assertEqual(run.history.design.shape, (len(expected["history"]), len(expected["design"])))
        self.assertEqual(run.history.design.tolist(), [h["design"] for h in expected["history"]])
        # The budget's count holds a measured gradient cost, so it is the object's own record's.
        self.assertEqual(run.history.simulation_equivalents.tolist(),
                         [h["simulation_equivalents"] for h in record["history"]])
        self.assertEqual(run.responses, expected["responses"])

    def test_simulate_gives_the_trajectory_of_mbsopt_simulate(self):
        trajectory = mbsopt.simulate("pendulum", set={"settings.end_time": 1})
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "pendulum.csv")
            result = command("simulate", "pendulum", "--set", "settings.end_time=1", "--out", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(path, newline="") as f:
                rows = list(csv.reader(f))
        header, values = rows[0], numpy.array(rows[1:], dtype=float)
        named = zip(["t", *trajectory.coordinates, *trajectory.sensor_names],
                    ["s", *trajectory.coordinate_units, *trajectory.sensor_units])
        self.assertEqual(header, ["%s [%s]" % (name, unit) for name, unit in named])
        self.assertEqual(trajectory.coordinate_units, ["rad"])  # the pendulum's hinge
        columns = numpy.column_stack([trajectory.time, trajectory.q, trajectory.sensors])
        self.assertEqual(columns.shape, values.shape)
        # The CSV prints 17 significant digits: it reads back to the same doubles.
        numpy.testing.assert_array_equal(columns, values)

    def test_a_model_file_runs_as_the_command_line_runs_it(self):
        # An MJCF file, its limit left out by the word setting model.ignore, as `--set` does it.
        arm = os.path.join(SOURCE, "tests", "7-io", "models", "arm.xml")
        trajectory = mbsopt.simulate(arm, set={"model.ignore": "limits"})
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "arm.csv")
            result = command("simulate", arm, "--set", "model.ignore=limits", "--out", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(path, newline="") as f:
                values = numpy.array(list(csv.reader(f))[1:], dtype=float)
        self.assertEqual(trajectory.coordinates, ["yaw", "shoulder", "elbow", "extension"])
        numpy.testing.assert_array_equal(numpy.column_stack([trajectory.time, trajectory.q]), values[:, :5])
        with self.assertRaisesRegex(Exception, r"arm\.xml:22: .*limits"):
            mbsopt.simulate(arm)

    def test_a_run_driven_by_accuracy_is_that_of_the_command_line(self):
        # The extrapolation to 1e-6 with rows every 0.1 s: the same rows as `mbsopt simulate --accuracy
        # 1e-6 --output-step 0.1` to the bit, and an estimate within the accepted half of the tolerance.
        trajectory = mbsopt.Scene("four_bar").simulate(accuracy=1e-6, output_step=0.1)
        self.assertEqual(trajectory.integrator, "extrapolation")
        numpy.testing.assert_allclose(trajectory.time, numpy.arange(41) * 0.1, rtol=0, atol=1e-12)
        self.assertLessEqual(numpy.abs(trajectory.estimated_error.q).max(), 0.5e-6)
        self.assertEqual(trajectory.estimated_error.sensors.shape, trajectory.sensors.shape)
        # Newton stops at 1e-9 there, above the scene's 1e-10: no round-off floor is measured. At 1e-8 it is,
        # and it is part of the estimate.
        self.assertIsNone(trajectory.estimated_error.round_off_floor)
        tight = mbsopt.Scene("four_bar").simulate(accuracy=1e-8, output_step=0.1)
        self.assertGreater(tight.estimated_error.round_off_floor, 0.0)
        self.assertLessEqual(tight.estimated_error.round_off_floor, numpy.abs(tight.estimated_error.q).max())
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "four_bar.csv")
            result = command("simulate", "four_bar", "--accuracy", "1e-6", "--output-step", "0.1", "--out", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(path, newline="") as f:
                values = numpy.array(list(csv.reader(f))[1:], dtype=float)
        numpy.testing.assert_array_equal(numpy.column_stack([trajectory.time, trajectory.q, trajectory.sensors]),
                                         values)
        # A fixed step has no estimate unless asked for, and then it is the command line's default one.
        self.assertIsNone(mbsopt.simulate("pendulum", set={"settings.end_time": 0.5}).estimated_error)
        estimated = mbsopt.simulate("pendulum", set={"settings.end_time": 0.5}, estimate_error=True)
        self.assertEqual(estimated.estimated_error.q.shape, estimated.q.shape)

    def test_fast_steps_are_those_of_the_command_line(self):
        # fast_steps=True runs what `mbsopt simulate --fast-steps` runs: the same rows to the bit, in fewer
        # Newton iterations than the default run (tests/4-integrators/test_fast_steps.cpp for their accuracy).
        overrides = {"settings.step": 5e-3}
        trajectory = mbsopt.simulate("four_bar", set=overrides, fast_steps=True)
        default = mbsopt.simulate("four_bar", set=overrides)
        self.assertLess(trajectory.newton_iterations.sum(), default.newton_iterations.sum() / 1.5)
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "four_bar.csv")
            result = command("simulate", "four_bar", "--dt", "5e-3", "--fast-steps", "--error-estimate", "off",
                             "--out", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            with open(path, newline="") as f:
                values = numpy.array(list(csv.reader(f))[1:], dtype=float)
        numpy.testing.assert_array_equal(numpy.column_stack([trajectory.time, trajectory.q, trajectory.sensors]),
                                         values)
        with self.assertRaisesRegex(ValueError, "not --fast-steps"):
            mbsopt.simulate("four_bar", integrator="extrapolation", fast_steps=True)

    def test_parameters_and_overrides(self):
        self.assertEqual(mbsopt.parameters("tramway")["front_secondary.k"], 246000.0)
        self.assertEqual(mbsopt.parameters("tramway", set={"front_secondary.k": 1.5e5})["front_secondary.k"], 1.5e5)

    def test_the_lists_of_choices_are_those_the_command_line_accepts(self):
        def accepted(subcommand, flag):  # CLI11's "--flag TEXT:{a,b,c}" in --help
            text = command(subcommand, "--help").stdout
            match = re.search(re.escape(flag) + r" TEXT:\{([^}]*)\}", text)
            self.assertIsNotNone(match, f"{subcommand} --help has no choices for {flag}")
            return match.group(1).split(",")

        self.assertEqual(accepted("optimize", "--optimizer"), mbsopt.optimizers())
        self.assertEqual(accepted("optimize", "--formulation"), mbsopt.formulations())
        gradients = accepted("optimize", "--gradient")
        self.assertEqual(gradients[:len(mbsopt.gradient_methods())], mbsopt.gradient_methods())
        self.assertEqual(accepted("simulate", "--integrator"), mbsopt.integrators())

    def test_errors_are_exceptions_with_the_command_lines_words(self):
        result = command("simulate", "no_such_scene")
        self.assertEqual(result.returncode, 1)
        with self.assertRaises(Exception) as raised:
            mbsopt.simulate("no_such_scene")
        self.assertIn(str(raised.exception), result.stderr)
        with self.assertRaises(ValueError):
            mbsopt.optimize("tramway", optimizer="bfgs")


class PersistentObjects(unittest.TestCase):
    def test_a_scenes_overrides_accumulate_as_the_command_lines_sets_do(self):
        scene = mbsopt.Scene("pendulum", set={"settings.end_time": 1})
        scene.set({"bob.mass": 2.5})
        self.assertEqual(scene.parameters["bob.mass"], 2.5)
        trajectory = scene.simulate()
        with tempfile.TemporaryDirectory() as directory:
            path = os.path.join(directory, "pendulum.csv")
            result = command("simulate", "pendulum", "--set", "settings.end_time=1", "--set", "bob.mass=2.5",
                             "--out", path)
            self.assertEqual(result.returncode, 0, result.stderr)
            values = numpy.loadtxt(path, delimiter=",", skiprows=1)
        numpy.testing.assert_array_equal(numpy.column_stack([trajectory.time, trajectory.q]),
                                         values[:, :2])
        self.assertEqual(scene.coordinates, trajectory.coordinates)

    def test_a_problems_variables_are_its_design_section(self):
        # tramway.yaml's design: the secondary suspensions' yaw stiffness and damping, bounded
        # [50, 1000] kN·m/rad and [5, 50] kN·m·s/rad, starting at the scene's own values.
        problem = mbsopt.Problem("tramway")
        self.assertEqual(problem.variables, ["front_secondary.k", "rear_secondary.k", "front_secondary.c",
                                             "rear_secondary.c", "b_{k+1}"])
        parameters = mbsopt.Scene("tramway").parameters
        numpy.testing.assert_allclose(problem.start[:4], [parameters[name] for name in problem.variables[:4]],
                                      rtol=1e-15)
        numpy.testing.assert_allclose(problem.lower[:4], [50e3, 50e3, 5e3, 5e3], rtol=1e-15)
        numpy.testing.assert_allclose(problem.upper[:4], [1000e3, 1000e3, 50e3, 50e3], rtol=1e-15)

    def test_a_problem_evaluated_again_and_again_keeps_no_stale_state(self):
        # A kept simulation must not leak from one point into another: a, b, a again on one object
        # give what fresh objects give at each point.
        problem = mbsopt.Problem("tramway", gradient="direct")
        a, b = [2.0e5, 1.0e5, 3.0e4, 2.0e4], [3.0e5, 4.0e5, 1.0e4, 4.0e4]
        first_a, at_b, again_a = (problem.evaluate(design, artificial=2.0) for design in (a, b, a))
        for design, values in ((a, first_a), (b, at_b), (a, again_a)):
            fresh = mbsopt.evaluate("tramway", design=design, artificial=2.0, gradient="direct")
            numpy.testing.assert_array_equal(values.constraints, fresh.constraints)
            numpy.testing.assert_array_equal(values.constraint_jacobian, fresh.constraint_jacobian)
        self.assertFalse(numpy.array_equal(first_a.constraints, at_b.constraints))

    def test_a_refused_override_leaves_the_scene_as_it_was_and_a_name_set_again_takes_its_new_value(self):
        scene = mbsopt.Scene("pendulum", set={"bob.mass": 2.0})
        with self.assertRaisesRegex(RuntimeError, "mass must be positive, got -1 \\(value from --set bob.mass=-1\\)"):
            scene.set({"bob.mass": -1})
        self.assertEqual(scene.parameters["bob.mass"], 2.0)
        scene.set({"bob.mass": 3.0})  # not refused for the earlier -1
        self.assertEqual(scene.parameters["bob.mass"], 3.0)

    def test_threads_sharing_one_object_get_what_fresh_objects_give(self):
        # simulate() and evaluate() run without the GIL; the objects' own locks keep a set() or a
        # second evaluation from changing what one of them reads (without them: a segfault).
        scene = mbsopt.Scene("pendulum", set={"settings.end_time": 0.2})
        trajectories = []
        threads = [threading.Thread(target=lambda: trajectories.extend(scene.simulate() for _ in range(10))),
                   threading.Thread(target=lambda: [scene.set({"bob.mass": 1.0}) for _ in range(100)])]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        # 1.0 kg is the scene's own mass: whichever set() a simulation follows, its trajectory is this one.
        expected = mbsopt.simulate("pendulum", set={"settings.end_time": 0.2}).q
        for trajectory in trajectories:
            numpy.testing.assert_array_equal(trajectory.q, expected)
        problem = mbsopt.Problem("tramway", gradient="direct")
        designs = [[2.0e5, 1.0e5, 3.0e4, 2.0e4], [3.0e5, 4.0e5, 1.0e4, 4.0e4]]
        results = [None, None]

        def evaluate(k):
            results[k] = problem.evaluate(designs[k], artificial=2.0)
        threads = [threading.Thread(target=evaluate, args=(k,)) for k in range(2)]
        for thread in threads:
            thread.start()
        for thread in threads:
            thread.join()
        for design, values in zip(designs, results):
            fresh = mbsopt.evaluate("tramway", design=design, artificial=2.0, gradient="direct")
            numpy.testing.assert_array_equal(values.constraint_jacobian, fresh.constraint_jacobian)

    def test_errors_of_the_objects(self):
        with self.assertRaisesRegex(ValueError, "unknown gradient method 'nope'"):
            mbsopt.Problem("tramway", gradient="nope")
        with self.assertRaisesRegex(RuntimeError, "no 'design:' section"):
            mbsopt.Problem("pendulum")
        with self.assertRaisesRegex(ValueError, "2 values for 4 design variables"):
            mbsopt.Problem("tramway").evaluate([1.0, 2.0])
        with self.assertRaisesRegex(RuntimeError, "did you mean 'mass'"):
            mbsopt.Scene("pendulum").set({"bob.mas": 1})
        with self.assertRaisesRegex(ValueError, "jobs must be at least 1, not 0"):
            mbsopt.Problem("tramway", jobs=0)

    def test_a_design_is_checked_as_the_scene_checks_its_numbers(self):
        # Outside its bounds only when asked for, and then named; a negative stiffness never (the
        # scene's own check, at its line), where it used to give an RMS of 1e135.
        problem = mbsopt.Problem(os.path.join(SOURCE, "problems", "suite", "tuned_mass_damper.yaml"))
        with self.assertRaisesRegex(ValueError, "tmd.k = -400 lies outside its bounds"):
            problem.evaluate([-400.0, 5.0], gradients=False)
        with self.assertRaisesRegex(ValueError, "k must not be negative, got -400"):
            problem.evaluate([-400.0, 5.0], gradients=False, outside_bounds=True)
        outside = problem.evaluate([1200.0, 5.0], gradients=False, outside_bounds=True)
        self.assertEqual(outside.outside_bounds, ["tmd.k = 1200 above its upper bound 1000"])
        self.assertEqual(problem.evaluate([464.85, 10.58], gradients=False).outside_bounds, [])


class RandomInputs(unittest.TestCase):
    """The command line's fuzzing of designs and run options (tests/fuzz/, docs/fuzzing.md) for the
    module, from a fixed seed: random design points, artificial variables and optimizer choices on
    the tuned mass damper over its first 0.2 s. Every call either refuses its input with one line
    (ValueError, or RuntimeError for what the simulation refuses) or returns finite numbers only:
    no non-finite answer let through, no crash."""

    SPECIAL = [float("nan"), float("inf"), -float("inf"), 0.0, -1.0, 1e308, -1e308, 5e-324, 1e-300]

    def setUp(self):
        self.random = random.Random(20261202)
        self.problem = mbsopt.Problem(os.path.join(SOURCE, "problems", "suite", "tuned_mass_damper.yaml"),
                                      set={"settings.end_time": 0.2})

    def number(self, low, high):
        """A special value one time in six, else uniform on [low, high] widened by half its width."""
        if self.random.random() < 1 / 6:
            return self.random.choice(self.SPECIAL)
        width = high - low
        return self.random.uniform(low - width / 2, high + width / 2)

    def refused(self, call):
        try:
            return call()
        except (ValueError, RuntimeError) as error:
            self.assertNotIn("\n", str(error))
            self.assertTrue(str(error))
            return None

    def assertFinite(self, values, what):
        self.assertTrue(numpy.all(numpy.isfinite(numpy.asarray(values, dtype=float))), what)

    def test_random_design_points_are_refused_or_evaluated_finite(self):
        lower, upper = self.problem.lower, self.problem.upper
        evaluated = 0
        for _ in range(150):
            size = self.random.choice([len(lower) - 1] * 8 + [len(lower) - 2, len(lower)])
            design = [self.number(lower[i % len(lower)], upper[i % len(upper)]) for i in range(size)]
            artificial = self.random.choice([None, None, self.number(lower[-1], upper[-1])])
            outside = self.random.random() < 0.5
            values = self.refused(lambda: self.problem.evaluate(design, artificial=artificial,
                                                                gradients=self.random.random() < 0.5,
                                                                outside_bounds=outside))
            if values is None:
                continue
            evaluated += 1
            for key in ("cost", "cost_functional", "constraints", "cost_gradient", "constraint_jacobian"):
                if getattr(values, key) is not None:
                    self.assertFinite(getattr(values, key), key)
            if not outside:
                self.assertEqual(values.outside_bounds, [])
            given = design if design else list(self.problem.start[:-1])  # none given: the start's
            point = given + ([] if artificial is None else [artificial])  # b_{k+1} last, as in lower
            inside = all(lo <= x <= hi for x, lo, hi in zip(point, lower, upper))
            self.assertEqual(values.outside_bounds == [], inside, point)
        self.assertGreater(evaluated, 20)  # the draws reach the evaluation, not only the refusals

    def test_random_run_options_are_refused_or_end_with_a_finite_record(self):
        optimizers = mbsopt.optimizers() + ["nope"]
        formulations = mbsopt.formulations() + ["", "nope"]
        ran = 0
        for _ in range(30):
            options = dict(optimizer=self.random.choice(optimizers), formulation=self.random.choice(formulations),
                           epsilon=self.random.choice([None, None, self.number(0.0, 1e-6)]),
                           budget=self.random.choice([None, self.number(1.0, 30.0)]),
                           max_iter=self.random.choice([-1, 0, 1, 2, 3]),
                           settings=self.random.choice([{}, {}, {"xtol_rel": self.number(0.0, 1e-3)}, {"nope": 1}]))
            run = self.refused(lambda: self.problem.optimize(**options))
            if run is None:
                continue
            ran += 1
            self.assertIsInstance(run.status, mbsopt.Status, options)
            self.assertFinite(run.design, "design")
            self.assertFinite(list(run.responses.values()), "responses")
            if run.status == mbsopt.Status.converged:
                self.assertTrue(math.isfinite(run.cost_functional), options)
        self.assertGreater(ran, 3)


class Gradients(unittest.TestCase):
    def test_adjoint_and_direct_agree_on_the_tramway(self):
        # Two independent exact methods: equal to round-off (1e-10 of the largest entry).
        design = [2.0e5, 1.0e5, 3.0e4, 2.0e4]
        adjoint = mbsopt.evaluate("tramway", design=design, artificial=2.0, gradient="adjoint")
        direct = mbsopt.evaluate("tramway", design=design, artificial=2.0, gradient="direct")
        self.assertEqual(adjoint.variables[-1], "b_{k+1}")
        self.assertEqual(adjoint.constraint_jacobian.shape, (len(adjoint.constraint_names), 5))
        # Over the design variables' columns (b_{k+1}'s, exact in both, would set a looser scale).
        scale = numpy.abs(direct.constraint_jacobian[:, :-1]).max()
        self.assertGreater(scale, 0.0)
        numpy.testing.assert_allclose(adjoint.constraint_jacobian[:, :-1], direct.constraint_jacobian[:, :-1],
                                      rtol=0, atol=1e-10 * scale)
        numpy.testing.assert_array_equal(adjoint.constraints, direct.constraints)


if __name__ == "__main__":
    unittest.main()
