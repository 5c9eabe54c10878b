#!/usr/bin/env bash
# vtkdf end to end on bundled data: every subcommand, chained as a user would (linfac's
# field into medial, voxelize's masks into chamfer), the --timing line's format, the
# files written, and the failures that must give a non-zero exit status.
# usage: TestCli.sh VTKDF DATA_DIR OUT_DIR
set -u
vtkdf=$1
data=$2
out=$3
failures=0
fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}
mkdir -p "$out"
rm -f "$out"/*

# run NAME REGEX FILE... -- ARGS: runs vtkdf ARGS, expects status 0, a timing line
# matching REGEX and non-empty FILEs.
run() {
  local name=$1 regex=$2
  shift 2
  local files=()
  while [ "$1" != "--" ]; do
    files+=("$1")
    shift
  done
  shift
  local line
  if ! line=$("$vtkdf" "$@" 2>"$out/$name.err"); then
    fail "$name: exit status $? ($(head -c 300 "$out/$name.err"))"
    return
  fi
  echo "$line"
  grep -Eq "$regex" <<<"$line" || fail "$name: no timing line matching $regex"
  for f in "${files[@]}"; do
    [ -s "$f" ] || fail "$name: $f not written"
  done
}

timing='backend=cpu renderer="cpu" time_s=[0-9.]+'
run linfac "^vtkdf: linfac dims=[0-9]+x[0-9]+x[0-9]+ $timing culling_factor=[0-9.]+ stages=sites:" \
  "$out/linfac.vti" "$out/linfac.png" -- \
  linfac "$data/bunny_small.vtp" -o "$out/linfac.vti" --resolution 24 --signed \
  --arrays distance,point --backend cpu --timing --png "$out/linfac.png"
run medial "^vtkdf: medial dims=[0-9]+x[0-9]+x[0-9]+ $timing medial_voxels=[1-9]" \
  "$out/medial.vti" "$out/medial.vtp" -- \
  medial "$out/linfac.vti" -o "$out/medial.vti" --points "$out/medial.vtp" --backend cpu --timing
run voxelize "^vtkdf: voxelize dims=[0-9]+x[0-9]+x[0-9]+ $timing" "$out/voxels.vti" -- \
  voxelize "$data/bunny_small.vtp" -o "$out/voxels.vti" --resolution 24 --backend cpu --timing
run chamfer "^vtkdf: chamfer dims=[0-9]+x[0-9]+x[0-9]+ $timing layers=[1-9]" "$out/chamfer.vti" -- \
  chamfer "$out/voxels.vti" -o "$out/chamfer.vti" --metric manhattan --backend cpu --timing
run segment "^vtkdf: segment dims=[0-9]+x[0-9]+x[0-9]+ $timing regions=2 patches=[0-9]+ refused_merges=[0-9]+ stages=patches:" \
  "$out/segment.vti" "$out/segment.png" -- \
  segment "$data/plane.vtp" -o "$out/segment.vti" --resolution 20 --backend cpu --timing \
  --png "$out/segment.png" --surface "$out/segment.vtp"
[ -s "$out/segment.vtp" ] || fail "segment: $out/segment.vtp not written"
run union "^vtkdf: union pieces=4 queries=1 backend=cpu time_s=[0-9.]+ faces_visited=[1-9]" \
  "$out/union.vtp" -- \
  union "$data/hubo_ankle_convex4.vtp" -o "$out/union.vtp" --query 0 0.01 0.01 --timing
# blend: a field with itself is itself, at any T.
if "$vtkdf" blend "$out/segment.vti" "$out/segment.vti" -t 0.3 -o "$out/blend.vti" \
  --png "$out/blend.png" 2>"$out/blend.err"; then
  [ -s "$out/blend.vti" ] && [ -s "$out/blend.png" ] || fail "blend: outputs not written"
else
  fail "blend: exit status $? ($(head -c 300 "$out/blend.err"))"
fi

# Failures: a message and a non-zero status, never a crash or a silent success.
expect_failure() {
  local name=$1
  shift
  "$vtkdf" "$@" >"$out/$name.out" 2>&1
  local status=$?
  if [ $status -eq 0 ] || [ $status -gt 128 ]; then
    fail "$name: exit status $status, expected an error"
  fi
}
expect_failure unwritable linfac "$data/bunny_small.vtp" -o /nonexistent/dir/x.vti --resolution 16
expect_failure badbackend linfac "$data/bunny_small.vtp" -o "$out/x.vti" --backend nope
expect_failure missing linfac "$data/no_such_mesh.vtp" -o "$out/x.vti"
expect_failure subcommand frobnicate
expect_failure blendmesh blend "$data/plane.vtp" "$out/segment.vti" -t 0.5 -o "$out/x.vti"
expect_failure blendnot blend "$out/segment.vti" "$out/segment.vti" -o "$out/x.vti"
[ -e "$out/x.vti" ] && fail "a failed run wrote $out/x.vti"

# --help (alone or after a subcommand): the usage on stdout, status 0.
for args in "--help" "-h" "medial --help"; do
  # shellcheck disable=SC2086
  "$vtkdf" $args >"$out/help.out" 2>"$out/help.err" || fail "vtkdf $args: exit status $?"
  grep -q "usage: vtkdf linfac" "$out/help.out" || fail "vtkdf $args: no usage on stdout"
done

echo "$failures failures"
[ $failures -eq 0 ]
