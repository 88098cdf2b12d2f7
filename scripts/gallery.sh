#!/usr/bin/env bash
# Renders every default scene with its methods into docs/images/render-<scene>-<method>.png (the
# pictures of README.md and docs/render.md) and prints the timing table of docs/render.md from the
# sidecars. Usage: scripts/gallery.sh [build/lucent] [out/gallery]. Needs python3 for the table.
set -euo pipefail
lucent=${1:-build/lucent}
work=${2:-out/gallery}
mkdir -p "$work" docs/images
declare -A methods=(
  [dragon-marble]="ssss cdrf lambert"
  [bunny-skin]="ssss cdrf cdrf+translucency lambert"
  [bunny-jade]="cdrf cdrf+translucency ssss lambert"
  [spheres-skin]="cdrf ssss lambert"
)
for scene in dragon-marble bunny-skin bunny-jade spheres-skin; do
  for m in ${methods[$scene]}; do
    name=render-$scene-${m//+/-}
    "$lucent" render "data/scenes/$scene.json" --method "$m" --frames 3 -q --cache "$work/.cache" \
      --out "$work/$name.png" --json "$work/$name.json"
    cp "$work/$name.png" "docs/images/$name.png"
  done
done
python3 - "$work" <<'EOF'
import glob, json, os, sys
print("| scene | method | size | GPU frame ms | shadow | geometry | blur | compose | setup ms (cached fit) |")
print("|---|---|---|---|---|---|---|---|---|")
for path in sorted(glob.glob(os.path.join(sys.argv[1], "render-*.json")), key=os.path.getmtime):
    j = json.load(open(path))
    t, s = j["timings"], j["settings"]
    passes = {p["name"]: p["gpu_ms"] for p in t["passes"]}
    blur = sum(v for k, v in passes.items() if k.startswith("blur"))
    print("| %s | %s | %dx%d | %.1f | %.1f | %.1f | %s | %.1f | %.0f |" % (
        j["scene"]["name"], s["method"], s["width"], s["height"], t["gpu_frame_ms"], passes.get("shadow", 0),
        passes.get("geometry", 0), "%.1f" % blur if blur else "", passes.get("compose", 0), t["setup_ms"]))
EOF
