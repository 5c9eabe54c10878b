"""The plugin's enumerations against the module's tables (CTest: Architecture.Enums).

usage: check_enums.py SOURCE_DIR

Filters/vtkDistanceFieldEnums.cxx holds one table per enumeration property: its name, the
proxies of ParaView/DistanceFieldsFilters.xml that have it, and each value's number, name
and vtkdf word; the filters' checks and PrintSelf, and vtkdf's options, read the same
tables. This checks that every such proxy's property lists exactly the table's values
and names, and that every EnumerationDomain of the XML belongs to a table. Exits 1 and
prints every difference.
"""
import os
import re
import sys
import xml.etree.ElementTree as ET

TABLE = re.compile(r'const EnumTable (\w+)\("(\w+)",\s*\{([^}]*)\},\s*\{(.*?)\}\);', re.S)
VALUE = re.compile(r'\{\s*(-?\d+),\s*"(\w+)",\s*"([\w-]+)"\s*\}')


def main():
    root = sys.argv[1]
    source = open(os.path.join(root, "Filters", "vtkDistanceFieldEnums.cxx")).read()
    tables = {}
    for name, prop, proxies, values in TABLE.findall(source):
        entries = [(int(v), n) for v, n, _ in VALUE.findall(values)]
        for proxy in re.findall(r'"(\w+)"', proxies):
            tables[(proxy, prop)] = (name, entries)
    problems = []
    if not tables:
        problems.append("no table found in Filters/vtkDistanceFieldEnums.cxx")
    xml = ET.parse(os.path.join(root, "ParaView", "DistanceFieldsFilters.xml")).getroot()
    seen = set()
    for proxy in xml.iter():
        if not proxy.tag.endswith("Proxy") or proxy.get("name") is None:
            continue
        for prop in proxy:
            domain = prop.find("EnumerationDomain")
            if domain is None:
                continue
            key = (proxy.get("name"), prop.get("name"))
            entries = [(int(e.get("value")), e.get("text")) for e in domain.findall("Entry")]
            if key not in tables:
                problems.append("%s.%s: an enumeration without a table in "
                                "vtkDistanceFieldEnums.cxx" % key)
                continue
            seen.add(key)
            name, expected = tables[key]
            if entries != expected:
                problems.append("%s.%s: the XML lists %s, the table %s (enums::%s)"
                                % (key + (entries, expected, name)))
    for key in sorted(set(tables) - seen):
        problems.append("%s.%s: in table enums::%s but not in the XML" % (key + (tables[key][0],)))
    for problem in problems:
        print(problem)
    print("%d tables' proxies, %d problem(s)" % (len(tables), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
