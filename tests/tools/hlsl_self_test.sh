#!/bin/sh
# hlsl_check.sh has teeth: wrong HLSL fails it. GLSL's vec3 in place of float3 (glslang's
# HLSL front end refuses it), and GLSL's splat float3(x) (glslang accepts it, fxc and dxc
# do not: the check's grep refuses it).   hlsl_self_test.sh FACET MATERIAL OUTDIR
set -u
facet=$1 material=$2 out=$3
dir=$(dirname "$0")
status=0
for case in "vec3|s/static const float3 tangent_axis = float3(/static const vec3 tangent_axis = vec3(/|ERROR" \
            "splat|s/static const float3 tangent_axis = float3(\([^,]*\),[^)]*)/static const float3 tangent_axis = float3(\1)/|a splat"; do
  what=${case%%|*} rest=${case#*|}
  edit=${rest%|*} expect=${rest##*|}
  if output=$(sh "$dir/hlsl_check.sh" "$facet" "$material" "$out/$what" "$edit" 2>&1); then
    echo "FAIL: hlsl_check.sh passed HLSL with $what:"; echo "$output"; status=1
  elif ! printf '%s' "$output" | grep -q "$expect"; then
    echo "FAIL: hlsl_check.sh failed with $what, but not saying \"$expect\":"; echo "$output"; status=1
  else
    echo "ok: $what refused: $(printf '%s' "$output" | grep -m1 "$expect")"
  fi
done
exit $status
