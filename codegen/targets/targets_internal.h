// Shared by the target printers; private to codegen/src/targets.
#pragma once

#include <string>

#include "catalog/material.h"
#include "targets/targets.h"

#ifndef FACET_VERSION
#error "FACET_VERSION is set by CMake"
#endif

namespace facet {

// A few comment lines naming the lobes and their parameters, each starting with `marker`.
std::string describe_material(const Material& m, const std::string& marker);
std::string describe_lobe(const ModelSpec& s);

// Throws InputError naming each textured parameter of `m` (file and key) for a target
// that does not sample images yet.
void require_untextured(const Material& m, const std::string& target);

std::string generate_glsl(const Material& m, const GenerateOptions& o);
std::string generate_osl(const Material& m, const GenerateOptions& o);
std::string generate_pov(const Material& m, const GenerateOptions& o);
std::string generate_hlsl(const Material& m, const GenerateOptions& o);
std::string generate_wgsl(const Material& m, const GenerateOptions& o);

}  // namespace facet
