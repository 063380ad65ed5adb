#include "renderers/hlsl_shading.h"

#include <map>

#include "catalog/program.h"
#include "renderers/harness.h"
#include "targets/glsl_lights.h"
#include "targets/targets.h"

namespace facet {

std::string hlsl_shading_source(const Material& m) {
  MaterialProgram p = compile(m);
  HlslParts parts = hlsl_parts(p, m.source.empty() ? m.name : m.source, LightSource::Buffer);
  // What raycast.glsl's main does after the hit, at the G-buffer's uv and tangent frame.
  std::string sample;
  if (p.has_textures())
    sample = p.uses_vertex_color() ? "    facet_sample_textures(uvs.xy, uvs.zw, facet_gbuffer_color0.Load(texel));\n"
                                   : "    facet_sample_textures(uvs.xy, uvs.zw);\n";
  if (p.has_uv_frame()) sample += "    facet_uv_tangent = frame.xyz;\n    facet_uv_handedness = frame.w;\n";
  std::map<std::string, std::string> values = glsl_light::visibility_values();
  values["sample"] = sample;
  return parts.header + parts.library + parts.lights + render_harness("gbuffer_shade.hlsl", values);
}

}  // namespace facet
