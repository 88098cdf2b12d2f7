#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) into build-fuzz/ and runs each for
# a while: fuzz/build.sh [SECONDS_PER_TARGET]. Seeds come from tests/fixtures.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
out=build-fuzz
mkdir -p "$out"
cmake -S . -B build >/dev/null && cmake --build build --target lucent_lib -j2 >/dev/null
srcs=$(ls src/*/*.c build/generated/embedded.c)
flags=(-std=c11 -D_GNU_SOURCE -g -O1 -fsanitize=fuzzer,address,undefined -Iinclude -Isrc -I/usr/include/OpenEXR)
libs=(-lcjson -lOpenEXRCore -lpng -lz $(pkg-config --libs assimp lapacke nlopt fftw3 epoxy egl glfw3) -lembree3
      -lpthread -lm)
for t in material mcml image scene; do
  clang "${flags[@]}" fuzz/fuzz_$t.c $srcs "${libs[@]}" -o "$out/fuzz_$t"
done
mkdir -p "$out/corpus_material" "$out/corpus_mcml" "$out/corpus_image" "$out/corpus_scene"
cp tests/fixtures/materials/*.json data/materials.json "$out/corpus_material/" 2>/dev/null || true
cp tests/fixtures/mcml/*.mci tests/fixtures/mcml/mco/*.mco "$out/corpus_mcml/" 2>/dev/null || true
cp data/scenes/*.json tests/fixtures/scenes/*.json "$out/corpus_scene/" 2>/dev/null || true
for t in material mcml image scene; do
  echo "== fuzz_$t for ${secs}s"
  "$out/fuzz_$t" -max_total_time="$secs" -max_len=65536 "$out/corpus_$t" 2>&1 | tail -3
done
