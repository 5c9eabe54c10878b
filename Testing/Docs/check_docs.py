#!/usr/bin/env python3
"""Checks the documentation as a reader would meet it: the README at most 150 lines,
every relative link of the README and docs/*.md naming a file or folder of this
repository (not one outside it; an anchor, a heading of its page), every docs page reachable from the README, and every
filter of Filters/ and Rendering/ with a page that names it.

usage: check_docs.py SOURCE_DIR
"""
import glob
import os
import re
import sys

LINK = re.compile(r"\[[^\]]*\]\(([^)\s]+)\)")


def anchors(path):
    """The anchors GitHub gives a Markdown file's headings."""
    found = set()
    for heading in re.findall(r"^#+\s+(.*)$", open(path, encoding="utf-8").read(), re.M):
        found.add(re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-"))
    return found


def main():
    root = os.path.realpath(sys.argv[1])
    failures = []
    readme = os.path.join(root, "README.md")
    lines = open(readme, encoding="utf-8").read().count("\n")
    if lines > 150:
        failures.append(f"README.md has {lines} lines (at most 150)")
    pages = [readme] + sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    linked = set()
    for page in pages:
        text = open(page, encoding="utf-8").read()
        for target in LINK.findall(text):
            if re.match(r"[a-z]+://", target) or target.startswith(("#", "mailto:")):
                continue
            path = os.path.realpath(os.path.join(os.path.dirname(page), target.split("#")[0]))
            name = os.path.relpath(page, root)
            if os.path.commonpath([root, path]) != root:
                failures.append(f"{name}: link {target} leaves the repository")
            elif not os.path.exists(path):
                failures.append(f"{name}: link {target} names nothing")
            elif "#" in target and target.split("#")[1] not in anchors(path):
                failures.append(f"{name}: link {target} names no heading of its page")
            linked.add(path)
        if "../shared" in text or "shared/docs" in text:
            failures.append(f"{os.path.relpath(page, root)}: mentions a folder outside the repository")
    for page in pages[1:]:
        if page not in linked:
            failures.append(f"{os.path.relpath(page, root)}: no page links to it")
    docs = "".join(open(p, encoding="utf-8").read() for p in pages[1:])
    headers = glob.glob(os.path.join(root, "Filters", "vtk*.h")) + glob.glob(
        os.path.join(root, "Rendering", "vtk*.h"))
    for header in sorted(headers):
        name = os.path.basename(header)[:-2]
        if name not in docs:
            failures.append(f"{name}: no page of docs/ names it")
    for failure in failures:
        print(failure)
    print(f"{len(pages)} pages, {len(linked)} link targets, {len(headers)} classes:",
          "FAILED" if failures else "ok")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
