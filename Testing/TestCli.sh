#!/usr/bin/env bash
# vtkdf end to end on bundled data: every subcommand, chained as a user would (linfac's
# field into medial and render, voxelize's masks into chamfer, segment's field into
# blend and render), the --timing line's format, the
# files written, the values of the outputs (check_cli_values.py), and the failures that
# must give a non-zero exit status.
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
  # Under the sanitizers, vtkdf render gets Mesa's driver preloaded (Testing/CMakeLists.txt).
  local preload=""
  [[ $name == render* ]] && preload=${VTKDF_RENDER_PRELOAD:-}
  if ! line=$(LD_PRELOAD="$preload" "$vtkdf" "$@" 2>"$out/$name.err"); then
    fail "$name: exit status $? ($(head -c 300 "$out/$name.err"))"
    return
  fi
  echo "$line"
  echo "$line" >>"$out/timing.log"
  grep -Eq "$regex" <<<"$line" || fail "$name: no timing line matching $regex"
  for f in "${files[@]}"; do
    [ -s "$f" ] || fail "$name: $f not written"
  done
}

timing='backend=cpu renderer="cpu" time_s=[0-9.]+'
run linfac "^vtkdf: linfac dims=[0-9]+x[0-9]+x[0-9]+ $timing culling_factor=[0-9.]+ route=scan stages=input:[0-9.e-]+,sites:[0-9.e-]+,culling:[0-9.e-]+,scan:[0-9.e-]+,finalize:[0-9.e-]+,surface:[0-9.e-]+ peak_memory_mb=[0-9.]+$" \
  "$out/linfac.vti" "$out/linfac.png" -- \
  linfac "$data/bunny_small.vtp" -o "$out/linfac.vti" --resolution 24 --signed \
  --arrays distance,point,gradient,barycentric --backend cpu --timing --png "$out/linfac.png"
run linfac-queries "^vtkdf: linfac dims=[0-9]+x[0-9]+x[0-9]+ $timing culling_factor=[0-9.]+ route=queries stages=input:[0-9.e-]+,tree:[0-9.e-]+,queries:[0-9.e-]+ peak_memory_mb=[0-9.]+$" \
  "$out/linfac-queries.vti" -- \
  linfac "$data/bunny_small.vtp" -o "$out/linfac-queries.vti" --resolution 24 --signed \
  --route queries --arrays distance,cellid,feature --backend cpu --timing
run medial "^vtkdf: medial dims=[0-9]+x[0-9]+x[0-9]+ $timing medial_voxels=[1-9]" \
  "$out/medial.vti" "$out/medial.vtp" "$out/medial.png" -- \
  medial "$out/linfac.vti" -o "$out/medial.vti" --points "$out/medial.vtp" --backend cpu --timing \
  --png "$out/medial.png"
run voxelize "^vtkdf: voxelize dims=[0-9]+x[0-9]+x[0-9]+ $timing" "$out/voxels.vti" -- \
  voxelize "$data/bunny_small.vtp" -o "$out/voxels.vti" --resolution 24 --backend cpu --timing
run chamfer "^vtkdf: chamfer dims=[0-9]+x[0-9]+x[0-9]+ $timing layers=[1-9]" "$out/chamfer.vti" -- \
  chamfer "$out/voxels.vti" -o "$out/chamfer.vti" --metric manhattan --backend cpu --timing
run segment "^vtkdf: segment dims=[0-9]+x[0-9]+x[0-9]+ $timing regions=2 patches=[0-9]+ crossed_triangles=0 refused_merges=[0-9]+ stages=crossings:[0-9.e-]+,patches:" \
  "$out/segment.vti" "$out/segment.png" -- \
  segment "$data/plane.vtp" -o "$out/segment.vti" --resolution 20 --backend cpu --timing \
  --png "$out/segment.png" --surface "$out/segment.vtp"
# Each picture explains itself: its colour bar and the text around it (check_legend.py).
for picture in signed:linfac grey:medial region:segment; do
  /usr/bin/python3 "$(dirname "$0")/check_legend.py" "${picture%%:*}" "$out/${picture#*:}.png" ||
    fail "${picture#*:}.png: no legend"
done
[ -s "$out/segment.vtp" ] || fail "segment: $out/segment.vtp not written"
# The teapot's spout and handle cross its body: cut along the crossings (51 triangles),
# or not (--uncut: its 4 patches as they are). A build without CGAL (DF_USE_CGAL=OFF,
# set by Testing/CMakeLists.txt) finds the 3 groups of crossings, cuts none and says why.
if [ "${DF_USE_CGAL:-ON}" = ON ]; then
  crossed="patches=9 crossed_triangles=51"
