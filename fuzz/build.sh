#!/usr/bin/env bash
# Builds the libFuzzer targets (fuzz/fuzz_*.c) with clang, ASan + UBSan, into build-fuzz/ (CMake with
# -DLUCENT_FUZZ=ON: the library is compiled once, with -fsanitize=fuzzer-no-link), seeds a corpus per
# target from tests/fixtures, and runs each target in turn:
#   fuzz/build.sh [SECONDS_PER_TARGET] [TARGET...]     (make fuzz FUZZ_SECONDS=600)
# Targets: mesh (PLY/OBJ/STL/OFF/glTF import), ply (the PLY property API), plygz (.ply.gz: gzip framing and
# what it inflates to), points (point clouds as surfels), material, scene (+ --set), gltf (glTF scenes: .gltf/.glb,
# buffers, accessors, nodes, cameras, lights, materials), mcml (.mci/.mco), image (PNG/EXR/PFM, scanline and
# tiled), part (the part files of --part K/N that lucent merge reads), reference (compare's reference.json),
# view_script (`lucent view --script` files, checked whole).
# Findings land in build-fuzz/artifacts_<target>/; each run's
# last lines (executions, coverage) in build-fuzz/fuzz_<target>.log. Exit status 1 when a target found
# a crash, a leak or a timeout.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-60}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(mesh ply plygz points material scene gltf mcml image part reference view_script)
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
# plygz: an even first byte has the rest compressed by the target, an odd one feeds it as it is
mkdir -p "$out/corpus_plygz"
for f in tests/fixtures/mesh/*.ply tests/fixtures/bad-points/*.ply; do
  [ -f "$f" ] && { printf '\0'; cat "$f"; } >"$out/corpus_plygz/plain-$(basename "$f")"
done
for f in tests/fixtures/bad-meshes/hand-gz-*.ply.gz; do
  [ -f "$f" ] && { printf '\1'; cat "$f"; } >"$out/corpus_plygz/gz-$(basename "$f")"
done
[ -f tests/fixtures/mesh/tetra.ply ] && { printf '\1'; gzip -c tests/fixtures/mesh/tetra.ply; } >"$out/corpus_plygz/gz-tetra"
# points: the refused clouds, and a plain and a 3D Gaussian splatting one that load
seed points tests/fixtures/bad-points/*.ply
printf 'ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\nproperty float nx\nproperty float ny\nproperty float nz\nproperty uchar red\nproperty uchar green\nproperty uchar blue\nproperty float radius\nend_header\n0 0 0 0 0 1 255 0 0 0.5\n1 0 0 0 0 1 0 255 0 0.5\n0 1 0 0 0 1 0 0 255 0.5\n1 1 0 0 0 1 9 9 9 0.5\n' \
  >"$out/corpus_points/plain-colour-radius.ply"
printf 'ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\nproperty float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\nproperty float scale_0\nproperty float scale_1\nproperty float scale_2\nproperty float rot_0\nproperty float rot_1\nproperty float rot_2\nproperty float rot_3\nend_header\n0 0 0 0.1 0.2 0.3 -3 -3 -5 1 0 0 0\n1 0 0 0 0 0 -2 -4 -3 0.7 0.7 0 0\n' \
  >"$out/corpus_points/splats.ply"
seed material tests/fixtures/materials/*.json data/materials.json
seed mcml tests/fixtures/mcml/*.mci tests/fixtures/mcml/mco/*.mco
seed scene data/scenes/*.json tests/fixtures/scenes/*.json
seed reference tests/fixtures/compare/reference.json
seed view_script tests/fixtures/view/*.txt
seed gltf tests/fixtures/gltf/*.gltf tests/fixtures/gltf/*.glb
mkdir -p "$out/corpus_image"
for f in tests/fixtures/images/*.png; do [ -f "$f" ] && { printf '\0'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"; done
for f in tests/fixtures/images/*.exr tests/fixtures/bad-images/*.exr; do # scanline and tiled, good and short
  [ -f "$f" ] && { printf '\1'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"
done
for f in tests/fixtures/images/*.pfm; do [ -f "$f" ] && { printf '\2'; cat "$f"; } >"$out/corpus_image/$(basename "$f")"; done
# a part file (src/base/dist.c's layout, v2, little-endian): part 1 of 1 of `mcml x.mci`, an int64 tally of
# 2 values and a uint32 tally of 1, then the CRC-32 of all before it; after the target's first byte (0: the
# target writes the CRC itself, 1: the file as it is)
mkdir -p "$out/corpus_part"
python3 -c 'import struct, sys, zlib
b = b"LUCENT-PART v2\n\0" + struct.pack("<5I", 0x01020304, 1, 1, 2, 4) + b"mcml" + struct.pack("<I", 5) + b"x.mci"
b += struct.pack("<I", 2) + struct.pack("<IQqq", 0, 2, 7, 9) + struct.pack("<IQI", 2, 1, 3)
b += struct.pack("<I", zlib.crc32(b))
open(sys.argv[1], "wb").write(b"\0" + b)
open(sys.argv[2], "wb").write(b"\1" + b)' "$out/corpus_part/mcml-1-of-1" "$out/corpus_part/mcml-1-of-1-raw"
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
