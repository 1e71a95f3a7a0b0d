#!/usr/bin/env bash
# Builds the fuzz targets with clang (libFuzzer + ASan) in their own build folder and runs each for
# SECONDS: the glTF loader on a seed corpus of generated files, then the scene, sequence and preset
# JSON readers on the shipped documents. Usage: run_fuzz.sh [SECONDS (default 30)] [BUILD_DIR]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../../.." && pwd)"
seconds="${1:-30}"
build="${2:-$root/build/fuzz-assets}"
jobs="${WELKIN_FUZZ_JOBS:-2}"
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DWELKIN_FUZZ=ON \
  -DWELKIN_BUILD_EDITOR=OFF -DWELKIN_BUILD_BENCHMARKS=OFF -DWELKIN_BUILD_MODULES=OFF > "$build.configure.log"
cmake --build "$build" -j"$jobs" --target welkin_gltf_fuzzer welkin_assets_fuzz_seeds welkin_json_fuzzer
corpus="$build/fuzz-corpus"
mkdir -p "$corpus"
"$build/bin/welkin_assets_fuzz_seeds" "$corpus"
mkdir -p "$build/fuzz-artifacts"
# -rss_limit_mb bounds memory (a file may never make the loader allocate without limit);
# -timeout flags a single input that takes longer than 10 s (a hang).
ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 "$build/bin/welkin_gltf_fuzzer" \
  -max_total_time="$seconds" -rss_limit_mb=2048 -timeout=10 -max_len=65536 \
  -dict="$here/fuzz_gltf.dict" -artifact_prefix="$build/fuzz-artifacts/" "$corpus"

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