else
  crossed="patches=4 crossed_triangles=0"
fi
run segment-crossed "^vtkdf: segment dims=[0-9]+x[0-9]+x[0-9]+ $timing regions=[0-9]+ $crossed " \
  "$out/segment-crossed.vti" -- \
  segment "$data/teapot.vtp" -o "$out/segment-crossed.vti" --resolution 16 --backend cpu --timing
if [ "${DF_USE_CGAL:-ON}" != ON ]; then
  grep -q "3 of 3 groups of crossing triangles (51 triangles) could not be cut.*-DDF_USE_CGAL=OFF" \
    "$out/segment-crossed.err" || fail "segment-crossed: no warning naming DF_USE_CGAL"
fi
run segment-uncut "^vtkdf: segment dims=[0-9]+x[0-9]+x[0-9]+ $timing regions=[0-9]+ patches=4 crossed_triangles=0 " \
  "$out/segment-uncut.vti" -- \
  segment "$data/teapot.vtp" -o "$out/segment-uncut.vti" --resolution 16 --backend cpu --timing --uncut
# The surface's own options: the paper's vertices (no feature fans), a feature angle.
run segment-paper "^vtkdf: surface time_s=[0-9.e-]+ triangles=[1-9][0-9]* marching_cells=[0-9]+ feature_cells=0 " \
  "$out/segment-paper.vtp" -- \
  segment "$data/plane.vtp" -o "$out/segment-paper.vti" --resolution 20 --backend cpu --timing \
  --surface "$out/segment-paper.vtp" --paper-vertices --feature-angle 45
run union "^vtkdf: union pieces=4 queries=1 $timing faces_visited=[1-9][0-9]*$" \
  "$out/union.vtp" -- \
  union "$data/hubo_ankle_convex4.vtp" -o "$out/union.vtp" --query 0 0.01 0.01 --timing
run union-gpu "^vtkdf: union pieces=4 queries=1 backend=gpu renderer=\"[^\"]+\" time_s=[0-9.]+ faces_visited=[1-9][0-9]*$" \
  "$out/union-gpu.vtp" -- \
  union "$data/hubo_ankle_convex4.vtp" -o "$out/union-gpu.vtp" --query 0 0.01 0.01 --backend gpu \
  --timing
# The GPU's answer is the CPU's, bit for bit.
cmp -s "$out/union.vtp" "$out/union-gpu.vtp" || fail "union: the GPU's output differs from the CPU's"
# pd: a solid against itself intersects, by every pair.
run pd "^vtkdf: pd pairs=16 pairs_kept=[1-9][0-9]* $timing faces_visited=[1-9][0-9]*$" \
  "$out/pd.vtp" -- \
  pd "$data/hubo_ankle_convex4.vtp" "$data/hubo_ankle_convex4.vtp" -o "$out/pd.vtp" --timing
grep -Eq "intersecting=1 penetration_depth=0\.[0-9]+ " <<<"$("$vtkdf" pd "$data/hubo_ankle_convex4.vtp" \
  "$data/hubo_ankle_convex4.vtp" -o "$out/pd.vtp")" || fail "pd: a solid does not intersect itself"
# pd on the GPU: the CPU's answer; the rendered views' options, deprecated, only say so.
gpu_pd=$("$vtkdf" pd "$data/hubo_ankle_convex4.vtp" "$data/hubo_ankle_convex4.vtp" \
  -o "$out/pd-gpu.vtp" --backend gpu --pixels 64 --uncertified 2>"$out/pd-gpu.err")
[ "$gpu_pd" = "$("$vtkdf" pd "$data/hubo_ankle_convex4.vtp" "$data/hubo_ankle_convex4.vtp" \
  -o "$out/pd.vtp")" ] && cmp -s "$out/pd.vtp" "$out/pd-gpu.vtp" || fail "pd: the GPU's answer differs"
[ "$(grep -c "is deprecated and does nothing" "$out/pd-gpu.err")" = 2 ] ||
  fail "pd: --pixels and --uncertified do not say they are deprecated"
# proximity on both backends: the same answers, and the GPU's traffic reported.
run proximity "^vtkdf: proximity backend=cpu step=[0-9.e-]+ point_queries=[1-9][0-9]* bytes_to_gpu=0 " \
  "$out/proximity.vtp" -- \
  proximity "$data/bunny_small.vtp" "$data/cow.vtp" -o "$out/proximity.vtp" --resolution 16 --timing
