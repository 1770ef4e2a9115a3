#!/usr/bin/env python3
"""Writes the documentation's reference pages from the code itself, so that a new option, registry
entry or Python method appears in them without anyone editing a page:
- command-line.md: `mbsopt --help` and every subcommand's `--help` (their choices come from the
  registries);
- python-api.md: the module's functions, classes, methods, properties and enums with their
  signatures and docstrings;
- registries.md: every name a choice takes (integrators, gradient methods, optimizers,
  formulations) and the entry types of the scene files with their descriptions and keys.

    docs_reference.py --mbsopt build/release/app/mbsopt --python-path build/release/python --out DIR"""
import argparse
import inspect
import os
import re
import subprocess
import sys


def help_text(mbsopt, *arguments):
    result = subprocess.run([mbsopt, *arguments, "--help"], capture_output=True, text=True, check=True)
    return result.stdout.replace(mbsopt, "mbsopt")


def command_line_page(mbsopt):
    top = help_text(mbsopt)
    subcommands = re.findall(r"^  (\w+) {2,}", top.split("Subcommands:", 1)[1], flags=re.M)
    page = ["# Command line", "", "Generated from `mbsopt --help` and each command's `--help`.", "",
            "```text", top.rstrip(), "```", ""]
    for name in subcommands:
        page += [f"## mbsopt {name}", "", "```text", help_text(mbsopt, name).rstrip(), "```", ""]
    return "\n".join(page)


def documented(obj):
    return inspect.getdoc(obj) or ""


def signature_and_text(doc, name):
    """pybind11 puts the signature first: 'name(args) -> result' then the text."""
    lines = doc.splitlines()
    if lines and lines[0].startswith(name + "("):
        return lines[0], "\n".join(lines[1:]).strip()
    return name, doc


def python_page(module):
    page = ["# Python API", "", f"Generated from the docstrings of the module `mbsopt` {module.__version__}.", "",
            documented(module), "", "## Functions", ""]
    for name, function in sorted(inspect.getmembers(module, inspect.isbuiltin)):
        signature, text = signature_and_text(documented(function), name)
        page += [f"### `{signature}`", "", text, ""]
    page += ["## Classes", ""]
    for name, cls in sorted(inspect.getmembers(module, inspect.isclass)):
        page += [f"### `{name}`", "", documented(cls), ""]
        if hasattr(cls, "__members__"):  # an enumeration: its docstring lists the values and their meanings
            continue
        for member, value in sorted(vars(cls).items()):
            if member.startswith("_") and member not in ("__init__",):
                continue
            if isinstance(value, property):
                page += [f"- `{member}` (attribute): {documented(value) or '—'}"]
            elif callable(value):
                for overload in documented(value).split("\n\n") if member == "__init__" else [documented(value)]:
                    signature, text = signature_and_text(overload, member)
                    page += [f"- `{signature}`: {' '.join(text.split()) or '—'}"]
        page.append("")
    return "\n".join(page)


def registries_page(module):
    page = ["# Registries", "", "Generated from the registries the code asks: every name a choice takes, and the",
            "types of a scene file's entries.", ""]
    for title, names in (("Integrators", module.integrators()), ("Gradient methods", module.gradient_methods()),
                         ("Optimizers", module.optimizers()), ("Formulations", module.formulations())):
        page += [f"## {title}", "", ", ".join(f"`{n}`" for n in names), ""]
    page += ["Each one's description is in the `--help` of the commands that take it "
             "([command line](command-line.md)).", ""]
    for section, types in module.entry_types().items():
        page += [f"## Scene files: `{section}:`", "", "| type | what it is | keys |", "|---|---|---|"]
        for t in types:
            description = t["description"].replace("|", "\\|")
            page.append(f"| `{t['name']}` | {description} | {', '.join(f'`{k}`' for k in t['keys'])} |")
        page.append("")
    return "\n".join(page)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--mbsopt", required=True)
    parser.add_argument("--python-path", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    sys.path.insert(0, os.path.abspath(args.python_path))
    import mbsopt
    os.makedirs(args.out, exist_ok=True)
    for name, text in (("command-line.md", command_line_page(os.path.abspath(args.mbsopt))),
                       ("python-api.md", python_page(mbsopt)), ("registries.md", registries_page(mbsopt))):
        with open(os.path.join(args.out, name), "w", encoding="utf-8") as f:
            f.write(text.rstrip() + "\n")


if __name__ == "__main__":
    sys.exit(main())
