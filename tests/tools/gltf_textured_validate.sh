#!/bin/sh
# A textured glTF written by Blender's exporter (gltf_textured_blender.py, in FOLDER),
# imported by facet and validated against the reference on one renderer.
#
#   gltf_textured_validate.sh FACET FOLDER VARIANT RENDERER PYTHON
#
# VARIANT: glb (images embedded), external (image files beside the .gltf, one URI
# percent-encoded), datauri (images as data URIs), roundtrip (the GLB's import
# written back by `facet export-gltf` as .gltf, its images copied beside it, and
# imported again).
set -eu
facet=$1 folder=$2 variant=$3 renderer=$4 python=$5
work=$folder/$variant-$renderer
rm -rf "$work"
mkdir -p "$work"
case $variant in
  glb) in=$folder/textured.glb ;;
  external) in=$folder/external/textured.gltf ;;
  datauri) in=$folder/datauri/textured.gltf ;;
  roundtrip)
    "$facet" import-gltf "$folder/textured.glb" -o "$work/first/scene.json"
    "$facet" export-gltf "$work/first/scene.json" -o "$work/exported/textured.gltf"
    for key in normalTexture emissiveTexture; do  # glTF's own keys, for other viewers (k_d is baked: no baseColorTexture)
      grep -q "\"$key\"" "$work/exported/textured.gltf" || { echo "FAIL: export-gltf wrote no $key" >&2; exit 1; }
    done
    in=$work/exported/textured.gltf ;;
  *) echo "unknown variant $variant" >&2; exit 2 ;;
esac
"$facet" import-gltf "$in" -o "$work/scene.json"
grep -q '"texture"' "$work/scene.json" || { echo "FAIL: the imported scene has no textures" >&2; exit 1; }
grep -q '"normal_map"' "$work/scene.json" || { echo "FAIL: the sphere's normalTexture was not imported" >&2; exit 1; }
grep -q '"emission": *{' "$work/scene.json" || { echo "FAIL: the plane's emissiveTexture was not imported" >&2; exit 1; }
"$facet" validate --scene "$work/scene.json" --renderers "reference,$renderer" --size 160x120 --python "$python" \
  --out "$work/validate"
