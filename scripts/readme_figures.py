#!/usr/bin/env python3
"""Reruns the commands behind the figures a markdown file quotes and reports the figures that changed.

Two kinds of quoted figures are checked, in README.md and in every other markdown file named:
- console transcripts: each ```console block's `$ COMMAND` lines are run (bash, from the repository's
  root) and the lines quoted under them are compared with the command's output, figure by figure;
  a line `...` in the quote stands for output left out (the quote's first lines are the output's
  first lines; the lines after a `...` continue at the next output line that reads like the first
  of them, figures aside; a quote that does not end with `...` ends with the output);
- tables copied from a command's output: a comment `<!-- figures: COMMAND => FILE -->` on the line
  before a table says that COMMAND writes FILE (a path from the repository's root, or `-` for the
  command's standard output) and that FILE holds a table with the same header; rows are matched by
  their leading cells without figures (optimizer, gradient, formulation, …), or in order where those
  are missing or repeated, cells figure by figure.

A figure is a number as printed. Timings and the figures a clock decides (a number followed by a
time unit but for a simulated time such as "t = 1.5 s" or "steps of 0.001 s", after "wall time", in a column whose header names a time or a unit of seconds, a measured
gradient cost and the simulation-equivalents counted with it, the simulations that ran ahead on a
spare core) move with the machine's load: they are listed apart and do not count as changes. Other figures quoted elsewhere in the prose name their
command beside them; this script does not find those.

Exit status: 0 when no figure changed (timings aside), 1 when some did, 2 when a command failed or
an output could not be found or read.

    scripts/readme_figures.py                      # every figure set of README.md and the docs
    scripts/readme_figures.py --list               # the figure sets, with their commands
    scripts/readme_figures.py --only 1 3           # the sets numbered 1 and 3 by --list
    scripts/readme_figures.py --no-run             # compare with the outputs already written
    scripts/readme_figures.py problems/suite/README.md
"""
import argparse
import os
import re
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
# What follows a figure that a clock decides: a time, a cost measured by timing (a gradient in
# simulations, the budget spent counted with it, the thread time), the simulations that happened to
# run ahead on a spare core.
TIMED_AFTER = re.compile(r"^(?:\s*(?:s|ms|µs|us|ns|min|h)\b|\s*simulation-equivalents|, measured|"
                         r"\s*simulations' thread time|\s*of the simulations ran ahead|\s*more ran ahead)")
TIMING_HEADER = re.compile(r"time|\[(?:s|ms|µs)\]|seconds|equivalents", re.I)
MARKER = re.compile(r"^<!--\s*figures:\s*(.+?)\s*=>\s*(\S+)\s*-->\s*$")


class FigureSet:
    """Figures quoted at `line` of `path`: a console block (`command` and `quoted` output lines) or a
    table (`command`, the `output` file holding it and the quoted `rows`)."""

    def __init__(self, kind, path, line, command, quoted=None, output=None, rows=None):
        self.kind, self.path, self.line, self.command = kind, path, line, command
        self.quoted, self.output, self.rows = quoted, output, rows


def split_row(line):
    return [cell.strip() for cell in line.strip().strip("|").split("|")]


def read_table(lines, start):
    """The table starting at lines[start] (header, separator, rows): [(line index, cells), …]."""
    rows = []
    i = start
    while i < len(lines) and lines[i].lstrip().startswith("|"):
        if not re.fullmatch(r"\|?[\s:|-]+\|?", lines[i].strip()):
            rows.append((i, split_row(lines[i])))
        i += 1
    return rows


def figure_sets(path):
    with open(path, encoding="utf-8") as f:
        lines = f.read().splitlines()
    sets = []
    i = 0
    while i < len(lines):
        marker = MARKER.match(lines[i])
        if lines[i].strip() == "```console":
            i += 1
            command, quoted = None, []
            while i < len(lines) and lines[i].strip() != "```":
                if lines[i].startswith("$ "):
                    if command:
                        sets.append(FigureSet("console", path, command[0], command[1], quoted=quoted))
                    command, quoted = (i + 1, lines[i][2:]), []
                elif command:
                    quoted.append((i + 1, lines[i]))
                i += 1
            if command:
                sets.append(FigureSet("console", path, command[0], command[1], quoted=quoted))
        elif marker:
            j = i + 1
            while j < len(lines) and not lines[j].strip():
                j += 1
            rows = read_table(lines, j)
            if not rows:
                raise SystemExit(f"{path}:{i + 1}: a figures marker with no table after it")
            sets.append(FigureSet("table", path, i + 1, marker.group(1), output=marker.group(2),
                                  rows=[(k + 1, cells) for k, cells in rows]))
        i += 1
    return sets


