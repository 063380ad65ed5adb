#!/usr/bin/env bash
# Makes the README's pictures from real `facet validate` runs, photographed by headless Chromium:
#   docs/facet.png     a few classic materials on the `shadows` scene as the C++ reference,
#                      OpenGL, Cycles (OSL) and POV-Ray render them;
#   docs/gltf_pbr.png  the glTF PBR examples (examples/gltf_pbr/) on the `single` sphere, the same
#                      four renderers side by side;
#   docs/plot_ward.png the diagram: Ward's lobe in its two planes.
set -euo pipefail
cd "$(dirname "$0")/.."

# picture OUT.png TITLE SCENE SIZE IMAGE_PX WIDTHxHEIGHT FILE... : one column per material file,
# one row per renderer, and the validation's summary line under the table.
picture() {
  local png=$1 title=$2 scene=$3 size=$4 px=$5 window=$6
  shift 6
  local out=out/readme/$(basename "$png" .png)
  mkdir -p "$out"
  build/bin/facet validate "$@" --scene "$scene" --size "$size" \
    --out "$out" > "$out.log" 2>&1 || { cat "$out.log"; exit 1; }
  {
    echo "<!doctype html><meta charset=utf-8><style>
    body { margin: 0; padding: 14px 16px; background: #16181c; color: #e8e8e8; font: 15px system-ui, sans-serif; }
    h1 { font-size: 19px; margin: 0 0 10px; font-weight: 600; } table { border-spacing: 6px 4px; }
    td, th { text-align: center; font-weight: 500; font-size: 13px; color: #bbb; }
    img { width: ${px}px; height: ${px}px; display: block; border-radius: 3px; } td.name { text-align: right; color: #e8e8e8; }
    p { margin: 8px 0 0; font-size: 13px; color: #9ab; }
    </style><h1>$title</h1><table>
    <tr><th></th>"
    local f m
    for f in "$@"; do  # the file's name as words: ior_1_33 -> ior 1.33
      m=$(basename "$f" .json | sed -E 's/([0-9])_([0-9])/\1.\2/g; s/_/ /g'); echo "<th>$m</th>"
    done
    echo '</tr>'
    for r in reference:"C++ reference" glsl:"OpenGL (GLSL)" osl:"Cycles (OSL)" pov:"POV-Ray"; do
      local key=${r%%:*} label=${r#*:}
      echo "<tr><td class=name>$label</td>"
      for f in "$@"; do
        m=$(python3 -c 'import json,sys; print(json.load(open(sys.argv[1]))["name"])' "$f")
        echo "<td><img src=\"images/${m}_${scene}_${key}.png\"></td>"
      done
      echo '</tr>'
    done
    echo "</table><p>$(tail -1 "$out.log" | sed 's/&/\&amp;/g; s/</\&lt;/g')</p>"
  } > "$out/picture.html"
  chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size="${window/x/,}" \
    --screenshot="$PWD/$png" "file://$PWD/$out/picture.html" > /dev/null 2>&1
  echo "$png"
}

classic=()
for m in lambert oren_nayar cook_torrance ward toon ggx_conductor; do classic+=("examples/materials/$m.json"); done
picture docs/facet.png "One material description → GLSL, OSL, POV-Ray: the same pixels" shadows 256x256 150 1110x760 \
  "${classic[@]}"

gltf=()
for m in plastic_rough plastic_glossy matte_ior_1_0 water_ior_1_33 diamond_ior_2_4 specular_tinted specular_clamped \
         half_metal gold_rough gold_polished coat_red_paint coat_over_gold sheen_velvet sheen_satin; do
  gltf+=("examples/gltf_pbr/$m.json")
done
picture docs/gltf_pbr.png \
  "glTF 2.0 metallic–roughness (Appendix B, KHR_materials_ior, _specular, _sheen, _clearcoat): the same pixels" \
  single 128x128 96 1700x560 "${gltf[@]}"

# The README's diagram: Ward's lobe in its two planes.
build/bin/facet plot examples/materials/ward.json --light-angle 30 -o docs/plot_ward.png 2> /dev/null
echo "docs/plot_ward.png"
