"""The architecture's rules, checked on the sources (CTest: Architecture.Dependencies).

usage: check_dependencies.py SOURCE_DIR

- No file of Filters/Core includes a VTK header: the cores are plain C++.
- Filters/Core/<Family> includes, of another family, only a header in the PUBLIC_HEADERS of
  a family in its DEPENDS (Filters/Core/CMakeLists.txt, df_add_core_library); Common is
  every family's. Includes name the family ("Family/Header.h"); a bare name may only be a
  generated shader header.
- The filters (Filters/*.h, *.cxx) include only public core headers, and never the
  rendering module (Rendering/): a filter works where nothing renders.
- The families' dependencies have no cycle.
Exits 1 and prints every violation.
"""
import os
import re
import sys

INCLUDE = re.compile(r'^\s*#\s*include\s*([<"])([^>"]+)[>"]', re.M)


def families(core_cmake):
    """{family: (depends, public_headers, shaders)} from the df_add_core_library calls."""
    text = re.sub(r"#[^\n]*", "", open(core_cmake).read())
    found = {}
    for call in re.finditer(r"df_add_core_library\(([^)]*)\)", text):
        words = call.group(1).split()
        name, sections, key = words[0], {}, None
        for word in words[1:]:
            if word in ("SOURCES", "PUBLIC_HEADERS", "DEPENDS", "SHADERS"):
                key = word
                sections[key] = []
            elif key:
                sections[key].append(word)
        found[name] = (set(sections.get("DEPENDS", [])), set(sections.get("PUBLIC_HEADERS", [])),
                       {s.replace(".", "_") + ".h" for s in sections.get("SHADERS", [])})
    return found


def sources(folder):
    for root, _, names in os.walk(folder):
        for name in sorted(names):
            if name.endswith((".h", ".cxx")):
                yield os.path.join(root, name)


def main():
    root = sys.argv[1]
    core = os.path.join(root, "Filters", "Core")
    known = families(os.path.join(core, "CMakeLists.txt"))
    known["Common"] = (set(), {"Common/" + n for n in os.listdir(os.path.join(core, "Common"))},
                       set())
    shaders = set().union(*(f[2] for f in known.values()))
    core_headers = {n for f in os.listdir(core) if os.path.isdir(os.path.join(core, f))
                    for n in os.listdir(os.path.join(core, f)) if n.endswith(".h")}
    problems = []

    for path in sources(core):
        relative = os.path.relpath(path, root)
        family = os.path.relpath(path, core).split(os.sep)[0]
        if family not in known:
            problems.append("%s: its folder is no family of Filters/Core/CMakeLists.txt" % relative)
            continue
        depends = known[family][0]
        for kind, name in INCLUDE.findall(open(path).read()):
            if re.match(r"vtk|vtksys/", name):
                problems.append("%s includes %s: the cores are free of VTK" % (relative, name))
            if kind != '"' or name.startswith("vtk"):
                continue
            if "/" not in name:
                if name in core_headers or name not in shaders:
                    problems.append("%s includes \"%s\": name its family (\"Family/%s\"), or a "
                                    "generated shader header" % (relative, name, name))
                continue
            other = name.split("/")[0]
            if other in (family, "Common"):
                continue
            if other not in known:
                if os.path.isdir(os.path.join(core, other)):
                    problems.append("%s includes %s: no such family" % (relative, name))
                continue  # a library's own header (qhull's)
            if other not in depends:
                problems.append("%s includes %s: %s does not depend on %s (DEPENDS)" %
                                (relative, name, family, other))
            elif name not in known[other][1]:
                problems.append("%s includes %s, a private header of %s (PUBLIC_HEADERS)" %
                                (relative, name, other))

    for path in sources(os.path.join(root, "Filters")):
        if path.startswith(core + os.sep):
            continue
        relative = os.path.relpath(path, root)
        for kind, name in INCLUDE.findall(open(path).read()):
            family = name.split("/")[0]
            if family in known and family != "Common" and name not in known[family][1]:
                problems.append("%s includes %s, a private header of %s: filters call the "
                                "families' entry points" % (relative, name, family))
            if name.startswith("vtkSegmentedDistanceVolumeMapper") or \
                    name.startswith("vtkDistanceFieldsRendering") or \
                    os.path.exists(os.path.join(root, "Rendering", "Core", name)):
                problems.append("%s includes %s: the filters never depend on Rendering/" %
                                (relative, name))

    # No cycle among the families.
    state = {}

    def visit(family, trail):
        if state.get(family) == "done":
            return
        if state.get(family) == "open":
            problems.append("the families depend on each other in a cycle: %s" %
                            " -> ".join(trail + [family]))
            return
        state[family] = "open"
        for dependency in sorted(known.get(family, (set(),))[0]):
            visit(dependency, trail + [family])
        state[family] = "done"

    for family in sorted(known):
        visit(family, [])

    for problem in problems:
        print("FAIL:", problem)
    print("%d families, %d violations" % (len(known), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
