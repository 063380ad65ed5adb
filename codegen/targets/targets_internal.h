// Shared by the target printers; private to codegen/src/targets.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "catalog/material.h"
#include "catalog/program.h"
#include "targets/targets.h"

#ifndef FACET_VERSION
#error "FACET_VERSION is set by CMake"
#endif

namespace facet {

// A few comment lines naming the lobes and their parameters, each starting with `marker`.
std::string describe_material(const Material& m, const std::string& marker);
std::string describe_lobe(const ModelSpec& s);

// facet_reflect's `let b = …;` statement where the lobes read b (C-family targets): n × t, or
// w·(n × t) where they read the texture frame's tangent (MaterialProgram::uv_tangent).
std::string bitangent(const MaterialProgram& p, const std::string& let);


// The call of MaterialProgram::emission_weight (it must have one) at n·v written `NoV`: its
// textured parameters are the globals or locals of the same names the shading sampled; `after`
// follow them (OSL's free constants).
std::string emission_weight_call(const MaterialProgram& p, const std::string& NoV,
                                 const std::vector<std::string>& after = {});
// The lights templates' facet_emitted(n, v): "emitted", its return expression (m_e, times
// emission_weight(n·v) where layers lie over the emission: MaterialProgram::emission_weight), and
// "emitted_doc", what it is. The same text in GLSL, HLSL and WGSL.
void emitted_values(const MaterialProgram& p, std::map<std::string, std::string>& values);
// The library templates' facet_reflect(n, l, v, t[, c]) where the reflectance reads the coat's own
// normal (MaterialProgram::uses_coat_normal): "coat_param", c's declaration after t (`declaration`,
// in the target's spelling), and "coat_doc", what c is; empty otherwise.
void coat_normal_values(const MaterialProgram& p, const std::string& declaration,
                        std::map<std::string, std::string>& values);
// The normal maps' mapping functions of a C-family target, rendered from `template_path`
// (glsl/normal_map.glsl, …) with `literal` the target's number: facet_normal_mapped(n, t, w) for
// the lobes' map, facet_coat_normal_mapped(n, t, w) for the coat's (Material::coat_normal_map),
// each reading its sampled global (normal_map, coat_normal_map). Empty without either.
std::string normal_map_functions(const MaterialProgram& p, const std::string& template_path,
                                 const std::function<std::string(double)>& literal);
// The light templates' "mapping" (the lobes' normal ns and the tangent that follows it; the
// coat's nc where the coat has its own map), "coat_arg", what facet_reflect takes after t, and
// "emitted_normal", the normal facet_emitted reads (the coat's), in a C-family target whose local
// declaration is `let` ("vec3", "float3", "let").
void normal_mapping_values(const MaterialProgram& p, const std::string& let, std::map<std::string, std::string>& values);
// The argument a caller of facet_reflect passes after t: ", `normal`" (the coat's normal) where it
// takes one, else "".
std::string coat_normal_arg(const MaterialProgram& p, const std::string& normal);

std::string generate_glsl(const Material& m, const GenerateOptions& o);
std::string generate_osl(const Material& m, const GenerateOptions& o);
std::string generate_pov(const Material& m, const GenerateOptions& o);
std::string generate_hlsl(const Material& m, const GenerateOptions& o);
std::string generate_wgsl(const Material& m, const GenerateOptions& o);

}  // namespace facet
