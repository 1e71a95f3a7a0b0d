#!/usr/bin/env bash
# Scripted sessions of welkin-editor under a private Xvfb display, checking that it never loses work:
#   session_test.sh EDITOR [SOURCE_DIR]
# Runs the scripts in tests/editor/sessions/: quitting with unsaved edits asks (Cancel keeps the
# session, Discard quits, Save writes), opening/new scene and opening a sequence ask, "save as"
# onto an existing file asks, and a crash after an autosave is recovered by the next start.
# Exit 0 on success, 77 when Xvfb is missing.
set -u
EDITOR=${1:?usage: session_test.sh EDITOR [SOURCE_DIR]}
SOURCE_DIR=${2:-$(cd "$(dirname "$0")/../.." && pwd)}
TIMEOUT=${WELKIN_EDITOR_SESSION_TIMEOUT:-120}
SESSIONS="$SOURCE_DIR/tests/editor/sessions"

. "$(dirname "$0")/xvfb_display.sh"
editor_test_begin session_test 1280x800x24 KEEP_SESSION_OUTPUT
export SESSION_OUT="$OUT"
cd "$SOURCE_DIR" || fail "no source dir $SOURCE_DIR"

# run_session NAME CONFIG_NAME [ARGS...]: the script sessions/NAME.script with its own editor state
# folder ($OUT/CONFIG_NAME), so one scenario's autosave and last scene never reach another.
run_session() {
  local name=$1 config=$2
  shift 2
  XDG_CONFIG_HOME="$OUT/$config" timeout "$TIMEOUT" "$EDITOR" --size 1280x800 "$@" --script "$SESSIONS/$name.script" \
    > "$OUT/$name.log" 2>&1
  rc=$?
  echo "--- $name (exit $rc)"
  cat "$OUT/$name.log"
}

# A scene file's ball albedo, as text ("0.1, 0.8, 0.2"), whatever the JSON layout.
albedo_of() { tr -d ' \n' < "$1" | grep -o '"albedo":\[[^]]*\]' | head -n1; }

# 1. Quit asks: Cancel keeps the session (the lines after it run), Discard quits (the rest do not).
run_session quit-prompt quit
[ $rc -eq 0 ] || fail "quit-prompt: exit $rc"
[ -f "$OUT/after-cancel.json" ] || fail "quit-prompt: the session did not go on after Cancel"
[ "$(albedo_of "$OUT/after-cancel.json")" = '"albedo":[0.1,0.8,0.2]' ] || fail "quit-prompt: after-cancel.json lacks the edit"
[ -f "$OUT/after-discard.json" ] && fail "quit-prompt: lines ran after Discard quit"
[ -e "$OUT/quit/welkin/autosave/meta.json" ] && fail "quit-prompt: a clean quit left the autosave"

# 2. Save in the quit prompt writes the scene to its own file.
run_session quit-save save
[ $rc -eq 0 ] || fail "quit-save: exit $rc"
tr -d ' \n' < "$OUT/work.json" | grep -q '"azimuth_deg":123.5' || fail "quit-save: work.json lacks the edit"

# 3. Open, new, open sequence and save-as-over-a-file ask.
echo '{"keep": "me"}' > "$OUT/existing-1.json"
echo '{"keep": "me too"}' > "$OUT/existing-2.json"
run_session prompts prompts
[ $rc -eq 0 ] || fail "prompts: exit $rc"
[ "$(cat "$OUT/existing-1.json")" = '{"keep": "me"}' ] || fail "prompts: Cancel still replaced existing-1.json"
[ "$(albedo_of "$OUT/existing-2.json")" = '"albedo":[0.1,0.8,0.2]' ] || fail "prompts: Overwrite did not write existing-2.json"
[ "$(grep -o '"t"' "$OUT/first-sequence.json" | wc -l)" -ge 2 ] || fail "prompts: Save in the sequence prompt did not write both keys"

# 4. A crash after an autosave; the next start recovers the edits, unsaved, under their old name.
run_session crash crash
[ $rc -eq 70 ] || fail "crash: expected the simulated crash's exit status 70, found $rc"
[ -f "$OUT/crash/welkin/autosave/meta.json" ] || fail "crash: no autosave beside the editor state"
grep -q "crashed.json" "$OUT/crash/welkin/autosave/meta.json" || fail "crash: the autosave does not name the scene's file"
[ "$(albedo_of "$OUT/crashed.json")" = '"albedo":[0.8,0.3,0.2]' ] || fail "crash: crashed.json should still be the unedited scene"
run_session recover crash
[ $rc -eq 0 ] || fail "recover: exit $rc"
[ "$(albedo_of "$OUT/crashed.json")" = '"albedo":[0.1,0.8,0.2]' ] || fail "recover: the recovered edit was not saved"
[ -f "$OUT/recovered-sequence.json" ] || fail "recover: the recovered sequence was not saved"
[ -e "$OUT/crash/welkin/autosave/meta.json" ] && fail "recover: a clean quit left the autosave"

# 5. Another crash; Discard at the next start drops the autosave and keeps the file's scene.
run_session crash-again crash
[ $rc -eq 70 ] || fail "crash-again: exit $rc"
run_session recover-discard crash
[ $rc -eq 0 ] || fail "recover-discard: exit $rc"
[ -e "$OUT/crash/welkin/autosave/meta.json" ] && fail "recover-discard: Discard left the autosave"

# 6. A script ending on an unanswered quit quits without saving, and says so (the smoke scripts do).
printf 'load-scene assets/scenes/debug.json\nselect ball\nset core.DebugShape/shape box\nquit\n' > "$OUT/ends-on-quit.script"
XDG_CONFIG_HOME="$OUT/ends" timeout "$TIMEOUT" "$EDITOR" --size 1280x800 --script "$OUT/ends-on-quit.script" > "$OUT/ends.log" 2>&1
rc=$?
cat "$OUT/ends.log"
[ $rc -eq 0 ] || fail "ends-on-quit: exit $rc"
grep -q "quitting without saving" "$OUT/ends.log" || fail "ends-on-quit: the log does not say the edits were not saved"

echo "session_test: PASS"
