#!/usr/bin/env bash
# The viewport's cost under a private Xvfb display:
#   viewport_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]
# 1. measure-frames reports plausible figures (min <= median <= p90 <= max, the mean inside, fps =
#    1000 / mean; flying frames rendered smaller, settled still frames kept) and rejects a bad
#    argument with one error naming the script's line.
# 2. A flight that stops settles to the frame rendering goes on to give (byte for byte), and to the
#    frame of an editor that never moved within a stated tolerance (the clouds' jitter, the shadow
#    cascades anchored where the flight made them).
# Exit 0 on success, 77 when Xvfb is missing.
set -u
EDITOR=${1:?usage: viewport_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]}
IMAGE_CHECK=${2:?usage: viewport_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]}
SOURCE_DIR=${3:-$(cd "$(dirname "$0")/../.." && pwd)}
TIMEOUT=${WELKIN_EDITOR_SMOKE_TIMEOUT:-180}
# The settled frame after a flight against a fresh one: relative L1 over the colour channels.
SETTLED_TOLERANCE=0.02

. "$(dirname "$0")/xvfb_display.sh"
editor_test_begin viewport_test 1024x768x24 KEEP_SMOKE_OUTPUT
export XDG_CONFIG_HOME="$OUT/config" WELKIN_VIEWPORT_OUT="$OUT"
cd "$SOURCE_DIR" || fail "no source dir $SOURCE_DIR"
run_editor() {  # run_editor LOG ARGS...
  local log=$1
  shift
  timeout "$TIMEOUT" "$EDITOR" --no-config --size 800x500 "$@" > "$log" 2>&1
}

# measure-frames N ...: checks a report line's figures with awk; $1 the line, $2 rendered smaller
# at least, $3 kept exactly (or - for any).
check_report() {
  echo "$1" | awk -v smaller="$2" -v kept="$3" '{
    for (i = 1; i <= NF; ++i) f[i] = $i
    for (i = 1; i <= NF; ++i) gsub(/[,;]/, "", f[i])
    for (i = 1; i < NF; ++i) { before[f[i + 1]] = f[i] + 0; after[f[i]] = f[i + 1] + 0 }
    mean = after["mean"]; median = after["median"]; p90 = after["p90"]; lo = after["min"]; hi = after["max"]
    ok = lo > 0 && lo <= median && median <= p90 && p90 <= hi && lo <= mean && mean <= hi
    # fps agrees with the mean within 2%, and within its printed rounding (one decimal: 1.3 fps is 753 ms)
    fps = 1000 / mean; tolerance = 0.05 + 0.02 * fps
    ok = ok && (before["fps"] - fps) ^ 2 < tolerance ^ 2 && before["rendered"] >= smaller && (kept == "-" || before["kept"] == kept + 0)
    exit ok ? 0 : 1 }' || fail "implausible report: $1"
}

run_editor "$OUT/flight.log" assets/scenes/default.json --script tests/editor/viewport/settle-after-flight.script
rc=$?
cat "$OUT/flight.log"
[ $rc -eq 0 ] || fail "editor exited with $rc flying"
fly=$(grep '^measure-frames: 6 frames flying 200.0 m/s turning 20.0 deg/s' "$OUT/flight.log") || fail "no flight report"
check_report "$fly" 1 -
still=$(grep '^measure-frames: 4 frames still' "$OUT/flight.log") || fail "no still report"
check_report "$still" 0 4
grep -q '^measure-frames: passes, GPU ms per frame (frames run): .*clouds.march' "$OUT/flight.log" || fail "no passes in the flight's report"
"$IMAGE_CHECK" "$OUT/settled.exr" --same-as "$OUT/rendered.exr" --max-relative-l1 0 || fail "the kept frame is not the rendered one"

run_editor "$OUT/fresh.log" assets/scenes/default.json --script tests/editor/viewport/settle-fresh.script
rc=$?
cat "$OUT/fresh.log"
[ $rc -eq 0 ] || fail "editor exited with $rc at the fresh view"
"$IMAGE_CHECK" "$OUT/settled.exr" --same-as "$OUT/fresh.exr" --max-relative-l1 "$SETTLED_TOLERANCE" ||
  fail "the settled frame after a flight is not the fresh one"

# A bad argument: one error naming the line, exit 1.
printf 'measure-frames 0\nquit\n' > "$OUT/bad.script"
run_editor "$OUT/bad.log" --script "$OUT/bad.script"
rc=$?
cat "$OUT/bad.log"
[ $rc -eq 1 ] || fail "a bad measure-frames exited with $rc, not 1"
[ "$(grep -c 'bad.script:1: usage: measure-frames N' "$OUT/bad.log")" = 1 ] || fail "no single error naming bad.script:1"
grep -q "(expected a frame count from 1 to 100000, found '0')" "$OUT/bad.log" || fail "the error does not say what was wrong"
echo "viewport_test: ok"
