"""scripts/readme_figures.py on markdown written here, whose commands print known text: a transcript
or a table that still matches passes, a changed figure is reported with its line and exits 1, a
moved timing is listed but does not count, `...` skips output, and a failing command exits 2.
(ctest gives SCRIPT naming scripts/readme_figures.py.)"""
import os
import subprocess
import sys
import tempfile
import textwrap
import unittest

SCRIPT = os.environ["SCRIPT"]


def check(markdown, *options):
    """The script's exit status and report on `markdown`, where {table} names a file holding the
    table | solver | runs | wall time [s] | with the rows a, 7, 1.5 and b, 9, 2.0."""
    with tempfile.TemporaryDirectory() as directory:
        table = os.path.join(directory, "table.md")
        with open(table, "w") as f:
            f.write("| solver | runs | wall time [s] |\n|---|---|---|\n| a | 7 | 1.5 |\n| b | 9 | 2.0 |\n")
        path = os.path.join(directory, "FIGURES.md")
        with open(path, "w") as f:
            f.write(textwrap.dedent(markdown).replace("{table}", table))
        run = subprocess.run([sys.executable, SCRIPT, path, *options], capture_output=True, text=True)
        return run.returncode, run.stdout


TRANSCRIPT = """\
    ```console
    $ printf 'first 1.25\\nnoise\\nnoise\\nsteps 12, wall time 0.5 s\\nlast 3e-7\\n'
    first {first}
    ...
    steps 12, wall time {time} s
    last 3e-7
    ```
    """


class ReadmeFigures(unittest.TestCase):
    def test_an_unchanged_transcript_passes_whatever_its_timings(self):
        status, out = check(TRANSCRIPT.format(first="1.25", time="0.9"))
        self.assertEqual(status, 0, out)
        self.assertIn("0.9 → 0.5", out)  # listed as a timing

    def test_a_changed_figure_is_reported_at_its_line(self):
        status, out = check(TRANSCRIPT.format(first="1.26", time="0.5"))
        self.assertEqual(status, 1, out)
        self.assertIn("FIGURES.md:3: 1.26 → 1.25", out)  # line 3: the quoted "first"

    def test_a_table_is_compared_row_by_row_with_the_file_its_command_writes(self):
        quoted = """\
            <!-- figures: true => {table} -->
            | solver | runs | wall time [s] |
            |---|---|---|
            | b | 9 | 2.2 |
            | a | RUNS | 1.5 |
            """
        status, out = check(quoted.replace("RUNS", "7"))
        self.assertEqual(status, 0, out)
        self.assertIn("[wall time [s]]: 2.2 → 2.0", out)
        status, out = check(quoted.replace("RUNS", "8"))
        self.assertEqual(status, 1, out)
        self.assertIn("FIGURES.md:5 [runs]: 8 → 7", out)
        status, out = check(quoted.replace("| b | 9 | 2.2 |\n", ""))
        self.assertEqual(status, 1, out)
        self.assertIn("has a row the README does not quote: b", out)

    def test_a_failing_command_is_an_error(self):
        status, out = check("```console\n$ exit 3\n```\n")
        self.assertEqual(status, 2, out)
        self.assertIn("exited 3", out)


if __name__ == "__main__":
    unittest.main()
