"""The adapters' shape and the functions' length, checked on the sources
(CTest: Architecture.Functions).

usage: check_functions.py SOURCE_DIR

- ProcessRequest and RequestData are overridden only by the module's wrapped bases
  (vtkDistanceFieldImageAlgorithm, vtkDistanceFieldPolyDataAlgorithm,
  vtkDistanceFieldDataSetAlgorithm, vtkDistanceFieldUnstructuredGridAlgorithm: one per
  output type), which run every
  request the same way (Filters/vtkDistanceFieldRun.h); a filter supplies Execute.
- A filter's Execute is at most 120 lines: it maps VTK's data onto one core entry point
  and back, and holds no algorithm.
- No function of Filters/, Rendering/ or Programs/ is over 150 lines, but for those
  listed in LONG below (none today), each with the passes it still has to be split
  into; a listed function that got shorter must leave the list, so that it only shrinks.
- No source file (.cxx, .h) of Filters/, Rendering/, Programs/ or Testing/ is over 1,000
  lines: a longer one holds more than one thing, and is split by what it holds.
A function is counted from the first line of its signature to its closing brace (the
sources are clang-formatted: a function's braces stand at the start of a line), lambdas
inside it included. Exits 1 and prints every violation.
"""
import os
import re
import sys

ADAPTER_LIMIT = 120
FUNCTION_LIMIT = 150
FILE_LIMIT = 1000
BASES = {"Filters/vtkDistanceFieldImageAlgorithm.cxx", "Filters/vtkDistanceFieldPolyDataAlgorithm.cxx",
         "Filters/vtkDistanceFieldDataSetAlgorithm.cxx",
         "Filters/vtkDistanceFieldUnstructuredGridAlgorithm.cxx"}
# Functions still over the limit: "path:name" -> what they hold.
LONG = {
}

CONTROL = re.compile(r"^(if|for|while|switch|else|do|try|catch|return)\b")
SCOPE = re.compile(r"^(template\s*<[^>]*>\s*)?(namespace|extern|struct|class|enum|union)\b")
LAMBDA = re.compile(r"\[[^\]]*\]\s*\(")


def indent(line):
    return len(line) - len(line.lstrip(" "))


def functions(path):
    """(name, first line, length) of every function, member function and lambda whose
    body opens with a brace alone on its line (clang-format's style for them)."""
    lines = open(path, encoding="utf-8").read().split("\n")
    found = []
    for i, line in enumerate(lines):
        if line.strip() != "{":
            continue
        k = indent(line)
        h = i
        while h > 0:
            above = lines[h - 1]
            text = above.strip()
            if (not text or indent(above) < k or text.startswith(("//", "/*", "*", "#")) or
                    text.endswith((";", "{", "}", ":")) and not text.endswith("::")):
                break
            h -= 1
        head = " ".join(l.strip() for l in lines[h:i])
        if not head or "(" not in head or CONTROL.match(head) or SCOPE.match(head):
            continue
        close = next((j for j in range(i + 1, len(lines))
                      if lines[j].startswith(" " * k + "}") and indent(lines[j]) == k), None)
        if close is None:
            continue
        call = re.search(r"([~\w]+)\s*\(", head)
        name = "lambda" if LAMBDA.search(head) else (call.group(1) if call else head)
        found.append((name, h + 1, close - h + 1))
    return found


def sources(root, folders, suffixes=(".cxx",)):
    for folder in folders:
        for base, _, names in os.walk(os.path.join(root, folder)):
            for name in sorted(names):
                if name.endswith(suffixes):
                    yield os.path.relpath(os.path.join(base, name), root)


def main():
    root = sys.argv[1]
    problems = []
    seen_long = set()
    for path in sources(root, ("Filters", "Rendering", "Programs")):
        text = open(os.path.join(root, path), encoding="utf-8").read()
        adapter = re.match(r"Filters/vtk\w+\.cxx$", path) is not None
        for name, line, length in functions(os.path.join(root, path)):
            where = "%s:%d %s" % (path, line, name)
            key = "%s:%s" % (path, name)
            if adapter and name in ("ProcessRequest", "RequestData") and path not in BASES:
                problems.append("%s: only the wrapped bases run requests (%s); a filter "
                                "supplies Execute" % (where, ", ".join(sorted(BASES))))
            if adapter and name == "Execute" and length > ADAPTER_LIMIT:
                problems.append("%s: %d lines, over the adapters' %d" % (where, length, ADAPTER_LIMIT))
            if length > FUNCTION_LIMIT:
                if key in LONG:
                    seen_long.add(key)
                else:
                    problems.append("%s: %d lines, over %d: split it into passes named in one "
                                    "driver" % (where, length, FUNCTION_LIMIT))
        if adapter and path not in BASES and re.search(r"\bProcessRequest\s*\(", text):
            problems.append("%s: calls or defines ProcessRequest; the bases own it" % path)
    for path in sources(root, ("Filters", "Rendering", "Programs", "Testing"), (".cxx", ".h")):
        count = open(os.path.join(root, path), encoding="utf-8").read().count("\n")
        if count > FILE_LIMIT:
            problems.append("%s: %d lines, over %d: split it by what it holds" %
                            (path, count, FILE_LIMIT))
    for key in sorted(set(LONG) - seen_long):
        problems.append("%s: listed as over %d lines but it is not (any more): take it off "
                        "the list in %s" % (key, FUNCTION_LIMIT, os.path.basename(__file__)))
    for problem in problems:
        print(problem)
    print("%d problem(s)" % len(problems))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
