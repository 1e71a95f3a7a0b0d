#!/usr/bin/env bash
# Runs the installed welkin-editor from its prefix under a private Xvfb display, as a user would:
#   installed_editor.sh PREFIX SOURCE_ROOT WORK
# A script edits the debug scene, saves it under WORK and quits; the saved file must hold the edit.
# Exit 0 on success, 77 when Xvfb is missing.
set -u
PREFIX=${1:?usage}; SOURCE_ROOT=${2:?usage}; WORK=${3:?usage}
command -v Xvfb > /dev/null || { echo "installed_editor: Xvfb not installed; skipping"; exit 77; }
mkdir -p "$WORK"
XVFB_PID=""
trap '[ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2> /dev/null' EXIT
. "$(dirname "$0")/../editor/xvfb_display.sh"
start_private_xvfb "$WORK" 640x480x24 || exit 1
cat > "$WORK/edit.script" <<SCRIPT
select ball
set core.DebugShape/albedo [0.25, 0.5, 0.75]
save-scene "$WORK/edited.json"
expect-dirty scene no
quit
SCRIPT
cd "$SOURCE_ROOT" || exit 1
timeout 120 "$PREFIX/bin/welkin-editor" --no-config --size 640x480 --script "$WORK/edit.script" \
  assets/scenes/debug.json > "$WORK/editor.log" 2>&1
rc=$?
if [ $rc -ne 0 ]; then
  echo "installed_editor: welkin-editor --script exited $rc:" >&2
  cat "$WORK/editor.log" >&2
  exit 1
fi
grep -q '0\.75' "$WORK/edited.json" || { echo "installed_editor: the saved scene lacks the edit" >&2; exit 1; }
echo "installed_editor: ok"