# A time the run computes, not one it measures: "at t = 1.593 s", "steps of 0.001 s", "h = 1 ms".
SIMULATED_TIME_BEFORE = re.compile(r"(?:\b[th]\s*=|\bsteps? of|--dt)\s*$")


def is_timing(text, start, end):
    before = text[max(0, start - 12):start]
    if SIMULATED_TIME_BEFORE.search(before):
        return False
    return bool(TIMED_AFTER.match(text[end:])) or "wall time" in before


def figures(text, timing_column=False):
    """The text's numbers as printed, each with whether it is a timing, and the words between them."""
    numbers = [(m.group(), timing_column or is_timing(text, m.start(), m.end())) for m in NUMBER.finditer(text)]
    return numbers, NUMBER.sub("#", " ".join(text.split()))


class Report:
    def __init__(self):
        self.changed, self.timings, self.errors = [], [], []

    def compare(self, where, quoted, now, timing_column=False):
        """Figures of one quoted line or cell against the same line or cell now."""
        (old, old_words), (new, new_words) = figures(quoted, timing_column), figures(now, timing_column)
        if old_words != new_words or len(old) != len(new):
            self.changed.append(f"{where}: quoted «{quoted.strip()}», now «{now.strip()}»")
            return
        for (a, timing), (b, _) in zip(old, new):
            if a != b:
                (self.timings if timing else self.changed).append(f"{where}: {a} → {b}   «{now.strip()}»")


def run(command):
    """The command's status and output, run from the repository's root with the built `mbsopt` on PATH
    (the pages call it by its name)."""
    environment = dict(os.environ, PATH=os.pathsep.join([os.path.join(ROOT, "build", "release", "app"),
                                                        os.environ.get("PATH", "")]))
    result = subprocess.run(["bash", "-c", command], cwd=ROOT, capture_output=True, text=True, env=environment)
    return result.returncode, result.stdout + result.stderr


def check_console(figure_set, report, execute):
    if not execute:
        report.errors.append(f"{figure_set.path}:{figure_set.line}: a console transcript is checked only by "
                             "running its command (without --no-run)")
        return
    status, output = run(figure_set.command)
    if status not in (0, 2):  # 2: an optimizer that did not converge, with its outputs written
        report.errors.append(f"{figure_set.path}:{figure_set.line}: `{figure_set.command}` exited {status}:\n{output}")
        return
    out = output.splitlines()
    for (number, text), now in align(figure_set, out, report):
        report.compare(f"{figure_set.path}:{number}", text, now)


def words(text):
    return figures(text)[1]


def align(figure_set, out, report):
    """The quoted lines paired with the output's. The quote's `...` lines cut it into segments: the
    first is the output's first lines, each later one starts at the next output line equal to its
    first line, or else the next with the same words (figures aside), and a quote that does not end
    with `...` ends where the output ends. Quoted lines beyond the output are reported."""
    segments, segment = [], []
    for number, text in figure_set.quoted:
        if text.strip() == "...":
            segments.append(segment)
            segment = []
        else:
            segment.append((number, text))
    segments.append(segment)
    open_end = not segment
    pairs, position = [], 0
    for k, segment in enumerate(segments):
        if not segment:
            continue
        if k == len(segments) - 1 and not open_end and k > 0:
            start = len(out) - len(segment)
        elif k == 0:
            start = 0
        else:
            first = segment[0][1]
            start = next((i for i in range(position, len(out)) if out[i].split() == first.split()), None)
            if start is None:
                start = next((i for i in range(position, len(out)) if words(out[i]) == words(first)), None)
        if start is None or start < position:
            report.changed.append(f"{figure_set.path}:{segment[0][0]}: the quoted lines from here on are not in "
                                  f"the output of `{figure_set.command}`")
            return pairs
        pairs += list(zip(segment, out[start:start + len(segment)]))
        if start + len(segment) > len(out):
            report.changed.append(f"{figure_set.path}:{segment[len(out) - start][0]}: the quoted lines from here on "
                                  f"are beyond the output of `{figure_set.command}` ({len(out)} lines)")
            return pairs
        position = start + len(segment)
    if len(segments) == 1 and len(out) != len(figure_set.quoted):
        report.changed.append(f"{figure_set.path}:{figure_set.line}: {len(figure_set.quoted)} lines quoted, "
                              f"the command printed {len(out)}")
    return pairs


def row_key(cells):
    key = []
    for cell in cells:
        if NUMBER.search(cell):
            break
        key.append(cell)
    return tuple(key)


