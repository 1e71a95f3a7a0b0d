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
