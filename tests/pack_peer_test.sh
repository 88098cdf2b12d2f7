#!/usr/bin/env bash
# Issue 30 sections 3 and 4 checked by real peers (CTest label "peer": not under the sanitizers):
#   - every shader of a pack compiles for its engine with glslangValidator: GLSL 4.50, GLSL ES 3.00
#     (WebGL2), Vulkan GLSL to SPIR-V, HLSL (the snippets inside a minimal shader that calls them); and
#     glslang refuses what the issue found broken (the GLSL 4.50 blur as Vulkan GLSL, an int constant
#     in a float as GLSL ES), so the targets are checked for real;
#   - Khronos' glTF-Validator (npm gltf-validator, from `make setup`) reports 0 errors and 0 warnings on
#     the pack's material.gltf, with the sphere and with a mesh of the user's (--mesh);
#   - Blender 3.4's importer (scripts/peer/gltf_import.py) makes it a mesh using a material with
#     transmission and volume, whose node values are the glTF's by the importer's own rules
#     (io_scene_gltf2: Transmission = transmissionFactor, Volume Absorption colour = attenuationColor,
#     density = 1 / attenuationDistance), and whose absorption as Blender computes it, (1 - colour)
#     density (blender's gpu_shader_material_volume_absorption.glsl), is within 5% of the material's
#     sigma_a (docs/pack.md).
# A peer that is missing fails the test, naming `make setup`.
# Usage: pack_peer_test.sh path/to/lucent SOURCE_DIR
set -u
LUCENT=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
SRC=$(cd "$2" && pwd)
TMP=$(mktemp -d "${TMPDIR:-/tmp}/lucent-peer-XXXXXX")
trap 'rm -rf "$TMP"' EXIT
VALIDATOR=$SRC/build-tools/node_modules/gltf-validator
passed=0 failed=0
report() { # OK? DESCRIPTION [DETAIL]
  if [ "$1" = 1 ]; then
    passed=$((passed + 1)); echo "ok   $2"
  else
    failed=$((failed + 1)); echo "FAIL $2"; [ -n "${3:-}" ] && printf '%s\n' "$3" | sed 's/^/     /'
  fi
}
check() { # DESCRIPTION -- command...: the command succeeds
  local what=$1 out; shift 2
  if out=$("$@" 2>&1); then report 1 "$what"; else report 0 "$what" "$(tail -n 12 <<<"$out")"; fi
}
show() { # DESCRIPTION -- command...: the command succeeds; its output is shown either way
  local what=$1 out ok=0; shift 2
  out=$("$@" 2>&1) && ok=1
  report "$ok" "$what"
  printf '%s\n' "$out" | sed 's/^/     /'
}
refuse() { # DESCRIPTION SUBSTRING -- command...: the command fails saying SUBSTRING
  local what=$1 sub=$2 out; shift 3
  if ! out=$("$@" 2>&1) && [[ "$out" == *"$sub"* ]]; then report 1 "$what"; else report 0 "$what" "$out"; fi
}

for tool in glslangValidator node blender python3; do
  command -v "$tool" >/dev/null 2>&1 || { report 0 "$tool is installed (run make setup)"; echo "0 passed, 1 failed"; exit 1; }
done
[ -f "$VALIDATOR/package.json" ] || { report 0 "gltf-validator in $VALIDATOR (run make setup)"; echo "0 passed, 1 failed"; exit 1; }

export LUCENT_CACHE_DIR=$TMP/cache
few=(--sigma0-photons 1000 --transmit-photons 200 --lut-size 16x16 --object-height 0.2m --no-fit)
for e in glsl gles vulkan hlsl; do
  check "pack skin1 --engine $e" -- "$LUCENT" pack skin1 --engine "$e" "${few[@]}" --out "$TMP/$e"
done

