#!/bin/sh
# Generates a material for HLSL, the whole pixel shader and the --library, and runs
# glslang's HLSL front end on each (glslangValidator -D -V -S frag -e main: HLSL to
# SPIR-V, validated); the library under a small pixel-shader main that calls
# facet_reflect (and facet_sample_textures, for a textured material, with the vertex colour
# where it reads one; the coat's normal after t, where it takes one); the pixel shader
# also with -DFACET_SPIRV -DFACET_VERTEX_TANGENT. glslang accepts
# GLSL's one-number float3(x), which fxc and dxc refuse: a grep refuses it here.
#   hlsl_check.sh FACET MATERIAL OUTDIR [SED]
# SED (tests only, hlsl_self_test.sh): an edit applied to the generated files first.
set -eu
facet=$1 material=$2 out=$3 mutate=${4:-}
mkdir -p "$out"
name=$(basename "$material" .json)

check() {  # check FILE.hlsl
  if [ -n "$mutate" ]; then sed -i "$mutate" "$1"; fi
  if grep -nE 'float3\([^,()]*\)' "$1"; then
    echo "$1: float3(x) with one number (a splat): fxc and dxc refuse it; write float3(x, x, x) or (float3)(x)" >&2
    exit 1
  fi
  glslangValidator -D -V -S frag -e main "$1" -o "${1%.hlsl}.spv"
}

"$facet" generate "$material" --target hlsl -o "$out/$name.hlsl"
check "$out/$name.hlsl"
# The main's other branch: the vertex tangent, and each input at the glsl450 shader's location.
glslangValidator -D -V -S frag -e main -DFACET_SPIRV -DFACET_VERTEX_TANGENT "$out/$name.hlsl" -o "$out/$name.vk.spv"
"$facet" generate "$material" --target hlsl --library -o "$out/$name.lib.hlsl"
{
  cat "$out/$name.lib.hlsl"
  echo
  echo "float4 main(float3 n : TEXCOORD0, float3 l : TEXCOORD1, float3 v : TEXCOORD2, float4 uv : TEXCOORD3,"
  echo "            float4 color0 : COLOR0) : SV_Target"
  echo "{"
  if grep -q "void facet_sample_textures(float2 uv0, float2 uv1, float4 color0)" "$out/$name.lib.hlsl"; then
    echo "    facet_sample_textures(uv.xy, uv.zw, color0);  // a material that reads the vertex colour"
  elif grep -q "void facet_sample_textures" "$out/$name.lib.hlsl"; then
    echo "    facet_sample_textures(uv.xy, uv.zw);"
  fi
  echo "    float3 nn = normalize(n);"
  coat=""
  if grep -q "float3 facet_reflect(float3 n, float3 l, float3 v, float3 t, float3 c)" "$out/$name.lib.hlsl"; then
    coat=", nn"  # the clear coat's own normal: here the surface's
  fi
  echo "    return float4(facet_reflect(nn, normalize(l), normalize(v), facet_tangent(nn)$coat), 1.0);"
  echo "}"
} > "$out/$name.lib.main.hlsl"
check "$out/$name.lib.main.hlsl"
