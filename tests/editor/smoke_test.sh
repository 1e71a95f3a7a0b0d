#!/usr/bin/env bash
# Smoke test of welkin-editor under a private Xvfb display:
#   smoke_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]
# Runs assets/editor/smoke.script (edit, undo/redo, presets, timeline, screenshots), checks the saved
# preset and sequence files and that the screenshots are not blank, then runs
# assets/editor/smoke-reload.script in a second editor to load what the first one saved, and checks
# that a failing script makes the editor exit non-zero, and paints the clouds' coverage map. Exit 0 on success, 77 when Xvfb is missing.
set -u
EDITOR=${1:?usage: smoke_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]}
IMAGE_CHECK=${2:?usage: smoke_test.sh EDITOR IMAGE_CHECK [SOURCE_DIR]}
SOURCE_DIR=${3:-$(cd "$(dirname "$0")/../.." && pwd)}
TIMEOUT=${WELKIN_EDITOR_SMOKE_TIMEOUT:-180}

. "$(dirname "$0")/xvfb_display.sh"
editor_test_begin smoke_test 1600x900x24 KEEP_SMOKE_OUTPUT
echo "smoke_test: Xvfb on $DISPLAY"

# The editor state goes to the scratch folder, never to the user's config.
export XDG_CONFIG_HOME="$OUT/config"
export WELKIN_EDITOR_OUT="$OUT"
cd "$SOURCE_DIR" || fail "no source dir $SOURCE_DIR"

run_editor() {  # run_editor LOG ARGS...
  local log=$1
  shift
  timeout "$TIMEOUT" "$EDITOR" --size 1600x900 "$@" > "$log" 2>&1
}

# 1. The scripted session.
run_editor "$OUT/run1.log" assets/scenes/default.json --script assets/editor/smoke.script
rc=$?
cat "$OUT/run1.log"
[ $rc -eq 0 ] || fail "editor exited with $rc in the scripted session"

# 2. Its outputs.
preset="$OUT/presets/smoke-light.json"
[ -f "$preset" ] || fail "no preset written at $preset"
grep -Eq '"elevation_deg": 12\.5' "$preset" || { cat "$preset"; fail "preset lacks elevation_deg 12.5"; }
grep -Eq '"azimuth_deg": 250' "$preset" || { cat "$preset"; fail "preset lacks the applied preset's azimuth"; }
ls "$OUT/presets" | grep -q '\.tmp-' && fail "a temporary file was left beside the preset"
[ -f "$OUT/smoke-sequence.json" ] || fail "no sequence written"
"$IMAGE_CHECK" "$OUT/viewport.png" --min-width 200 --min-height 150 || fail "viewport screenshot is blank"
"$IMAGE_CHECK" "$OUT/viewport.exr" --min-width 200 --min-height 150 || fail "viewport EXR is blank or invalid"
"$IMAGE_CHECK" "$OUT/window.png" --min-width 1000 --min-height 600 || fail "window screenshot is blank"
[ -f "$XDG_CONFIG_HOME/welkin/editor.json" ] || fail "editor state was not saved to \$XDG_CONFIG_HOME/welkin/editor.json"

# 3. Another run loads what the first saved.
run_editor "$OUT/run2.log" --script assets/editor/smoke-reload.script
rc=$?
cat "$OUT/run2.log"
[ $rc -eq 0 ] || fail "editor exited with $rc reloading the saved preset"
"$IMAGE_CHECK" "$OUT/reloaded.png" --min-width 200 --min-height 150 || fail "reloaded viewport is blank"

# 4. A failing script line fails the run (so the checks above mean something).
printf 'load-scene assets/scenes/debug.json\nexpect core.Camera/ev100 99\nquit\n' > "$OUT/failing.script"
run_editor "$OUT/run3.log" --script "$OUT/failing.script"
rc=$?
[ $rc -ne 0 ] || { cat "$OUT/run3.log"; fail "a failing expect did not make the editor exit non-zero"; }
grep -q "failing.script:2" "$OUT/run3.log" || { cat "$OUT/run3.log"; fail "the failure does not name the script line"; }

# 5. Painting the clouds' coverage map in the viewport and on the map (assets/editor/smoke-map.script):
#    the map is written beside the saved scene, which names it.
run_editor "$OUT/run4.log" --script assets/editor/smoke-map.script
rc=$?
cat "$OUT/run4.log"
[ $rc -eq 0 ] || fail "editor exited with $rc painting the coverage map"
[ -f "$OUT/painted.coverage_map.png" ] || fail "no coverage map written beside the scene"
grep -q '"coverage_map": ".*painted.coverage_map.png"' "$OUT/painted.json" || fail "the saved scene does not name its coverage map"
"$IMAGE_CHECK" "$OUT/map-window.png" --min-width 1000 --min-height 600 || fail "map window screenshot is blank"

echo "smoke_test: PASS"
