#!/usr/bin/env bash
# Whether vtkdf's outputs are bit-identical to those of an earlier commit: for a change
# that must not alter results (a reorganization, a speed-up that keeps the arithmetic).
# Builds BASE_REF's vtkdf in a git worktree of it, ./build-base (its build tree
# build-base/build sits where ./build sits in this one, so that ccache, given
# CCACHE_BASEDIR, reuses the objects of the files that did not change), runs every case of
# Testing/Outputs/cases.txt with it and with BUILD_DIR's vtkdf (default ./build, as
# Testing/setup.sh makes it), and compares every file they write (Testing/Outputs/compare.py).
# usage: Testing/run-output-comparison.sh BASE_REF [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
base_ref=${1:?usage: Testing/run-output-comparison.sh BASE_REF [BUILD_DIR]}
build=$(cd "${2:-build}" && pwd)
if ! git rev-parse --verify --quiet "$base_ref^{commit}" >/dev/null; then
  echo "run-output-comparison: $base_ref is not a commit of this repository" >&2
  exit 2
fi
base_commit=$(git rev-parse "$base_ref^{commit}")
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# The earlier vtkdf, built once per commit (build-base/build/COMMIT names what it holds).
base_vtkdf=$root/build-base/build/bin/vtkdf
if [ ! -x "$base_vtkdf" ] || [ "$(cat build-base/build/COMMIT 2>/dev/null)" != "$base_commit" ]; then
  echo "== building vtkdf at $base_commit in build-base"
  git worktree remove --force build-base 2>/dev/null || rm -rf build-base
  git worktree prune
  git worktree add --detach build-base "$base_commit" >/dev/null
  export CCACHE_BASEDIR=$root/build-base
  cmake -S build-base -B build-base/build -DCMAKE_BUILD_TYPE=Release \
    -DPython3_EXECUTABLE=/usr/bin/python3 -DDF_WERROR="${DF_WERROR:-OFF}" >/dev/null
  cmake --build build-base/build -j "$(nproc)" --target vtkdf >/dev/null
  echo "$base_commit" >build-base/build/COMMIT
fi

# Runs every case with one vtkdf into one folder; the cases run in file order (later
# ones may read earlier ones' outputs).
run_cases() {
  local vtkdf=$1 out=$2 line name args
  mkdir -p "$out"
  while IFS= read -r line; do
    [[ $line =~ ^[[:space:]]*(#|$) ]] && continue
    name=$(sed -E 's/^[[:space:]]*([^|[:space:]]+)[[:space:]]*\|.*/\1/' <<<"$line")
    args=$(sed -E 's/^[^|]*\|[[:space:]]*//' <<<"$line")
    args=${args//DATA/$root/Testing/Data}
    args=${args//OUT/$out}
    local run=()
    [[ $name == render* ]] && run=(xvfb-run -a -s "-screen 0 1280x1024x24")
    # shellcheck disable=SC2086
    if ! "${run[@]}" "$vtkdf" $args >"$out/../$name.$(basename "$out").log" 2>&1; then
      echo "$name: vtkdf failed ($vtkdf)"
      cat "$out/../$name.$(basename "$out").log"
      return 1
    fi
  done <Testing/Outputs/cases.txt
}
echo "== the cases with $base_ref's vtkdf"
run_cases "$base_vtkdf" "$work/expected"
echo "== the cases with $build/bin/vtkdf"
run_cases "$build/bin/vtkdf" "$work/actual"
/usr/bin/python3 Testing/Outputs/compare.py "$work/expected" "$work/actual"
