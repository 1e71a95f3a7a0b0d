#!/usr/bin/env bash
# Builds the fuzz targets with clang (libFuzzer + ASan + UBSan) in their own build folder and runs each
# for SECONDS: the glTF loader on a seed corpus of generated files, OpenSubdiv refinement on small
# control meshes, then the scene, sequence and preset JSON readers on the shipped documents; then the
# runtime's unit tests, built in the same folder, under ASan and UBSan; then the editor's session
# fuzzer (random script sessions over the editor model) for SECONDS, also under ASan and UBSan.
# Usage: run_fuzz.sh [SECONDS (default 30)] [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
seconds="${1:-30}"
build="${2:-$root/build/fuzz-assets}"
jobs="${WELKIN_FUZZ_JOBS:-2}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DWELKIN_FUZZ=ON \
  -DWELKIN_BUILD_EDITOR=ON -DWELKIN_BUILD_BENCHMARKS=OFF -DWELKIN_BUILD_MODULES=OFF > "$build.configure.log"
cmake --build "$build" -j"$jobs" --target welkin_gltf_fuzzer welkin_assets_fuzz_seeds welkin_json_fuzzer \
  welkin_subdivision_fuzzer
corpus="$build/fuzz-corpus"
mkdir -p "$corpus"
"$build/bin/welkin_assets_fuzz_seeds" "$corpus"
mkdir -p "$build/fuzz-artifacts"
# -rss_limit_mb bounds memory (a file may never make the loader allocate without limit);
# -timeout flags a single input that takes longer than 10 s (a hang).
# UBSan findings stop the run with a stack (the build sets -fno-sanitize-recover=undefined).
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 "$build/bin/welkin_gltf_fuzzer" \
  -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
  -dict="$here/fuzz_gltf.dict" -artifact_prefix="$build/fuzz-artifacts/" "$corpus"

# Subdivision: the layout is in fuzz_subdivision.cpp (flags, levels, vertices - 1, budget exponent,
# adaptive distance, 20 heights, then faces as a size and its indices). Inputs up to 4 KiB keep each
# refinement small; the triangle budget (at most 64 Ki) bounds the output.
subdiv_corpus="$build/fuzz-corpus-subdivision"
mkdir -p "$subdiv_corpus"
heights='\000\001\002\001\000\001\003\004\002\001\000\002\001\000\003\001\002\000\001\002'
quads='\004\000\001\013\012\004\001\002\014\013\005\002\003\004\016\014'
tris='\003\000\001\012\003\001\013\012\003\001\002\013'
printf "\014\002\023\014\000$heights$quads" > "$subdiv_corpus/quads-uniform"
printf "\014\003\023\014\040$heights$quads" > "$subdiv_corpus/quads-adaptive"
printf "\010\002\023\014\000$heights$tris" > "$subdiv_corpus/triangles-loop"
printf "\054\003\023\014\000$heights$quads" > "$subdiv_corpus/quads-level-counts"
# Found by the fuzzer (UBSan: an infinite distance ratio converted to int), kept as a regression.
printf '\x13\x06\x08\x03\x04\x00\x01\x00\x0c\x01\x02\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x59\x00\x00\x00\x00\x00\xff\x00\xff\xff\x00\x02\x01\x00\x0a\x00\x00\x00\x03\x00\x01\x0a\x03\x01\x0b\x0a\x03\x01\x02\x0b' > "$subdiv_corpus/regression-infinite-ratio"
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 "$build/bin/welkin_subdivision_fuzzer" \
  -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=4096 \
  -artifact_prefix="$build/fuzz-artifacts/" "$subdiv_corpus"

# The JSON readers: the first byte picks the reader (0 scene, 1 sequence, 2 light preset, 3 debug
# shape), the rest is the document; inputs up to 1 MiB (nesting and size bounds are hit within it).
json_corpus="$build/fuzz-corpus-json"
mkdir -p "$json_corpus"
for f in "$root"/assets/scenes/*.json; do { printf '\000'; cat "$f"; } > "$json_corpus/scene-${f##*/}"; done
for f in "$root"/assets/sequences/*.json; do { printf '\001'; cat "$f"; } > "$json_corpus/sequence-${f##*/}"; done
for f in "$root"/assets/presets/core/*.json; do { printf '\002'; cat "$f"; } > "$json_corpus/preset-${f##*/}"; done
printf '\003{"shape": "box", "size_m": [1, 2, 3]}' > "$json_corpus/shape.json"
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 "$build/bin/welkin_json_fuzzer" \
  -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=1048576 \
  -artifact_prefix="$build/fuzz-artifacts/" "$json_corpus"

# The runtime's own unit tests (ECS, reflection, plugins, bounded file reads, scenes, JSON limits,
# painted maps) built in the same instrumented folder: under ASan and UBSan, any undefined behaviour
# (an integer overflow, a bad shift or cast) stops the test binary with a report.
cmake --build "$build" -j"$jobs" --target welkin_runtime_core_tests welkin_runtime_scene_tests
for t in welkin_runtime_core_tests welkin_runtime_scene_tests; do
  (cd "$root" && UBSAN_OPTIONS=print_stacktrace=1 ASAN_OPTIONS=detect_leaks=1 "$build/bin/$t" --gtest_brief=1)
done

# The editor's session fuzzer (tests/editor/fuzz): random sessions of script verbs over the editor
# model (only the model is built here, no window), its promises checked after every line. A failure
# writes the shrunk session to fuzz-artifacts/ as a script to keep under tests/editor/sessions/fuzz/.
cmake --build "$build" -j"$jobs" --target welkin_editor_session_fuzz
UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 ASAN_OPTIONS=detect_leaks=1 \
  "$build/bin/welkin_editor_session_fuzz" --seconds "$seconds" --seed "${WELKIN_SESSION_FUZZ_SEED:-1000}" \
  --out "$build/fuzz-artifacts"
