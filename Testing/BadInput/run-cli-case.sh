#!/usr/bin/env bash
# One case of cases.txt through vtkdf: run-cli-case.sh VTKDF CORPUS DATA OUT SUBCOMMAND
# INPUT "OPTIONS" "EXPECT". Fails on a crash (a signal), a time-out, a wrong exit status,
# an error that does not name the problem, or an output unlike the exact reference.
set -uo pipefail
vtkdf=$1 corpus=$2 data=$3 out=$4 sub=$5 input=$6 options=$7 expect=$8
mkdir -p "$out"
path="$corpus/$input"
[ -e "$path" ] || path="$data/$input"
kind=${expect%% *}
pattern=${expect#* }
result="$out/$sub.vti"
second=()
[ "$sub" = union ] && result="$out/$sub.vtp"
# pd: the bad input is P; Q is a good solid.
[ "$sub" = pd ] && result="$out/$sub.vtp" && second=("$data/hubo_ankle_convex4.vtp")
# proximity: the bad input is model A; model B is the teapot.
[ "$sub" = proximity ] && result="$out/$sub.vtp" && second=("$data/teapot.vtp")
# probe, clip: the bad input is the surface; the points (the dataset to clip) are the
# plane's.
[ "$sub" = probe ] && result="$out/$sub.vtp" && second=("$data/plane.vtp")
[ "$sub" = clip ] && result="$out/$sub.vtu" && second=("$data/plane.vtp")
# hausdorff: the bad input is mesh A; mesh B is the teapot.
[ "$sub" = hausdorff ] && result="$out/$sub.vtp" && second=("$data/teapot.vtp")
# band: vtkdf linfac's sparse band (vtkSparseDistanceField), 2 spacings unless the case
# gives its own.
command=$sub
if [ "$sub" = band ]; then
  command=linfac result="$out/$sub.vtpd"
  [[ "$options" == *--band* ]] || options="$options --band 2"
fi
rm -rf "$result" "${result%.vtpd}"
# shellcheck disable=SC2086 # the options are words
timeout 120 "$vtkdf" "$command" "$path" "${second[@]}" -o "$result" $options > "$out/$sub.stdout" 2> "$out/$sub.stderr"
status=$?
fail() {
  echo "FAIL ($sub $input $options): $*"
  sed -n 1,20p "$out/$sub.stderr"
  exit 1
}
[ $status -eq 124 ] && fail "timed out"
[ $status -ge 128 ] && fail "killed by signal $((status - 128))"
# Every message once (running a filter twice printed each error twice).
twice=$(grep -o 'ERR|.*' "$out/$sub.stderr" | sed 's/(0x[0-9a-f]*)//g' | sort | uniq -d | head -1)
[ -z "$twice" ] || fail "a message is printed twice: $twice"
case $kind in
  error | empty)
    [ $status -eq 1 ] || fail "exit status $status, expected 1"
    grep -Eq -- "$pattern" "$out/$sub.stderr" || fail "no message matching '$pattern'"
    [ -e "$result" ] && fail "an output file was written"
    ;;
  usage)
    [ $status -eq 2 ] || fail "exit status $status, expected 2 (usage)"
    grep -Eq -- "$pattern" "$out/$sub.stderr" || fail "no message matching '$pattern'"
    ;;
  exact)
    [ $status -eq 0 ] || fail "exit status $status, expected 0"
    /usr/bin/python3 "$corpus/check_output.py" "$path" "$result" || fail "output differs from the reference"
    ;;
  *) fail "unknown expectation '$expect'" ;;
esac
echo "ok ($sub $input $options): $kind"
