// facet — printing IR as C-like shading code (GLSL, OSL and HLSL share this).
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "catalog/program.h"
#include "core/ir.h"
#include "targets/writer.h"

namespace facet::targets {

struct CDialect {
  std::string float_type = "float";
  std::string color_type = "vec3";
  std::string color_ctor = "vec3";
  std::string atan2_name = "atan";
  std::string pi_name = "PI";
  // GLSL's vec3(x) repeats one number; HLSL's float3 constructor wants all three
  // (fxc and dxc refuse float3(x)): a grey literal is written out in full and a
  // number promoted to a colour is cast, (float3)(x).
  bool splat_ctor = true;
  // OSL has no global constants: a function receives the material constants
  // it reads (directly or through its callees) as trailing parameters.
  bool constants_as_params = false;
};

// The shared writer (targets/writer.h) with C's leaves: "2.0" for 2 (ESSL has no
// implicit int → float), colour constructors, float → colour promotion. GLSL, OSL
// and HLSL are its dialects.
class CPrinter : public ExprWriter {
 public:
  explicit CPrinter(CDialect d) : d_(std::move(d)) {}

  std::string type(ir::Type t) const { return t == ir::Type::Float ? d_.float_type : d_.color_type; }
  std::string literal(double v) const;
  std::string color_literal(const std::array<double, 3>& rgb) const;
  std::string expr(const ir::NodePtr& n) const;
  // The same, appended to `out`.
  void literal_to(std::string& out, double v) const;
  void color_literal_to(std::string& out, const std::array<double, 3>& rgb) const;
  // The whole definition: signature, citation on the first line, lets, return.
  std::string function(const ir::FunctionPtr& f) const;
  // The material constants `f` reads, itself or through callees (first-use order).
  const std::vector<ir::NodePtr>& free_constants(const ir::FunctionPtr& f) const;

 protected:
  void leaf_to(std::string& out, const ir::Node& n) const override;
  const char* builtin(ir::Op op) const override;
  void extra_args_to(std::string& out, const ir::Node& call) const override;
  void operand_to(std::string& out, const ir::Node& parent, size_t i) const override;

 private:
  void as_to(std::string& out, const ir::NodePtr& n, ir::Type wanted) const;  // promotes float → color where asked
  CDialect d_;
  mutable std::map<const ir::Function*, std::vector<ir::NodePtr>> free_cache_;
};

// The material's constants, one "<qualifier> <type> <name> = <value>;" line each in `printer`'s
// types: m_a and m_e unless an image sets them (kAmbientInput, kEmissionInput), tangent_axis,
// and the program's constants. GLSL's qualifier is "const", HLSL's "static const".
std::string material_constants(const MaterialProgram& p, const CPrinter& printer, const std::string& qualifier);

// "// text" lines, one per line of `text`, with `indent` before each.
std::string comment_lines(const std::string& text, const std::string& indent, const std::string& marker = "//");

}  // namespace facet::targets