def check_table(figure_set, report, execute):
    output = figure_set.output
    printed = None
    if execute:
        status, printed = run(figure_set.command)
        if status not in (0, 2):
            report.errors.append(f"{figure_set.path}:{figure_set.line}: `{figure_set.command}` exited {status}:\n{printed}")
            return
    if output == "-":
        if printed is None:
            report.errors.append(f"{figure_set.path}:{figure_set.line}: the table is the command's output; "
                                 "checked only by running it")
            return
        lines = printed.splitlines()
    else:
        try:
            with open(os.path.join(ROOT, output), encoding="utf-8") as f:
                lines = f.read().splitlines()
        except OSError as error:
            report.errors.append(f"{figure_set.path}:{figure_set.line}: {error}")
            return
    header = figure_set.rows[0][1]
    start = next((k for k, line in enumerate(lines) if line.lstrip().startswith("|") and split_row(line) == header),
                 None)
    if start is None:
        report.errors.append(f"{figure_set.path}:{figure_set.line}: no table with the header "
                             f"| {' | '.join(header)} | in {output}")
        return
    rows_now = [cells for _, cells in read_table(lines, start)[1:]]
    quoted = figure_set.rows[1:]
    timing_columns = [bool(TIMING_HEADER.search(name)) for name in header]
    keys_now, keys_quoted = [row_key(cells) for cells in rows_now], [row_key(cells) for _, cells in quoted]
    if all(keys_now) and all(keys_quoted) and len(set(keys_now)) == len(keys_now) and \
            len(set(keys_quoted)) == len(keys_quoted):
        now = dict(zip(keys_now, rows_now))  # rows by their leading cells, in any order
        pairs = []
        for (number, cells), key in zip(quoted, keys_quoted):
            if key in now:
                pairs.append((number, cells, now[key]))
            else:
                report.changed.append(f"{figure_set.path}:{number}: the row {' | '.join(key)} is not in {output} "
                                      "any more")
        for key in keys_now:
            if key not in keys_quoted:
                report.changed.append(f"{figure_set.path}:{figure_set.line}: {output} has a row the README does not "
                                      f"quote: {' | '.join(key)}")
    else:  # leading cells with figures, or repeated: row by row, in order
        pairs = [(number, cells, new) for (number, cells), new in zip(quoted, rows_now)]
        if len(quoted) != len(rows_now):
            report.changed.append(f"{figure_set.path}:{figure_set.line}: {len(quoted)} rows quoted, {len(rows_now)} "
                                  f"in {output}")
    for number, cells, new_cells in pairs:
        for name, old, new, timing in zip(header, cells, new_cells, timing_columns):
            report.compare(f"{figure_set.path}:{number} [{name}]", old, new, timing)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0],
                                     epilog="\n".join(__doc__.splitlines()[1:]),
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    pages = ["README.md"] + sorted(os.path.relpath(os.path.join(ROOT, "docs", name), ROOT)
                                   for name in os.listdir(os.path.join(ROOT, "docs")) if name.endswith(".md"))
    parser.add_argument("files", nargs="*", default=pages + ["problems/suite/README.md"],
                        help="markdown files (default: README.md, docs/*.md and problems/suite/README.md; "
                             "docs/getting-started/ is run by tests/docs/run_pages.py)")
    parser.add_argument("--list", action="store_true", help="list the figure sets and their commands, run nothing")
    parser.add_argument("--only", type=int, nargs="+", metavar="N", help="only the sets numbered N by --list")
    parser.add_argument("--no-run", action="store_true",
                        help="compare tables with the outputs already written, without running their commands")
    args = parser.parse_args()
    sets = [s for name in args.files for s in figure_sets(os.path.join(ROOT, name) if not os.path.isabs(name) else name)]
    if args.list:
        for number, s in enumerate(sets, 1):
            where = f"{os.path.relpath(s.path, ROOT)}:{s.line}"
            target = "" if s.kind == "console" else f"  => {s.output}"
            print(f"{number:3}  {s.kind:7}  {where:18}  {s.command}{target}")
        return 0
    chosen = [s for number, s in enumerate(sets, 1) if not args.only or number in args.only]
    report = Report()
    for number, s in enumerate(chosen, 1):
        print(f"[{number}/{len(chosen)}] {os.path.relpath(s.path, ROOT)}:{s.line}: {s.command}", file=sys.stderr, flush=True)
        (check_console if s.kind == "console" else check_table)(s, report, not args.no_run)
    for title, entries in (("figures changed", report.changed), ("timings (not counted as changes)", report.timings),
                           ("errors", report.errors)):
        if entries:
            print(f"{title}: {len(entries)}")
            for entry in entries:
                print("  " + entry.replace(ROOT + "/", ""))
    if not report.changed and not report.errors:
        print(f"no figure changed in {len(chosen)} figure sets ({len(report.timings)} timings moved)")
    return 2 if report.errors else 1 if report.changed else 0


if __name__ == "__main__":
    sys.exit(main())
