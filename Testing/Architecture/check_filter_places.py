"""Every filter in every place a filter must be (CTest: Architecture.FilterPlaces).

usage: check_filter_places.py SOURCE_DIR

A filter is a class of Filters/vtk*.h with a New() that is not an implicit function
(vtkMeshDistanceFunction is documented and tested with its filter, and has no proxy or
subcommand of its own: ParaView's clip filters list only their own functions).
docs/architecture.md ("Adding a
filter") lists the places in the order one fills them; this checks that each filter is:
1. in the module's class list (cmake/vtkDistanceFieldsModule.cmake);
2. a ParaView proxy of that class (ParaView/DistanceFieldsFilters.xml);
3. run by a case of the plugin's tests (Testing/ParaView/cases.py, by proxy name);
4. run by a vtkdf subcommand (Programs/vtkdf/), or listed in NO_SUBCOMMAND with why;
5. named on a page of docs/ and in the README's table;
6. run by a Python test (Testing/Python/).
A writer (a subclass of vtkWriter: vtkOpenVDBLevelSetWriter) writes a filter's output
and is documented with it: it needs places 1, 4, 5's page and 6 (ParaView's writers are
ParaView's own, and the plugin is built without OpenVDB).
Exits 1 and prints every missing place.
"""
import glob
import os
import re
import sys

# Filters with no vtkdf subcommand of their own, and why (none today).
NO_SUBCOMMAND = {}


def text(root, *patterns):
    found = []
    for pattern in patterns:
        for path in sorted(glob.glob(os.path.join(root, pattern))):
            found.append(open(path, encoding="utf-8").read())
    return "\n".join(found)


def main():
    root = sys.argv[1]
    filters, writers = [], set()
    for header in sorted(glob.glob(os.path.join(root, "Filters", "vtk*.h"))):
        name = os.path.basename(header)[:-2]
        source = open(header).read()
        if re.search(r"static\s+%s\s*\*\s*New\s*\(\s*\)" % name, source) and \
                "public vtkImplicitFunction" not in source:
            filters.append(name)
            if "public vtkWriter" in source:
                writers.add(name)
    places = [
        ("the class list of cmake/vtkDistanceFieldsModule.cmake",
         text(root, "cmake/vtkDistanceFieldsModule.cmake"), lambda c: '/Filters/%s"' % c),
        ("a proxy of ParaView/DistanceFieldsFilters.xml",
         text(root, "ParaView/DistanceFieldsFilters.xml"), lambda c: 'class="%s"' % c),
        ("a case of Testing/ParaView/cases.py",
         text(root, "Testing/ParaView/cases.py"), lambda c: 'filter="%s"' % c[3:]),
        ("a vtkdf subcommand (Programs/vtkdf/)",
         text(root, "Programs/vtkdf/*.cxx"), lambda c: c),
        ("a page of docs/", text(root, "docs/*.md"), lambda c: "`%s`" % c),
        ("the README's table", text(root, "README.md"), lambda c: "| `%s` |" % c),
        ("a Python test (Testing/Python/)", text(root, "Testing/Python/*.py"), lambda c: c),
    ]
    problems = []
    for name in filters:
        for where, corpus, token in places:
            if where.startswith("a vtkdf") and name in NO_SUBCOMMAND:
                continue
            if name in writers and ("ParaView" in where or "README" in where):
                continue
            if token(name) not in corpus:
                problems.append("%s: not in %s" % (name, where))
    for problem in problems:
        print(problem)
    print("%d filters, %d places each: %d missing" % (len(filters), len(places), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
