// facet — the HLSL shading pass over the G-buffer (the vulkan-hlsl renderer): the
// material's generated HLSL (targets/targets.h, hlsl_parts) under
// renderers/harness/gbuffer_shade.hlsl, a pixel shader `main` that reads the seven
// G-buffer images at its pixel and calls facet_shade. glslangValidator -D -V -S frag
// -e main compiles it to SPIR-V.
#pragma once

#include <string>

#include "catalog/material.h"

namespace facet {

std::string hlsl_shading_source(const Material& m);

}  // namespace facet