run proximity-gpu "^vtkdf: proximity backend=gpu step=[0-9.e-]+ point_queries=[1-9][0-9]* bytes_to_gpu=[1-9][0-9]* bytes_from_gpu=[1-9]" \
  "$out/proximity-gpu.vtp" -- \
  proximity "$data/bunny_small.vtp" "$data/cow.vtp" -o "$out/proximity-gpu.vtp" --resolution 16 \
  --backend gpu --timing
# (The values agree to rounding: Proximity.BruteForce.*.gpu checks them.)
answers() {
  "$vtkdf" proximity "$data/aneurysm.vtp" "$data/teapot.vtp" -o "$out/p.vtp" --resolution 16 \
    --backend "$1" | grep -Eo "colliding=[01]|contacts=[0-9]+" | tr '\n' ' '
}
[ "$(answers cpu)" = "$(answers gpu)" ] && [[ "$(answers cpu)" == *contacts=[1-9]* ]] || fail "proximity: the GPU's contacts differ from the CPU's"
# probe: points from a .csv (with a header) and from a mesh, signed by the winding
# number; the .npy of distances equal to the .vtp's Distance; the summary printed.
printf 'x,y,z\n0,0,0\n0.1,4.5,0.2\n20,0,0\n' >"$out/points.csv"
run probe "^vtkdf: probe time_s=[0-9.]+ stages=.*tree.*queries.* evaluations=[1-9][0-9]* peak_memory_mb=" \
  "$out/probe.vtp" -- \
  probe "$data/bunny_small.vtp" "$out/points.csv" -o "$out/probe.vtp" --signed --timing
"$vtkdf" probe "$data/bunny_small.vtp" "$out/points.csv" -o "$out/probe.npy" --signed \
  >"$out/probe-npy.out" || fail "probe -o .npy: exit status $?"
grep -Eq "^vtkdf: probe points=3 max_abs_distance=[0-9.]+ .* farthest_point=2 beyond=0" \
  "$out/probe-npy.out" || fail "probe: the summary ($(head -c 300 "$out/probe-npy.out"))"
[ "$(stat -c %s "$out/probe.npy")" = $((128 + 3 * 8)) ] || fail "probe: the .npy's size"
"$vtkdf" probe "$data/cow.vtp" "$data/plane.vtp" -o "$out/probe-mesh.vtp" --max-distance 0.5 \
  >/dev/null || fail "probe: points of a mesh, capped"
# hausdorff: both outputs written, the distance found inside its certified interval,
# which is no wider than asked (1e-5 of the diagonal, at most 0.16 here).
run hausdorff "^vtkdf: hausdorff time_s=[0-9.]+ stages=input:[0-9.e-]+,trees:[0-9.e-]+,points:[0-9.e-]+,refine:[0-9.e-]+ pieces=[1-9][0-9]* rounds=[1-9][0-9]* evaluations=[1-9][0-9]* peak_memory_mb=" \
  "$out/hausdorff-a.vtp" "$out/hausdorff-b.vtp" -- \
  hausdorff "$data/bunny_small.vtp" "$data/cow.vtp" -o "$out/hausdorff-a.vtp" \
  --output-b "$out/hausdorff-b.vtp" --relative-error 1e-5 --timing
grep -E "^vtkdf: hausdorff distance=" "$out/timing.log" | tail -1 |
  awk '{ for (i = 2; i <= NF; i++) { split($i, kv, "="); v[kv[1]] = kv[2] }
         exit !(v["lower"] <= v["distance"] && v["distance"] <= v["upper"] &&
                v["upper"] - v["lower"] <= 1.6e-4 && v["distance"] > 0) }' ||
  fail "hausdorff: the distance outside its interval, or the interval too wide"
# clip: linfac's grid cut inside the bunny (the winding sign by default).
run clip "^vtkdf: clip time_s=[0-9.]+ stages=distances:[0-9.e-]+,clip:[0-9.e-]+ peak_memory_mb=" \
  "$out/clip.vtu" -- \
  clip "$data/bunny_small.vtp" "$out/linfac.vti" -o "$out/clip.vtu" --timing
# blend: a field with itself is itself, at any T.
if "$vtkdf" blend "$out/segment.vti" "$out/segment.vti" -t 0.3 -o "$out/blend.vti" \
  --png "$out/blend.png" 2>"$out/blend.err"; then
  [ -s "$out/blend.vti" ] && [ -s "$out/blend.png" ] || fail "blend: outputs not written"
else
  fail "blend: exit status $? ($(head -c 300 "$out/blend.err"))"
fi
# render (the suite runs under Xvfb): the segmented field's surfaces, and the signed
# field composited.
run render "^vtkdf: render dims=[0-9]+x[0-9]+x[0-9]+ mode=surface size=96x80 slices=[1-9][0-9]* regions=2 first_frame_s=[0-9.]+ frame_s=[0-9.]+ renderer=" \
  "$out/render.png" -- \
  render "$out/segment.vti" -o "$out/render.png" --size 96 80 --azimuth 40 --elevation 30 --timing
