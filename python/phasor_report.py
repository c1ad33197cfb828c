#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""phasor_report — the pages phasor writes, rendered from its JSON results by jinja2 templates
(templates/ beside this file).

The phasor program (src/app/plot.cpp) stages the JSON and runs

    python3 phasor_report.py compare --data results.json --out index.html

Commands:

  compare   `phasor compare`'s index.html from its results.json (docs/compare.md lists the fields):
            the command, version, seed, -D values, the reference and its noise floor, the table,
            every run's warnings and images, the differences, profile and convergence plots. Relative
            links only, no script.

Exit status: 0 written; 1 an error (one line "error: reason" on stderr; for a file that cannot be
written the reason is the system's); 2 bad arguments; 3 jinja2 is not installed for this
interpreter (the caller may try another one).
"""

import argparse
import json
import math
import os
import sys

try:
    import jinja2
except ImportError:
    print("error: jinja2 is not installed for this Python (apt-get install python3-jinja2)", file=sys.stderr)
    sys.exit(3)

TEMPLATES = os.path.join(os.path.dirname(os.path.abspath(__file__)), "templates")


class ReportError(Exception):
    pass


def number(value, digits=3):
    """A number for people: `digits` significant digits; "—" when there is none."""
    if value is None or (isinstance(value, float) and not math.isfinite(value)):
        return "—"
    if isinstance(value, int):
        return str(value)
    return f"{value:.{digits}g}"


def seconds(value):
    """A duration: "0.25 s", "12 s", "2m05s"."""
    if value is None:
        return "—"
    if value < 60:
        return f"{value:.3g} s"
    return f"{int(value) // 60}m{int(value) % 60:02d}s"


def environment():
    env = jinja2.Environment(loader=jinja2.FileSystemLoader(TEMPLATES), autoescape=True,
                             undefined=jinja2.StrictUndefined, trim_blocks=True, lstrip_blocks=True)
    env.filters["num"] = number
    env.filters["seconds"] = seconds
    return env


def render_compare(results):
    if results.get("format") != "phasor-compare-results":
        raise ReportError("the data is not phasor compare's results.json (no 'format': 'phasor-compare-results')")
    if results.get("format_version") != 1:
        raise ReportError(f"results.json has format_version {results.get('format_version')}; this module reads 1")
    return environment().get_template("compare.html.j2").render(r=results)


def main(argv):
    parser = argparse.ArgumentParser(prog="phasor_report.py", description="phasor's pages (jinja2).")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("compare", help="phasor compare's index.html from its results.json")
    p.add_argument("--data", required=True, help="results.json")
    p.add_argument("--out", required=True, help="output HTML file")
    p.add_argument("--format", default="html", help="(accepted for symmetry with phasor_plot.py; html only)")
    args = parser.parse_args(argv)
    try:
        with open(args.data, encoding="utf-8") as f:
            results = json.load(f)
        page = render_compare(results)
        with open(args.out, "w", encoding="utf-8") as f:
            f.write(page)
    except (ReportError, json.JSONDecodeError, jinja2.TemplateError) as e:
        print(f"error: {e}", file=sys.stderr)
        return 1
    except OSError as e:  # a failed read or write: the system's reason
        print(f"error: {e.strerror or e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
