#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Checks that every citation of docs/theory.md in the source tree resolves.

    check_theory_citations.py ROOT            check the tree at ROOT (exit 1 on any error)
    check_theory_citations.py ROOT --list     also print every citation found and where
    check_theory_citations.py --self-test     check the checker on small texts (exit 1 on failure)

A citation is the word "theory" followed by a list of references (comment line breaks may fall
anywhere inside it; "theory §4.3's last item" and "theory §9 item 5" are citations too):

    §N[.N…]                a numbered heading of docs/theory.md           theory §2.4
    §A–B, §A–§B            both ends exist                                theory §4.4–4.5, §1–§2
    … item(s)/step(s) K[–L] numbered list items K (to L) in that section  theory §9 items 1–2
    … "Title"              words that section contains                    theory §9 "Geometry"
    D4a, §0 D14, D1–D5     a row of the decisions table (§0)              theory §0 D4a/D14
    Appendix A             a heading "Appendix A"                         theory Appendix A

separated by ",", "/", "and" or "(". The checker also reports "theory" directly followed by a bare
number (theory 6.7: write §6.7), by the supplement's numbering (theory S6.1: write "supplement
S6.1" or cite the section of docs/theory.md that covers it), a section number that is not a
heading (theory §9.5), and any mention of design.md or style.md, which are not in the repository.
"""
import os
import re
import sys

# Files whose citations are checked: the code and everything a reader follows from it.
SCANNED_DIRS = ["src", "tests", "bench", "scenes", "tools", "python", "scripts", "docs", "cmake"]
SCANNED_FILES = ["README.md", "CMakeLists.txt", "Makefile"]
SCANNED_SUFFIXES = (".h", ".hpp", ".cpp", ".cc", ".py", ".sh", ".md", ".wscene", ".txt", ".cmake", ".in")
THEORY = "docs/theory.md"
SELF = "tests/docs/check_theory_citations.py"

NUM = r"\d+(?:\.\d+)*"
DEC = r"D\d+[a-z]?"
DASH = r"\s*[–-]\s*"
SECTION = re.compile(
    r"§\s*(?P<a>" + NUM + r")(?:" + DASH + r"§?(?P<b>" + NUM + r"))?(?:'s)?"
    r"(?:\s+(?:sampling\s+)?(?:items?|steps?)\s+(?P<i>\d+)(?:" + DASH + r"(?P<j>\d+))?"
    r"|\s+\"(?P<title>[^\"]+)\")?"
)
DECISION = re.compile(r"(?P<a>" + DEC + r")(?:" + DASH + r"(?P<b>" + DEC + r"))?(?:'s)?")
APPENDIX = re.compile(r"Appendix\s+(?P<a>[A-Z])\b")
SEPARATOR = re.compile(r"\s*(?:,|/|\(|\band\b)?\s*")
THEORY_WORD = re.compile(r"\btheory\b(?!\.md)")
BARE_NUMBER = re.compile(r"\s+(S?\d)")
FORBIDDEN = re.compile(r"\b(design|style)\.md\b")
# A comment's line break: newline, indentation, the comment marker of the next line.
CONTINUATION = re.compile(r"[ \t]*\n[ \t]*(?:///|//|#|\*(?!\*))?[ \t]*")


class Theory:
    """The headings, numbered list items, bold titles and decision rows of docs/theory.md."""

    def __init__(self, text):
        self.sections = {}  # "2.4" -> section text (to the next heading of the same or a higher level)
        self.appendices = set()
        self.decisions = set()
        lines = text.split("\n")
        heads = []
        for n, line in enumerate(lines):
            m = re.match(r"(#{1,6})\s+(.*)", line)
            if m:
                heads.append((n, len(m.group(1)), m.group(2).strip()))
        for idx, (n, level, title) in enumerate(heads):
            end = len(lines)
            for n2, level2, _ in heads[idx + 1:]:
                if level2 <= level:
                    end = n2
                    break
            body = "\n".join(lines[n:end])
            m = re.match(r"(?:<a [^>]*></a>\s*)?(" + NUM + r")\.?(?:\s|$)", title)
            if m:
                self.sections[m.group(1)] = body
            m = re.match(r"(?:<a [^>]*></a>\s*)?Appendix\s+([A-Z])\b", title)
            if m:
                self.appendices.add(m.group(1))
        for line in self.sections.get("0", "").split("\n"):
            m = re.match(r"\|\s*(?:<a [^>]*></a>\s*)?\**(" + DEC + r")\**\s*\|", line)
            if m:
                self.decisions.add(m.group(1))

    def has_item(self, section, k):
        return re.search(r"(?m)^\s*(?:[-*]\s+)?" + str(k) + r"\.\s", self.sections[section]) is not None

    def has_title(self, section, title):
        return title.lower() in " ".join(self.sections[section].lower().split())


def decision_range(a, b):
    """D1–D5 → D1 … D5 (the numbered rows between; lettered rows only as named)."""
    na, nb = int(re.match(r"D(\d+)", a).group(1)), int(re.match(r"D(\d+)", b).group(1))
    if nb < na:
        return None
    return [a] + ["D%d" % n for n in range(na + 1, nb)] + [b]


def check_section(theory, m):
    """Errors for one §-reference match."""
    errors = []
    a, b = m.group("a"), m.group("b")
    for s in [a] + ([b] if b else []):
        if s not in theory.sections:
            errors.append("§%s is not a heading of %s" % (s, THEORY))
    if errors:
        return errors
    if m.group("i"):
        lo, hi = int(m.group("i")), int(m.group("j") or m.group("i"))
        for k in range(lo, hi + 1):
            if not theory.has_item(a, k):
                errors.append("§%s has no numbered item %d" % (a, k))
    if m.group("title") and not theory.has_title(a, m.group("title")):
        errors.append('§%s has no paragraph or heading "%s"' % (a, m.group("title")))
    return errors


def check_decision(theory, m):
    a, b = m.group("a"), m.group("b")
    names = decision_range(a, b) if b else [a]
    if names is None:
        return ["%s–%s is not a range" % (a, b)]
    return ["%s is not a row of the decisions table (§0)" % d for d in names if d not in theory.decisions]


def parse_citation(theory, text, pos):
    """Parses the reference list that starts at text[pos] (just after "theory").

    Returns (references, errors); references is empty if the word is not a citation.
    """
    refs, errors = [], []
    m = re.compile(r"\s*").match(text, pos)
    p = m.end()
    first = True
    while True:
        for kind, rx in (("section", SECTION), ("decision", DECISION), ("appendix", APPENDIX)):
            m = rx.match(text, p)
            if m:
                break
        else:
            m = None
        if not m:
            break
        refs.append(m.group(0))
        if kind == "section":
            errors += check_section(theory, m)
        elif kind == "decision":
            errors += check_decision(theory, m)
        elif m.group("a") not in theory.appendices:
            errors.append("Appendix %s is not a heading of %s" % (m.group("a"), THEORY))
        p = m.end()
        first = False
        sep = SEPARATOR.match(text, p)
        if not sep:
            break
        # A separator continues the list only if another reference follows it.
        nxt = sep.end()
        if not any(rx.match(text, nxt) for rx in (SECTION, DECISION, APPENDIX)):
            break
        p = nxt
    if first:
        bare = BARE_NUMBER.match(text, pos)
        if bare:
            if bare.group(1).startswith("S"):
                errors.append("'theory S…' is the supplement's numbering: write 'supplement S…' or cite a "
                              "section of %s" % THEORY)
            else:
                errors.append("'theory %s…' lacks '§'" % bare.group(1))
    return refs, errors


def flatten(text):
    """The text with comment line breaks replaced by spaces, and the line of each character."""
    out, line_of = [], []
    line, last = 1, 0
    for m in CONTINUATION.finditer(text):
        out.append(text[last:m.start()])
        line_of.extend([line] * (m.start() - last))
        out.append(" ")
        line_of.append(line)
        line += text.count("\n", m.start(), m.end())
        last = m.end()
    out.append(text[last:])
    line_of.extend([line] * (len(text) - last))
    return "".join(out), line_of


def check_text(theory, name, text, listing=None):
    """Errors ("name:line: message") for one file's text."""
    errors = []
    flat, line_of = flatten(text)
    for m in THEORY_WORD.finditer(flat):
        refs, errs = parse_citation(theory, flat, m.end())
        line = line_of[m.start()]
        if listing is not None and refs:
            listing.append("%s:%d: theory %s" % (name, line, ", ".join(refs)))
        errors += ["%s:%d: %s" % (name, line, e) for e in errs]
    for n, l in enumerate(text.split("\n"), 1):
        for m in FORBIDDEN.finditer(l):
            errors.append("%s:%d: cites %s, which is not in the repository (cite docs/theory.md, "
                          "docs/architecture.md, docs/kernels.md …)" % (name, n, m.group(0)))
    return errors


