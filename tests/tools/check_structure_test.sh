#!/usr/bin/env bash
# tools/check-structure must find each planted fault (tests/tools/structure_fixture/planted: a function
# and a member function of 121 lines, a GLSL function of 121 lines, a line of 111 columns) and nothing
# at the limits themselves (a function of 120 lines, a line of 110 characters with multi-byte ones, a
# file of 500 lines), and a file of 501 lines, which is made here.
set -euo pipefail
cd "$(dirname "$0")/../.."
fail() { echo "check_structure_test: $*" >&2; exit 1; }

set +e
out=$(tools/check-structure tests/tools/structure_fixture/planted 2>/dev/null)
rc=$?
set -e
[ "$rc" = 1 ] || fail "planted faults: exit $rc, expected 1"
expected="tests/tools/structure_fixture/planted/planted.cpp:4: function too_long_function has 121 lines (limit 120)
tests/tools/structure_fixture/planted/planted.cpp:248: function too_long_member has 121 lines (limit 120)
tests/tools/structure_fixture/planted/planted.cpp:371: line has 111 columns (ColumnLimit 110)
tests/tools/structure_fixture/planted/planted.frag:3: function too_long_shader_function has 121 lines (limit 120)"
[ "$out" = "$expected" ] || fail "planted faults: got
$out
expected
$expected"

tools/check-structure tests/tools/structure_fixture/clean 2>/dev/null || fail "the clean fixture was refused"

# Files of 500 and 501 lines, made in a folder of their own.
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
for n in 500 501; do
  for ((i = 0; i < n; ++i)); do echo "// line $i"; done >"$dir/lines_$n.h"
done
set +e
out=$(tools/check-structure "$dir" 2>/dev/null)
rc=$?
set -e
[ "$rc" = 1 ] || fail "long file: exit $rc, expected 1"
[ "$out" = "$dir/lines_501.h:1: file has 501 lines (limit 500)" ] || fail "long file: got '$out'"
echo "check_structure_test: every planted fault found, nothing at the limits"