run render-composite "^vtkdf: render dims=[0-9]+x[0-9]+x[0-9]+ mode=composite size=64x64 slices=12 " \
  "$out/composite.png" -- \
  render "$out/linfac.vti" -o "$out/composite.png" --mode composite --size 64 64 --slices 12 \
  --timing

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
VTKDF_GL_PLATFORM=none expect_failure uniongpu union "$data/hubo_ankle_convex4.vtp" \
  -o "$out/x.vtp" --backend gpu
grep -q "Backend is GPU but" "$out/uniongpu.out" || fail "union --backend gpu without a GPU: no message"
VTKDF_GL_PLATFORM=none expect_failure proximitygpu proximity "$data/bunny_small.vtp" \
  "$data/cow.vtp" -o "$out/x.vtp" --backend gpu
grep -q "Backend is GPU but" "$out/proximitygpu.out" || fail "proximity --backend gpu without a GPU: no message"
expect_failure probeout probe "$data/bunny_small.vtp" "$out/points.csv" -o "$out/x.vtu"
grep -q "name it OUT.vtp" "$out/probeout.out" || fail "probe -o .vtu for a point cloud: no message"
printf '0,0,0\n1,nan,0\n' >"$out/nan.csv"
expect_failure probenan probe "$data/bunny_small.vtp" "$out/nan.csv" -o "$out/x.vtp"
grep -q "point 1 has a NaN" "$out/probenan.out" || fail "probe with a NaN point: no message"
expect_failure hausdorffnone hausdorff "$data/bunny_small.vtp" "$data/cow.vtp" -o "$out/x.vtp" \
  --relative-error 0
expect_failure hausdorffout hausdorff "$data/bunny_small.vtp" "$data/cow.vtp" -o "$out/x.vti"
expect_failure clipout clip "$data/bunny_small.vtp" "$out/linfac.vti" -o "$out/x.vtp"
grep -q "name it OUT.vtu" "$out/clipout.out" || fail "clip -o .vtp: no message"
expect_failure clipsign clip "$data/bunny_small.vtp" "$out/linfac.vti" -o "$out/x.vtu" --sign up
expect_failure clipvalue clip "$data/bunny_small.vtp" "$out/linfac.vti" -o "$out/x.vtu" \
  --value nan
grep -q "Value must be finite" "$out/clipvalue.out" || fail "clip --value nan: no message"
expect_failure pdone pd "$data/hubo_ankle_convex4.vtp" -o "$out/x.vtp"
expect_failure unionpieces union "$data/hubo_ankle_convex4.vtp" -o "$out/x.vtp" --piece-array Nope
expect_failure rendermesh render "$data/plane.vtp" -o "$out/x.png"
expect_failure rendermode render "$out/segment.vti" -o "$out/x.png" --mode mip
DISPLAY= expect_failure renderdisplay render "$out/segment.vti" -o "$out/x.png"
grep -q "needs an X server" "$out/renderdisplay.out" || fail "render without DISPLAY: no message"
[ -e "$out/x.vti" ] && fail "a failed run wrote $out/x.vti"
[ -e "$out/x.png" ] && fail "a failed run wrote $out/x.png"
[ -e "$out/x.vtp" ] && fail "a failed run wrote $out/x.vtp"
[ -e "$out/x.vtu" ] && fail "a failed run wrote $out/x.vtu"
# union --convex-hulls on convex pieces: the same answer, no warning.
"$vtkdf" union "$data/hubo_ankle_convex4.vtp" -o "$out/union-hulls.vtp" --query 0 0.01 0.01 \
  --convex-hulls 2>"$out/union-hulls.err" || fail "union --convex-hulls: exit status $?"
grep -q "convex hulls" "$out/union-hulls.err" && fail "union --convex-hulls warned on convex pieces"

# The outputs' values: fields against what they must hold (check_cli_values.py).
/usr/bin/python3 "$(dirname "$0")/check_cli_values.py" "$out" "$data" "$out/timing.log" ||
  fail "the outputs' values"

# --help (alone or after a subcommand): the usage on stdout, status 0.
for args in "--help" "-h" "medial --help"; do
  # shellcheck disable=SC2086
  "$vtkdf" $args >"$out/help.out" 2>"$out/help.err" || fail "vtkdf $args: exit status $?"
  grep -q "usage: vtkdf linfac" "$out/help.out" || fail "vtkdf $args: no usage on stdout"
done

echo "$failures failures"
[ $failures -eq 0 ]
