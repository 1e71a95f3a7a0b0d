# Sourced by the scripts that run welkin-editor headless (the editor's smoke and session tests, the
# package test's installed editor). start_private_xvfb DIR SCREEN starts Xvfb on a display it picks
# itself (it writes the number to fd 3 once it accepts clients), sets XVFB_PID and exports DISPLAY;
# on failure it prints why and returns 1. The caller kills $XVFB_PID when done.
start_private_xvfb() {
  local dir=$1 screen=$2
  Xvfb -displayfd 3 -screen 0 "$screen" -nolisten tcp 3> "$dir/display" 2> "$dir/xvfb.log" &
  XVFB_PID=$!
  for _ in $(seq 100); do
    [ -s "$dir/display" ] && break
    kill -0 "$XVFB_PID" 2> /dev/null || { cat "$dir/xvfb.log" >&2; echo "Xvfb did not start" >&2; return 1; }
    sleep 0.1
  done
  [ -s "$dir/display" ] || { echo "Xvfb gave no display number" >&2; return 1; }
  export DISPLAY=":$(head -n1 "$dir/display")"
}

# editor_test_begin NAME SCREEN KEEP_VARIABLE: the start of each editor test script. Skips (exit 77)
# without Xvfb, makes the scratch folder $OUT (kept, and its path printed, when $KEEP_VARIABLE is 1,
# else removed on exit), defines `fail MESSAGE` (prints "NAME: FAIL: MESSAGE", exits 1), stops Xvfb
# on exit and starts it on a private display.
editor_test_begin() {
  EDITOR_TEST_NAME=$1 EDITOR_TEST_KEEP=$3
  command -v Xvfb > /dev/null || { echo "$EDITOR_TEST_NAME: Xvfb not installed; skipping"; exit 77; }
  OUT=$(mktemp -d "${TMPDIR:-/tmp}/welkin-editor-$EDITOR_TEST_NAME.XXXXXX")
  XVFB_PID=""
  trap editor_test_end EXIT
  start_private_xvfb "$OUT" "$2" || fail "no display"
}
editor_test_end() {
  [ -n "$XVFB_PID" ] && kill "$XVFB_PID" 2> /dev/null && wait "$XVFB_PID" 2> /dev/null
  if [ "${!EDITOR_TEST_KEEP:-0}" = 1 ]; then
    echo "$EDITOR_TEST_NAME: output kept in $OUT"
  else
    rm -rf "$OUT"
  fi
}
fail() {
  echo "$EDITOR_TEST_NAME: FAIL: $*" >&2
  exit 1
}
