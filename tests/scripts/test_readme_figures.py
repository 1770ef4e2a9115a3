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


TABLE = "| solver | runs | wall time [s] |\n|---|---|---|\n| a | 7 | 1.5 |\n| b | 9 | 2.0 |\n"


def check(markdown, *options):
    """The script's exit status and report on `markdown`, where {table} names a file holding TABLE."""
    with tempfile.TemporaryDirectory() as directory:
        table = os.path.join(directory, "table.md")
        with open(table, "w") as f:
            f.write(TABLE)
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

    def test_a_simulated_time_is_a_figure_not_a_timing(self):
        status, out = check("```console\n$ echo 'peak at t = 1.6 s, steps of 0.001 s, wall time 0.2 s'\n"
                            "peak at t = 1.5 s, steps of 0.001 s, wall time 0.9 s\n```\n")
        self.assertEqual(status, 1, out)
        self.assertIn("FIGURES.md:3: 1.5 → 1.6", out)
        self.assertIn("timings (not counted as changes): 1", out)

    def test_a_later_segment_starts_at_the_line_it_quotes_not_at_the_first_of_its_shape(self):
        status, out = check("```console\n$ printf '1 2\\n3 4\\n5 6\\nend\\n'\n1 2\n...\n3 4\n...\n```\n")
        self.assertEqual(status, 0, out)
        status, out = check("```console\n$ printf '1 2\\n3 4\\n5 6\\nend\\n'\n1 2\n...\n3 5\n...\n```\n")
        self.assertEqual(status, 1, out)
        self.assertIn("FIGURES.md:5: 5 → 4", out)  # the nearest line of its shape, 3 4

    def test_quoted_lines_beyond_the_output_are_reported(self):
        status, out = check("```console\n$ printf 'a 1\\nb 2\\n'\na 1\n...\nb 2\nc 3\n...\n```\n")
        self.assertEqual(status, 1, out)
        self.assertIn("FIGURES.md:6: the quoted lines from here on are beyond the output", out)

    def test_rows_without_a_key_of_words_are_compared_in_order(self):
        quoted = "<!-- figures: true => {table} -->\n" + TABLE
        # The file's rows are a, b; quoted in order they match, and a first cell with a figure
        # ("a1") turns the comparison to the rows' order.
        self.assertEqual(check(quoted)[0], 0)
        status, out = check(quoted.replace("| a |", "| a1 |"))
        self.assertEqual(status, 1, out)
        self.assertIn("[solver]: quoted «a1», now «a»", out)

    def test_a_failing_command_is_an_error(self):
        status, out = check("```console\n$ exit 3\n```\n")
        self.assertEqual(status, 2, out)
        self.assertIn("exited 3", out)


if __name__ == "__main__":
    unittest.main()
