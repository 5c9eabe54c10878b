"""A rule of the shaders, checked on the sources (CTest: Architecture.Shaders).

usage: check_shaders.py SOURCE_DIR

- No shader declares a sized array of doubles (double, dvecN, dmatN): NVIDIA's GL (driver
  580, on an H100) kept such an array, indexed at run time, in single precision, which
  llvmpipe in CI cannot show (the medial pass marked voxels the CPU does not). Hold the
  doubles' bits instead (uvec2, packDouble2x32), as Shaders/MedialAxis.comp.glsl does.
  Buffer blocks' run-time sized arrays (`double x[];`) are memory, not such arrays.
Exits 1 and prints every violation.
"""
import os
import re
import sys

DOUBLE = r"\b(?:double|dvec[234]|dmat[234](?:x[234])?)\b"
# `dvec3 name[8]`, `double a, b[2]`, `dvec3[8] name`: a size inside the brackets.
SIZED = re.compile(DOUBLE + r"(?:\s*\[\s*[^\]\s][^\]]*\]\s*\w+|\s+[\w\s,]*?\w+\s*\[\s*[^\]\s][^\]]*\])")


def strip_comments(text):
    text = re.sub(r"/\*.*?\*/", lambda m: "\n" * m.group(0).count("\n"), text, flags=re.S)
    return re.sub(r"//[^\n]*", "", text)


def violations(path):
    found = []
    for number, line in enumerate(strip_comments(open(path).read()).split("\n"), 1):
        for statement in line.split(";"):
            # A declaration, not an expression that reads an array: `double r = a[i]`
            # has an `=` before the brackets.
            head = statement.split("=")[0]
            if SIZED.search(head):
                found.append("%s:%d: %s" % (path, number, line.strip()))
                break
    return found


def main():
    if len(sys.argv) != 2:
        print(__doc__)
        return 2
    shaders = os.path.join(sys.argv[1], "Shaders")
    found = []
    for name in sorted(os.listdir(shaders)):
        if name.endswith(".glsl"):
            found += violations(os.path.join(shaders, name))
    for line in found:
        print("a sized array of doubles (kept in single precision by some GLs): " + line)
    print("%d violations" % len(found))
    return 1 if found else 0


if __name__ == "__main__":
    sys.exit(main())
