#!/usr/bin/env bash
# Makes docs/facet.png, the README's picture (and docs/plot_ward.png, its diagram): a few materials on the `shadows`
# scene as the C++ reference, OpenGL, Cycles (OSL) and POV-Ray render them,
# from a real `facet validate` run, photographed by headless Chromium.
set -euo pipefail
cd "$(dirname "$0")/.."
out=out/readme
mkdir -p "$out"
materials=(lambert oren_nayar cook_torrance ward toon ggx_conductor)
files=()
for m in "${materials[@]}"; do files+=("examples/materials/$m.json"); done
build/bin/facet validate "${files[@]}" --scene shadows --size 256x256 --out "$out" > "$out.log" 2>&1 || {
  cat "$out.log"; exit 1; }
{
  echo '<!doctype html><meta charset=utf-8><style>
  body { margin: 0; padding: 14px 16px; background: #16181c; color: #e8e8e8; font: 15px system-ui, sans-serif; }
  h1 { font-size: 19px; margin: 0 0 10px; font-weight: 600; } table { border-spacing: 6px 4px; }
  td, th { text-align: center; font-weight: 500; font-size: 13px; color: #bbb; }
  img { width: 150px; height: 150px; display: block; border-radius: 3px; } td.name { text-align: right; color: #e8e8e8; }
  p { margin: 8px 0 0; font-size: 13px; color: #9ab; }
  </style><h1>One material description → GLSL, OSL, POV-Ray: the same pixels</h1><table>
  <tr><th></th>'
  for m in "${materials[@]}"; do echo "<th>$m</th>"; done
  echo '</tr>'
  for r in reference:"C++ reference" glsl:"OpenGL (GLSL)" osl:"Cycles (OSL)" pov:"POV-Ray"; do
    key=${r%%:*}; label=${r#*:}
    echo "<tr><td class=name>$label</td>"
    for m in "${materials[@]}"; do echo "<td><img src=\"images/${m}_shadows_${key}.png\"></td>"; done
    echo '</tr>'
  done
  echo "</table><p>$(tail -1 "$out.log" | sed 's/&/\&amp;/g; s/</\&lt;/g')</p>"
} > "$out/picture.html"
chromium --headless --no-sandbox --disable-gpu --hide-scrollbars --window-size=1110,760 \
  --screenshot="$PWD/docs/facet.png" "file://$PWD/$out/picture.html" > /dev/null 2>&1
echo "docs/facet.png"
# The README's diagram: Ward's lobe in its two planes.
build/bin/facet plot examples/materials/ward.json --light-angle 30 -o docs/plot_ward.png 2> /dev/null
echo "docs/plot_ward.png"
