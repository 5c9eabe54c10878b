#!/usr/bin/env bash
# The module as a user of another project gets it (run by .ci/run, as root, after
# Testing/run-tests.sh has built ./build):
# 1. the install tree: `cmake --install build` under a fresh prefix; the downstream example
#    project (Examples/Downstream) configured with find_package against it, built and run;
#    its Python script, vtkdf and the example program run from there, with no library
#    path set (their RPATHs are relative to themselves);
# 2. the Debian packages: a build for /usr (multiarch libdir), `cpack -G DEB`,
#    `apt-get install ./*.deb`; then the downstream example, vtkdf and the system Python's
#    import with no environment variables at all; then the packages are removed again;
# 3. the ParaView plugin's package (vtkdistancefields-paraview, from ./build-paraview, which
#    Testing/run-paraview-tests.sh builds): installed, loaded by pvbatch by path and
#    through PV_PLUGIN_PATH, a filter run; Debian's paraview package unchanged; removed.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
step() { echo "== $*"; }

# Whether every shared library of the given files resolves (ldd prints "not found").
resolves() {
  local bad
  bad=$(ldd "$@" 2>&1 | grep "not found" || true)
  if [ -n "$bad" ]; then
    echo "unresolved libraries: $bad"
    return 1
  fi
}

step "install tree under $work/prefix"
cmake --install build --prefix "$work/prefix" >/dev/null
prefix="$work/prefix"
python_dir="$prefix/lib/python3/dist-packages"
resolves "$prefix/bin/vtkdf" "$prefix/libexec/vtkdistancefields/MeshToFields" \
  "$python_dir/vtkdistancefields/"*.so
env -u LD_LIBRARY_PATH "$prefix/bin/vtkdf" --help >/dev/null
# The .vdb writer loads OpenVDB's module from beside the library when it first writes.
with_openvdb=$(grep -c "^DF_USE_OPENVDB:BOOL=ON" build/CMakeCache.txt || true)
if [ "$with_openvdb" = 1 ]; then
  resolves "$prefix/lib/libvtkDistanceFieldsOpenVDB.so"
  env -u LD_LIBRARY_PATH "$prefix/bin/vtkdf" linfac Testing/Data/bunny_small.vtp \
    --resolution 32 --band 2 --vdb "$work/band.vdb" >/dev/null
  [ -s "$work/band.vdb" ]
fi
env -u LD_LIBRARY_PATH "$prefix/libexec/vtkdistancefields/MeshToFields" \
  Testing/Data/bunny_small.vtp "$work/fields" 32
ls "$work/fields"/*.vti >/dev/null
cmake -S Examples/Downstream -B "$work/downstream" -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$work/downstream" >/dev/null
"$work/downstream/DownstreamField"
PYTHONPATH="$python_dir" /usr/bin/python3 Examples/Downstream/downstream_field.py

step "Debian packages"
cmake -S . -B build-deb -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DBUILD_TESTING=OFF -DPython3_EXECUTABLE=/usr/bin/python3 -DDF_WERROR="${DF_WERROR:-OFF}" >/dev/null
cmake --build build-deb -j "$(nproc)" >/dev/null
(cd build-deb && rm -f ./*.deb && cpack -G DEB >/dev/null)
for deb in build-deb/*.deb; do
  echo "$deb:"
  dpkg-deb --field "$deb" Package Depends Recommends | sed 's/^/  /'
done
apt-get install -y -qq ./build-deb/*.deb >/dev/null
cleanup() {
  apt-get remove -y -qq vtkdistancefields vtkdistancefields-dev >/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
resolves /usr/bin/vtkdf
env -i PATH=/usr/bin:/bin vtkdf --help >/dev/null
if [ "$with_openvdb" = 1 ]; then
  env -i PATH=/usr/bin:/bin vtkdf linfac Testing/Data/bunny_small.vtp --resolution 32 --band 2 \
    --vdb "$work/band-deb.vdb" >/dev/null
  [ -s "$work/band-deb.vdb" ]
fi
env -i PATH=/usr/bin:/bin /usr/bin/python3 -c \
  "import vtkdistancefields; print('import vtkdistancefields:', vtkdistancefields.__file__)"
(cd "$work" && env -i PATH=/usr/bin:/bin /usr/bin/python3 "$root/Examples/Downstream/downstream_field.py")
env -i PATH=/usr/bin:/bin cmake -S Examples/Downstream -B "$work/downstream-deb" >/dev/null
env -i PATH=/usr/bin:/bin cmake --build "$work/downstream-deb" >/dev/null
env -i PATH=/usr/bin:/bin "$work/downstream-deb/DownstreamField"
cleanup
trap - EXIT
if dpkg-query -W -f='${Status}' vtkdistancefields 2>/dev/null | grep -q "ok installed"; then
  echo "the package is still installed"
  exit 1
fi

# 3. The ParaView plugin's package, made from ./build-paraview (Testing/run-paraview-tests.sh
#    built it there and unpacked python3-paraview, whose modules pvbatch needs, beside it).
step "the ParaView plugin's Debian package"
if [ ! -f build-paraview/CPackConfig.cmake ]; then
  echo "no ./build-paraview: run Testing/run-paraview-tests.sh first"
  exit 1
fi
work=$(mktemp -d)
(cd build-paraview && rm -f ./*.deb && cpack -G DEB >/dev/null)
deb=$(ls build-paraview/vtkdistancefields-paraview_*.deb)
echo "$deb:"
dpkg-deb --field "$deb" Package Depends Recommends | sed 's/^/  /'
dpkg-deb --field "$deb" Depends | grep -q "paraview" || { echo "it does not depend on paraview"; exit 1; }
apt-get install -y -qq "./$deb" >/dev/null
cleanup_plugin() {
  apt-get remove -y -qq vtkdistancefields-paraview >/dev/null || true
  rm -rf "$work"
}
trap cleanup_plugin EXIT
plugins=/usr/lib/x86_64-linux-gnu/paraview-5.11/plugins
resolves "$plugins/DistanceFields/"*.so
# No file of Debian's paraview package changed (its paraview.plugins.xml included).
dpkg --verify paraview
pv_python=build-paraview/python3-paraview/usr/lib/python3/dist-packages
(cd "$work" && env -i PATH=/usr/bin:/bin PYTHONPATH="$root/$pv_python" \
  pvbatch "$root/Testing/ParaView/installed_plugin.py" "$root/Testing/Data/bunny_small.vtp")
(cd "$work" && env -i PATH=/usr/bin:/bin PYTHONPATH="$root/$pv_python" \
  PV_PLUGIN_PATH="$plugins/DistanceFields" \
  pvbatch "$root/Testing/ParaView/installed_plugin.py" "$root/Testing/Data/bunny_small.vtp" auto)
cleanup_plugin
trap - EXIT
if [ -e "$plugins/DistanceFields" ]; then
  echo "the plugin's folder is still there"
  exit 1
fi
echo "install tests passed"
