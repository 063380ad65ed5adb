#!/bin/sh
# The glTF corpus (gltf_corpus.py, in FOLDER/corpus) imported by facet and validated on one
# renderer against the reference: every file in one `facet validate` call (--scene repeated),
# so a renderer with a slow start (webgl, vulkan, wgpu, osl) starts once for the corpus.
#
#   gltf_corpus_validate.sh FACET FOLDER RENDERER PYTHON [SIZE]
#
# FOLDER/corpus holds at least 20 files.
#
# Passes only if every file imports and every comparison passes; `facet validate` counts a
# scene whose reference is black, one colour, or shows an object from behind or unlit as
# UNINFORMATIVE, not passed, so a file that imported inside out fails here too.
set -eu
facet=$1 folder=$2 renderer=$3 python=$4 size=${5:-96x72}
work=$folder/validate/$renderer
rm -rf "$work"
mkdir -p "$work/scenes"
set --
count=0
for file in "$folder/corpus"/*.gltf "$folder/corpus"/*.glb; do
  [ -e "$file" ] || continue
  stem=$(basename "$file")
  stem=${stem%.*}
  "$facet" import-gltf "$file" -o "$work/scenes/$stem.json" 2> "$work/scenes/$stem.notes" ||
    { cat "$work/scenes/$stem.notes" >&2; echo "FAIL: facet import-gltf $file" >&2; exit 1; }
  set -- "$@" --scene "$work/scenes/$stem.json"
  count=$((count + 1))
done
[ "$count" -ge 20 ] ||
  { echo "FAIL: only $count corpus files in $folder/corpus (gltf_corpus.py writes 28)" >&2; exit 1; }
"$facet" validate "$@" --renderers "reference,$renderer" --size "$size" --python "$python" --out "$work/out" |
  tee "$work/validate.log"
grep -q "facet validate: $count of $count comparisons pass" "$work/validate.log" ||
  { echo "FAIL: expected $count of $count comparisons to pass" >&2; exit 1; }
