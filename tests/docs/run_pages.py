#!/usr/bin/env python3
"""Runs the pages of the documentation's getting-started guide as a reader would, in one fresh
directory, in the order given: each block after a `<!-- file: NAME -->` line is written to NAME;
each ```console block's `$ COMMAND` lines are run (bash, with the directory of `mbsopt` and of the
Python interpreter first on PATH and the module's directory on PYTHONPATH) and their quoted output
is compared with what the command prints, line by line (scripts/readme_figures.py's rules: `...`
stands for lines left out, timings may move, the words must be the same). A command must exit 0, or
1 where its quote shows an error line (`: error:`). Any other fenced block on a page is an error, so
that no block goes unrun.

The pages' figures come from one machine; on another CPU the same build rounds differently, which
moves the last digits of a result and, through an optimizer's path, its counts. So a quoted figure
holds when it is within 1e-3 of the printed one, relative (the pages state results to three or
four digits; an optimum that moved by more is a change to explain); when both are below 1e-6 in
magnitude (violations, residuals, KKT norms: round-off that the pages quote only as "tiny"); or,
for a count (an integer: simulations, gradients, iterations, Newton iterations), within 20 % of it
(round-off may move an optimizer's path by some evaluations, not its order of magnitude).

    run_pages.py --mbsopt build/release/app/mbsopt --python-path build/release/python PAGE.md ...

Exit status 0 when every command ran and every quoted figure holds, 1 otherwise."""
import argparse
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts"))
import readme_figures  # noqa: E402 (after the path is set)

FILE = re.compile(r"^<!-- file: (\S+) -->$")
FENCE = re.compile(r"^```(\w*)$")


def steps(path):
    """The page's files to write and transcripts to check, in page order: ("file", line, name, text)
    and ("console", line, FigureSet)."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    transcripts = {s.line: s for s in readme_figures.figure_sets(path) if s.kind == "console"}
    out, pending, i = [], None, 0
    while i < len(lines):
        marker, fence = FILE.match(lines[i]), FENCE.match(lines[i])
        if marker:
            pending = marker.group(1)
        elif fence:
            language, start = fence.group(1), i
            i += 1
            while i < len(lines) and lines[i] != "```":
                i += 1
            body = "\n".join(lines[start + 1:i]) + "\n"
            if pending:
                out.append(("file", start + 1, pending, body))
            elif language == "console":
                out += [("console", s.line, s) for line, s in sorted(transcripts.items()) if start < line - 1 < i]
            else:
                raise SystemExit(f"{path}:{start + 1}: a ```{language} block that is neither a console transcript "
                                 "nor a file (<!-- file: NAME --> before it): the tests would not run it")
            pending = None
        i += 1
    return out


def close(quoted, printed):
    """Whether a printed figure is the quoted one, in the sense of the module's docstring."""
    if quoted == printed:
        return True
    a, b = float(quoted), float(printed)
    if max(abs(a), abs(b)) <= 1e-6:
        return True
    if re.fullmatch(r"[-+]?\d+", quoted) and re.fullmatch(r"[-+]?\d+", printed):
        return abs(a - b) <= 0.2 * max(abs(a), abs(b))
    return abs(a - b) <= 1e-3 * max(abs(a), abs(b))


class Report(readme_figures.Report):
    def compare(self, where, quoted, now, timing_column=False):
        (old, old_words), (new, new_words) = (readme_figures.figures(quoted, timing_column),
                                              readme_figures.figures(now, timing_column))
        if old_words != new_words or len(old) != len(new):
            self.changed.append(f"{where}: quoted «{quoted.strip()}», now «{now.strip()}»")
            return
        for (a, timing), (b, _) in zip(old, new):
            if timing:
                if a != b:
                    self.timings.append(f"{where}: {a} → {b}")
            elif not close(a, b):
                self.changed.append(f"{where}: {a} → {b}   «{now.strip()}»")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mbsopt", required=True, help="the mbsopt program to run as `mbsopt`")
    parser.add_argument("--python-path", default="", help="the directory of the mbsopt Python module")
    parser.add_argument("pages", nargs="+")
    args = parser.parse_args()
    environment = dict(os.environ)
    bin_dirs = [os.path.dirname(os.path.abspath(args.mbsopt)), os.path.dirname(sys.executable)]
    environment["PATH"] = os.pathsep.join(bin_dirs + [environment.get("PATH", "")])
    environment["PYTHONPATH"] = os.path.abspath(args.python_path) if args.python_path else ""
    report = Report()
    with tempfile.TemporaryDirectory() as directory:
        for page in args.pages:
            for step in steps(page):
                if step[0] == "file":
                    _, _, name, text = step
                    with open(os.path.join(directory, name), "w", encoding="utf-8") as f:
                        f.write(text)
                    continue
                transcript = step[2]
                print(f"{page}:{transcript.line}: $ {transcript.command}", file=sys.stderr, flush=True)
                result = subprocess.run(["bash", "-c", transcript.command], cwd=directory, env=environment,
                                        capture_output=True, text=True)
                expected = 1 if any(": error:" in text for _, text in transcript.quoted) else 0
                if result.returncode != expected:
                    report.errors.append(f"{page}:{transcript.line}: `{transcript.command}` exited "
                                         f"{result.returncode}, not {expected}:\n{result.stdout}{result.stderr}")
                    continue
                output = (result.stdout + result.stderr).splitlines()
                for (number, text), now in readme_figures.align(transcript, output, report):
                    report.compare(f"{page}:{number}", text, now)
    for title, entries in (("figures changed", report.changed), ("errors", report.errors),
                           ("timings (not counted)", report.timings)):
        if entries:
            print(f"{title}: {len(entries)}")
            for entry in entries:
                print("  " + entry)
    return 1 if report.changed or report.errors else 0


if __name__ == "__main__":
    sys.exit(main())
