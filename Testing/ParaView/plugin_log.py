"""Loads the plugin and makes every proxy of its XML that names a class, as ParaView's
GUI does at start-up (pvbatch plugin_log.py PLUGIN XML...). ParaView logs what it cannot
make of a proxy's XML (an element it has no class for, such as a domain another version
has) while it makes the proxy: the test fails on any error or warning line
(FAIL_REGULAR_EXPRESSION, Testing/ParaView/CMakeLists.txt) and passes on the closing
count."""
import sys
import xml.etree.ElementTree as ET

from paraview import servermanager, simple

plugin = sys.argv[1]
simple.LoadPlugin(plugin, remote=True)
made = 0
for path in sys.argv[2:]:
    for group in ET.parse(path).getroot().iter("ProxyGroup"):
        for proxy in group:
            if proxy.get("class") is None or proxy.get("name") is None:
                continue  # a base (its properties reach ParaView through its subclasses)
            if servermanager.CreateProxy(group.get("name"), proxy.get("name")) is None:
                print("ERROR: ParaView made no proxy %s/%s" % (group.get("name"), proxy.get("name")))
                sys.exit(1)
            made += 1
print("made %d proxies of the plugin" % made)
