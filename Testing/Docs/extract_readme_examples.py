#!/usr/bin/env python3
"""Writes the README's C++ and Python examples to files, so that CTest builds and runs
exactly what a reader copies. The README holds one ```cpp block and one ```python block.

usage: extract_readme_examples.py README.md OUT.cxx OUT.py
"""
import re
import sys


def fenced_blocks(text, language):
    return re.findall(r"^```" + language + r"\n(.*?)^```", text, re.S | re.M)


def main():
    readme, out_cxx, out_py = sys.argv[1:4]
    text = open(readme, encoding="utf-8").read()
    for language, path in (("cpp", out_cxx), ("python", out_py)):
        blocks = fenced_blocks(text, language)
        if len(blocks) != 1:
            sys.exit(f"{readme}: expected one ```{language} block, found {len(blocks)}")
        with open(path, "w", encoding="utf-8") as out:
            out.write(blocks[0])


if __name__ == "__main__":
    main()
