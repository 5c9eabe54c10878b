#!/usr/bin/env bash
# The BSD-only build: configured with -DDF_USE_CGAL=OFF into ./build-bsd (after
# Testing/setup.sh has installed what the project needs), it must not include a header
# of CGAL, GMP or MPFR (the compiler's dependency files say what each object read) nor
# link GMP or MPFR (ldd), and passes the tests that the option changes: the crossing
# search, the segmented field's tests, the mapper's accuracy, vtkdf end to end and the
# bad-input corpus's segmented cases (the other filters do not use CGAL). Extra arguments
# go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-bsd -DCMAKE_BUILD_TYPE=Release -DDF_USE_CGAL=OFF \
  -DPython3_EXECUTABLE=/usr/bin/python3 -DDF_WERROR="${DF_WERROR:-OFF}" >/dev/null
# What the tests below run: vtkdf, the Python packages and the tests' programs.
cmake --build build-bsd -j "$(nproc)" --target vtkdf vtkDistanceFieldsPython \
  vtkDistanceFieldsRenderingPython TestCrossingCore TestSegmentedDistanceField \
  TestSegmentedDistanceContour TestSegmentImages TestDistanceFieldBlend \
  TestSegmentedDistanceVolumeMapper

status=0
mapfile -t depfiles < <(find build-bsd -name '*.o.d')
[ "${#depfiles[@]}" -gt 0 ] || { echo "FAIL: no dependency files in build-bsd"; exit 1; }
if readers=$(grep -lE '/CGAL/|/gmp(xx)?\.h|/mpfr\.h' "${depfiles[@]}"); then
  echo "FAIL: objects of the BSD-only build read CGAL's, GMP's or MPFR's headers:"
  echo "$readers"
  status=1
fi
mapfile -t binaries < <(find build-bsd -type f \( -name "*.so*" -o -perm -u+x \) ! -name "*.py" ! -name "*.sh")
for binary in "${binaries[@]}"; do
  if ldd "$binary" 2>/dev/null | grep -E 'libgmp|libmpfr'; then
    echo "FAIL: $binary links GMP or MPFR"
    status=1
  fi
done
echo "BSD-only build: ${#depfiles[@]} objects and ${#binaries[@]} libraries and programs" \
  "without CGAL, GMP or MPFR"
[ "$status" = 0 ] || exit 1

cd build-bsd
xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" ctest --output-on-failure -j "$(nproc)" \
  -R '^(Core\.Crossings|Segment\.|BadInput\.(cli\..*\.segment|python\.segment)$|Cli\.vtkdf|Render\.Mapper\.accuracy\.)' "$@"
