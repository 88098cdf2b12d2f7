#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/fuzz_*.c) with clang, ASan + UBSan, into build-fuzz/ (CMake with
# -DLUCENT_FUZZ=ON: the library is compiled once, with -fsanitize=fuzzer-no-link), seeds a corpus per
# target from tests/fixtures, and runs each target in turn:
#   fuzz/build.sh [SECONDS_PER_TARGET] [TARGET...]     (make fuzz FUZZ_SECONDS=600)
# Targets: mesh (PLY/OBJ/STL/OFF/glTF import), ply (the PLY property API), material, scene (+ --set), gltf
# (glTF scenes: .gltf/.glb, buffers, accessors, nodes, cameras, lights, materials),
# mcml (.mci/.mco), image (PNG/EXR/PFM), part (the part files of --part K/N that lucent merge reads). Findings land in build-fuzz/artifacts_<target>/; each run's
# last lines (executions, coverage) in build-fuzz/fuzz_<target>.log. Exit status 1 when a target found
# a crash, a leak or a timeout.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(mesh ply material scene gltf mcml image part)
command -v clang >/dev/null || { echo "fuzz: clang is needed (Debian: clang)"; exit 1; }
out=build-fuzz
cmake -S . -B "$out" -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DLUCENT_FUZZ=ON -DLUCENT_MPI=OFF \
  -DLUCENT_WERROR=OFF -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
cmake --build "$out" --target "${targets[@]/#/fuzz_}" -j2 >/dev/null
seed() { # seed TARGET FILES...
  local dir=$out/corpus_$1
  shift
  mkdir -p "$dir"
  for f in "$@"; do [ -f "$f" ] && cp "$f" "$dir/" || true; done
}
mesh_seed() { # the mesh target's first byte picks the format: 0 ply, 1 obj, 4 stl, 5 off, 6 gltf
  local dir=$out/corpus_mesh
  mkdir -p "$dir"
  local i=0
  for f in tests/fixtures/mesh/*.ply tests/fixtures/bad-meshes/*.ply; do
    [ -f "$f" ] && { printf '\0'; cat "$f"; } >"$dir/ply$((i++))"
  done
  for f in tests/fixtures/bad-meshes/*.obj; do [ -f "$f" ] && { printf '\1'; cat "$f"; } >"$dir/obj$((i++))"; done
  printf '\1v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\nf -1 -2 -3 1/1/1\n' >"$dir/obj-seed"
  printf '\4solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid t\n' >"$dir/stl-seed"
  printf '\5OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$dir/off-seed"
  [ -f tests/fixtures/mesh/tetra.ply ] && { printf '\0'; gzip -c tests/fixtures/mesh/tetra.ply; } >"$dir/ply-gz"
  return 0
}
mesh_seed
seed ply tests/fixtures/mesh/*.ply tests/fixtures/bad-meshes/*.ply
seed material tests/fixtures/materials/*.json data/materials.json
seed mcml tests/fixtures/mcml/*.mci tests/fixtures/mcml/mco/*.mco
seed scene data/scenes/*.json tests/fixtures/scenes/*.json
seed gltf tests/fixtures/gltf/*.gltf tests/fixtures/gltf/*.glb
mkdir -p "$out/corpus_image"
for f in tests/fixtures/images/*.png; do [ -f "$f" ] && { printf '\0'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"; done
for f in tests/fixtures/images/*.exr; do [ -f "$f" ] && { printf '\1'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"; done
for f in tests/fixtures/images/*.pfm; do [ -f "$f" ] && { printf '\2'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"; done
# a part file (src/base/dist.c's layout, little-endian): part 1 of 1 of `mcml x.mci`, an int64 tally of
# 2 values and a uint32 tally of 1
mkdir -p "$out/corpus_part"
tallies='\0\0\0\0\2\0\0\0\0\0\0\0\7\0\0\0\0\0\0\0\11\0\0\0\0\0\0\0\2\0\0\0\1\0\0\0\0\0\0\0\3\0\0\0'
printf 'LUCENT-PART v1\n\0\4\3\2\1\1\0\0\0\1\0\0\0\2\0\0\0\4\0\0\0mcml\5\0\0\0x.mci\2\0\0\0'"$tallies" \
  >"$out/corpus_part/mcml-1-of-1"
status=0
for t in "${targets[@]}"; do
  mkdir -p "$out/artifacts_$t"
  echo "== fuzz_$t for ${secs}s"
  # -rss_limit_mb: a parser that takes more than 2 GB on a 64 KiB input has a bomb in it. The mesh target's
  # assimp formats run in a forked child, which inherits libFuzzer's malloc hook (it would save the child's
  # large allocations as out-of-memory findings of the parent's, which are not): there, an allocation
  # above 1.5 GB fails instead (assimp's bad_alloc ends the child, an error in the parent), as the
  # child's address-space limit makes it fail in a build without sanitizers.
  opts=${ASAN_OPTIONS:-}
  [ "$t" = mesh ] && opts="$opts:allocator_may_return_null=1:max_allocation_size_mb=1536"
  if ! ASAN_OPTIONS=$opts "$out/fuzz_$t" -max_total_time="$secs" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
      -artifact_prefix="$out/artifacts_$t/" -print_final_stats=1 "$out/corpus_$t" >"$out/fuzz_$t.log" 2>&1; then
    status=1
  fi
  grep -E "^#[0-9]+.*DONE|stat::number_of_executed_units|cov:|ERROR|SUMMARY" "$out/fuzz_$t.log" | tail -4
done
exit $status
