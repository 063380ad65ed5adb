#!/bin/sh
# Generates a material for a GLSL dialect and runs glslangValidator on it
# (-V, to SPIR-V, for glsl450).   glsl_check.sh FACET MATERIAL DIALECT OUTDIR
set -eu
facet=$1 material=$2 dialect=$3 out=$4
mkdir -p "$out"
name=$(basename "$material" .json)
"$facet" generate "$material" --target "$dialect" -o "$out/$name.$dialect.frag"
if [ "$dialect" = glsl450 ]; then
  glslangValidator -V "$out/$name.$dialect.frag" -o "$out/$name.spv"
else
  glslangValidator "$out/$name.$dialect.frag"
fi