def scanned_files(root):
    for f in SCANNED_FILES:
        if os.path.isfile(os.path.join(root, f)):
            yield f
    for d in SCANNED_DIRS:
        for dirpath, dirnames, filenames in os.walk(os.path.join(root, d)):
            dirnames.sort()
            for f in sorted(filenames):
                rel = os.path.relpath(os.path.join(dirpath, f), root)
                if f.endswith(SCANNED_SUFFIXES) and rel not in (THEORY, SELF):
                    yield rel


def check_tree(root, listing=None):
    with open(os.path.join(root, THEORY), encoding="utf-8") as f:
        theory_text = f.read()
    theory = Theory(theory_text)
    errors = []
    count = 0
    for rel in scanned_files(root):
        with open(os.path.join(root, rel), encoding="utf-8", errors="replace") as f:
            found = []
            errors += check_text(theory, rel, f.read(), found)
            count += len(found)
            if listing is not None:
                listing += found
    return errors, count


def self_test():
    theory = Theory(
        "# t\n## 0. Decisions\n| # | topic |\n|---|---|\n| D4 | x |\n| <a id=\"d4a\"></a>D4a | y |\n| D5 | z |\n"
        "## 2. Sourcing\n### 2.4 Closed forms\n1. one\n2. two\n**Geometry.** text\n"
        "## 9. Aperture\n1. a\n2. b\n## Appendix A. Script\n")
    cases = [
        # (text, expected number of errors, what it shows)
        ("// theory §2.4 item 2, §0 D4a/D5", 0, "a valid list"),
        ("// (theory §2.4's\n// item 1; §2 \"Geometry\")", 0, "a list across comment lines"),
        ("// theory §2.4 \"Geometry\", Appendix A, D4–D5", 0, "titles, appendices, ranges"),
        ("// theory §4.99 says", 1, "a section that is not a heading"),
        ("// theory §9.5", 1, "a sub-number that is an item, not a heading"),
        ("// theory §2.4 item 3", 1, "an item that does not exist"),
        ("// theory §2.4 items 1–3", 1, "a range of items past the end"),
        ("// theory §0 D17", 1, "a decision that does not exist"),
        ("// theory §2.4, §0 D4, D9", 1, "a bad decision later in a list"),
        ("// theory §2.4\n// \"Nothing\"", 1, "a title that does not exist"),
        ("// theory 6.7", 1, "a missing §"),
        ("// theory S6.1", 1, "the supplement's numbering"),
        ("// see design.md §4.1", 1, "a file that is not in the repository"),
        ("# style.md §2.6", 1, "the other one"),
        ("// thin-phase theory holds for h/λ ≲ 0.2", 0, "the word alone"),
    ]
    failed = 0
    for text, expected, what in cases:
        errs = check_text(theory, "case", text)
        if len(errs) != expected:
            failed += 1
            print("FAIL (%s): %r gave %d error(s), expected %d: %s" % (what, text, len(errs), expected, errs))
    print("self-test: %d of %d cases passed" % (len(cases) - failed, len(cases)))
    return 1 if failed else 0


def main(argv):
    if argv[1:] == ["--self-test"]:
        return self_test()
    if len(argv) < 2:
        print(__doc__)
        return 2
    listing = [] if "--list" in argv[2:] else None
    errors, count = check_tree(argv[1], listing)
    for l in listing or []:
        print(l)
    for e in errors:
        print("error: " + e)
    print("%d citations of %s checked, %d error(s)" % (count, THEORY, len(errors)))
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
