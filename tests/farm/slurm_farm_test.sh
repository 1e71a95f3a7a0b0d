#!/usr/bin/env bash
# `welkin farm slurm --submit` on a real Slurm (tests/farm/slurm_cluster.sh: one node on localhost):
# a 4-task array renders a short sequence into a folder whose name needs quoting, the assembling job
# writes the contact sheet after it, and every file must equal a single-process `welkin sequence`
# render byte for byte. Then `welkin farm status` and the guard against submitting twice.
# Usage: slurm_farm_test.sh WELKIN SOURCE_DIR. Skipped (exit 77) only when not root.
# WELKIN_SLURM_TIMING=1 also times the same farm with 1 task (the figures in docs/farms.md).
set -euo pipefail
WELKIN=$1
SRC=$2
PATH=$PATH:/usr/sbin:/sbin
if [ "$(id -u)" -ne 0 ]; then
  echo "skipped: the test cluster's slurmd must run as root"
  exit 77
fi
for program in munged slurmctld slurmd sbatch squeue scontrol; do
  command -v "$program" >/dev/null || { echo "FAIL: $program is not installed (tools/setup installs munge, slurmctld, slurmd)"; exit 1; }
done
source "$(dirname "$0")/slurm_cluster.sh"

T=$(mktemp -d /tmp/welkin-slurm-test.XXXXXX)
finish() {
  local status=$?
  slurm_cluster_stop
  if [ "$status" -eq 0 ]; then rm -rf "$T"; else echo "test files kept in $T" >&2; fi
}
trap finish EXIT
fail() {
  echo "FAIL: $*" >&2
  tail -n 5 "$T"/cluster/slurmctld.log "$T"/cluster/slurmd.log >&2 || true
  exit 1
}

slurm_cluster_start "$T/cluster" >"$T/cluster-start.log" 2>&1 || { cat "$T/cluster-start.log"; fail "the cluster did not start"; }

# 8 frames (0 to 14 s at 0.5 fps) of the flight from dawn, small.
RUN=("$SRC/assets/scenes/flight.json" "$SRC/assets/sequences/dawn-to-noon.json" --fps 0.5 --to 14 --size 64x36)
start=$SECONDS
"$WELKIN" sequence "${RUN[@]}" --out "$T/single" --contact-sheet "$T/single-sheet.png" >/dev/null 2>&1 || fail "the single-process render"
echo "single process: $((SECONDS - start)) s"

# Submits a farm of `tasks` tasks into `out` and waits for it; prints the seconds it took.
farm() {
  local tasks=$1 out=$2 sheet=$3 submitted render assemble started=$SECONDS
  submitted=$("$WELKIN" farm slurm "${RUN[@]}" --out "$out" --tasks "$tasks" --contact-sheet "$sheet" --submit) ||
    fail "welkin farm slurm --submit: $submitted"
  read -r render assemble < <(sed -n 's/^submitted render job \([0-9]*\) ([0-9]* tasks) and assembling job \([0-9]*\)$/\1 \2/p' <<<"$submitted") || true
  [ -n "$render" ] && [ -n "$assemble" ] || fail "no job ids in: $submitted"
  slurm_wait_idle 300 || fail "the jobs did not finish within 300 s"
  local states
  states=$( (scontrol show job "$render" && scontrol show job "$assemble") | grep -o 'JobState=[A-Z_]*' | sort | uniq -c | tr -s ' ')
  [ "$states" = " $((tasks + 1)) JobState=COMPLETED" ] || { cat "$out"/slurm/*.log >&2; fail "job states: $states"; }
  echo $((SECONDS - started))
}

OUT="$T/farm out/it's \$(frames)"
SHEET="$T/farm sheet.png"
seconds=$(farm 4 "$OUT" "$SHEET")
echo "4 tasks: $seconds s from submission to the contact sheet"

# Byte for byte: the frames, the manifest's run, the contact sheet.
frames=0
for f in "$T"/single/frame_*.png; do
  cmp -s "$f" "$OUT/$(basename "$f")" || fail "$(basename "$f") differs from the single-process render"
  frames=$((frames + 1))
done
[ "$frames" -eq 8 ] || fail "$frames frames, expected 8"
[ "$(ls "$OUT" | grep -c '^frame_')" -eq 8 ] || fail "the farm wrote other frames: $(ls "$OUT")"
cmp -s "$T/single-sheet.png" "$SHEET" || fail "the contact sheet differs"
[ "$(ls "$OUT/slurm" | grep -c '^render-.*\.log$')" -eq 4 ] || fail "expected 4 task logs in slurm/: $(ls "$OUT/slurm")"

status=$("$WELKIN" farm status "$OUT") || fail "welkin farm status: $status"
echo "$status"
grep -q '^done         8 of 8$' <<<"$status" || fail "status does not say 8 of 8 done"
grep -q '^missing      0$' <<<"$status" || fail "status reports missing frames"
if grep -q '^failed' <<<"$status"; then fail "status reports failures"; fi

# Not twice: the folder records the jobs.
set +e
again=$("$WELKIN" farm slurm "${RUN[@]}" --out "$OUT" --tasks 4 --submit 2>&1)
code=$?
set -e
[ "$code" -eq 3 ] || fail "a second --submit exited $code: $again"
grep -q "jobs were already submitted" <<<"$again" || fail "a second --submit: $again"
[ -z "$(squeue -h -o %i)" ] || fail "a second --submit queued jobs"

if [ "${WELKIN_SLURM_TIMING:-0}" = 1 ]; then
  echo "1 task: $(farm 1 "$T/farm-1" "$T/sheet-1.png") s from submission to the contact sheet"
  echo "4 tasks: $(farm 4 "$T/farm-4" "$T/sheet-4.png") s from submission to the contact sheet"
fi
echo "PASS"