# ---- shaders: one wrapper per language calls every snippet ----
main_glsl='layout(location = 0) out vec4 o_color;
void main() {
    o_color = vec4(lucent_cdrf(u_lut, 0.5, 0.1) * lucent_transmittance(2.0)
                   + lucent_sss_pass(u_lut, vec2(0.5), vec2(0.001, 0.0), 0), 1.0);
}'
snippets() { cat "$1/taps.glsl" "$1/cdrf.glsl" "$1/translucency.glsl"; }
{ echo "#version 450 core"; snippets "$TMP/glsl"; echo "layout(binding = 2) uniform sampler2D u_lut;"; echo "$main_glsl"; } >"$TMP/glsl.frag"
{ printf '#version 300 es\nprecision highp float;\nprecision highp int;\n'; snippets "$TMP/gles"; echo "uniform sampler2D u_lut;"; echo "$main_glsl"; } >"$TMP/gles.frag"
{ echo "#version 450"; snippets "$TMP/vulkan"; echo "layout(set = 0, binding = 2) uniform sampler2D u_lut;"; echo "$main_glsl"; } >"$TMP/vulkan.frag"
{ cat "$TMP/hlsl/taps.hlsl" "$TMP/hlsl/cdrf.hlsl" "$TMP/hlsl/translucency.hlsl"
  echo 'Texture2D<float4> lut : register(t2);
SamplerState linear_clamp : register(s0);
float4 main(float4 position : SV_Position) : SV_Target
{
    return float4(lucent_cdrf(lut, linear_clamp, 0.5, 0.1) * lucent_transmittance(2.0)
                  + lucent_sss_pass(lut, linear_clamp, float2(0.5, 0.5), float2(0.001, 0.0), 0), 1.0);
}'; } >"$TMP/hlsl.hlsl"
check "GLSL 4.50: the blur pass compiles" -- glslangValidator -S frag "$TMP/glsl/blur.frag.glsl"
check "GLSL 4.50: taps, CDRF and translucency compile" -- glslangValidator -S frag "$TMP/glsl.frag"
check "GLSL ES 3.00: the blur pass is ES" -- grep -q "^#version 300 es$" "$TMP/gles/blur.frag.glsl"
check "GLSL ES 3.00: the blur pass compiles" -- glslangValidator -S frag "$TMP/gles/blur.frag.glsl"
check "GLSL ES 3.00: taps, CDRF and translucency compile" -- glslangValidator -S frag "$TMP/gles.frag"
check "Vulkan GLSL: the blur pass compiles to SPIR-V" -- glslangValidator -V -S frag "$TMP/vulkan/blur.frag.glsl" -o "$TMP/blur.spv"
check "Vulkan GLSL: taps, CDRF and translucency compile to SPIR-V" -- glslangValidator -V -S frag "$TMP/vulkan.frag" -o "$TMP/s.spv"
check "HLSL: the blur pass compiles (ps, main)" -- glslangValidator -D -V -e main -S frag "$TMP/hlsl/blur.hlsl" -o "$TMP/bh.spv"
check "HLSL: taps, CDRF and translucency compile" -- glslangValidator -D -V -e main -S frag "$TMP/hlsl.hlsl" -o "$TMP/sh.spv"
# what the issue found: the 4.50 blur is not Vulkan GLSL, and GLSL ES takes no int in a float
refuse "glslang refuses the GLSL 4.50 blur as Vulkan GLSL" "non-opaque uniforms outside a block" -- \
  glslangValidator -V -S frag "$TMP/glsl/blur.frag.glsl" -o "$TMP/x.spv"
printf '#version 300 es\nprecision highp float;\nconst float K = 1;\nout vec4 o;\nvoid main() { o = vec4(K); }\n' >"$TMP/int.frag"
refuse "glslang refuses 'const float K = 1;' as GLSL ES 3.00" "non-convertible constant type" -- glslangValidator -S frag "$TMP/int.frag"

# ---- Khronos' glTF-Validator ----
check "pack with --mesh (tetra.ply)" -- "$LUCENT" pack marble --engine json "${few[@]}" --mesh "$SRC/tests/fixtures/mesh/tetra.ply" --out "$TMP/mesh"
validate() { # FILE: 0 errors, 0 warnings (infos: the extensions the validator does not know)
  node "$SRC/scripts/peer/validate_gltf.js" "$VALIDATOR" "$1" >"$TMP/report.json" &&
    python3 - "$TMP/report.json" <<'EOF'
import json, sys
r = json.load(open(sys.argv[1]))
print("errors %d, warnings %d, infos %d: %s" % (r["numErrors"], r["numWarnings"], r["numInfos"],
      sorted(set(m["code"] + " " + m["message"].split(":")[-1].strip() for m in r["messages"]))))
sys.exit(0 if r["numErrors"] == 0 and r["numWarnings"] == 0 else 1)
EOF
}
for f in glsl/material.gltf mesh/material.gltf; do
  show "glTF-Validator: $f has 0 errors and 0 warnings" -- validate "$TMP/$f"
done

# ---- Blender 3.4's importer ----
check "Blender imports material.gltf" -- blender -b --factory-startup -P "$SRC/scripts/peer/gltf_import.py" -- \
  "$TMP/glsl/material.gltf" "$TMP/blender.json"
show "Blender: a mesh uses a material with transmission and volume, the glTF's values" -- \
  python3 - "$TMP/glsl/material.gltf" "$TMP/blender.json" <<'EOF'
import json, math, sys
g = json.load(open(sys.argv[1]))
b = json.load(open(sys.argv[2]))
mat = g["materials"][0]
ext, pbr = mat["extensions"], mat["pbrMetallicRoughness"]
vol = ext["KHR_materials_volume"]
bm = b["materials"][mat["name"]]
bad = []
def near(what, got, want, rel=1e-6):
    if not abs(got - want) <= rel * max(abs(want), 1e-6):
        bad.append("%s: Blender %r, glTF %r" % (what, got, want))
if not any(o["type"] == "MESH" and mat["name"] in o["materials"] for o in b["objects"]):
    bad.append("no mesh uses %s: %r" % (mat["name"], b["objects"]))
p = bm["principled"]
near("Transmission", p["Transmission"], ext["KHR_materials_transmission"]["transmissionFactor"])
near("IOR", p["IOR"], ext["KHR_materials_ior"]["ior"])
near("Roughness", p["Roughness"], pbr["roughnessFactor"])
near("Metallic", p["Metallic"], pbr["metallicFactor"])
for c in range(3):
    near("Base Color[%d]" % c, p["Base Color"][c], pbr["baseColorFactor"][c])
if not bm["volume_linked"] or not bm["volume_absorption"]:
    bad.append("no Volume Absorption on the material output")
else:
    va = bm["volume_absorption"]
    near("Density", va["Density"], 1 / vol["attenuationDistance"])
    near("Thickness", bm["thickness"], vol["thicknessFactor"])
    sigma_a = mat["extras"]["lucent"]["sigma_a"]  # mm^-1
    for c in range(3):
        near("Volume Absorption Color[%d]" % c, va["Color"][c], vol["attenuationColor"][c])
        blender = (1 - va["Color"][c]) * va["Density"] / 1000  # Blender's absorption, mm^-1
        print("channel %d: sigma_a %.6g /mm, Blender's absorption %.6g /mm (%.2f%%)"
              % (c, sigma_a[c], blender, 100 * blender / sigma_a[c]))
        if not (0.95 * sigma_a[c] <= blender <= sigma_a[c] * (1 + 1e-6)):
            bad.append("channel %d: Blender's absorption %.6g, sigma_a %.6g: more than 5%% off" % (c, blender, sigma_a[c]))
print("\n".join(bad))
sys.exit(1 if bad else 0)
EOF

echo "$passed passed, $failed failed"
[ "$failed" = 0 ]
