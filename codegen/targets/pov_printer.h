// facet — IR as POV-Ray 3.7 functions, on the shared writer (targets/writer.h).
// Private to codegen/targets (targets/pov*.cpp).
//
// POV-Ray functions are scalar: a function that reads a non-grey colour
// constant (itself or through a callee) is printed once per channel, suffixed
// _R, _G, _B. They have no local variables: a function with lets calls a chain
// of helpers F__1, F__2…, each taking the lets computed so far.
//
// Everything printed is first folded (fold()): rewrites that POV-Ray evaluates
// to the same value, so the scene reads as its formulas do.
#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/ir.h"
#include "core/vec.h"
#include "targets/writer.h"

namespace facet::targets {

// The longest line of a scene (comments and mesh data included).
inline constexpr size_t kPovWidth = 120;

// POV-Ray's keywords are lower case: identifiers that start upper case never clash.
std::string capital(const std::string& s);

// A number as POV-Ray reads it back exactly: "pi" for π, "0" for ±0.
std::string pov_number(double v);
std::string pov_vector(const Vec3& v);  // <x, y, z>
std::string pov_rgb(const std::array<double, 3>& c);    // <r, g, b>

// The scaffolding is IR too: functions named Facet_… (the shading frame, the
// lights, the objects), built from these and printed like the catalog's.
bool is_scaffold(const ir::Function& f);
ir::Expr var(const std::string& name);                            // a parameter or SDL identifier
ir::FunctionPtr declared(const std::string& name, size_t params);  // a function declared elsewhere
bool is_declared(const ir::Function& f);                            // made by declared(): never printed

// `n` with channel `ch` of its colour literals, rewritten where POV-Ray's
// double arithmetic (IEEE 754) gives the same value:
//   exactly: x*1, 1*x, x/1 → x; x - 0 → x; -(-x) → x; x*-1 → -x; (-x)*(-y) → x*y;
//     x + (-y) → x - y and x - (-y) → x + y, for -y a negative number, a minus or
//     a negative number times y (IEEE 754 defines x - y as x + (-y));
//   the same but for the sign of a zero result: x + 0, 0 + x → x; 0 - x → -x;
//     -(number) → the negated number (POV-Ray's numbers print ±0 as 0 anyway);
//     0*x, x*0 → 0 where x is a finite number or a variable named in `finite`.
ir::NodePtr fold(const ir::NodePtr& n, int ch, const std::set<std::string>& finite);
// The variables fold() takes as finite in the scaffolding (functions named
// Facet_…): the hit point x, y, z; the unit normal Nx, Ny, Nz; and Lx, Ly, Lz,
// the unit l or the vector to a light. Each is finite wherever POV-Ray shades;
// where a normal or l is not (0/0 at a degenerate mesh normal, or at the light
// itself) all three components are NaN, and so is n·l and the reflectance.
const std::set<std::string>& pov_finite_variables();

class PovPrinter : public ExprWriter {
 public:
  // Functions in `own` (a material's lobes, reflectance and scaffolding) and
  // every constant get `prefix`, so several materials can share one scene file;
  // catalog terms are shared and printed once.
  explicit PovPrinter(std::string prefix = "", std::set<const ir::Function*> own = {})
      : prefix_(std::move(prefix)), own_(std::move(own)) {}

  void add_own(const ir::FunctionPtr& f) {
    own_.insert(f.get());
    alive_.push_back(f);
  }
  bool channel_dependent(const ir::FunctionPtr& f) const;
  std::string name(const ir::FunctionPtr& f, int channel) const;
  std::string constant_name(const ir::Node& c, int channel) const;
  // #declare lines of the constants `cs`.
  std::string constants(const std::vector<ir::NodePtr>& cs) const;
  // `n`, channel `ch`, folded; `finite` as for fold().
  std::string expr(const ir::NodePtr& n, int ch, const std::set<std::string>& finite = {}) const;
  // Every channel's declarations of `f`, with its citation and doc as comments.
  std::string function(const ir::FunctionPtr& f) const;

 protected:
  void leaf_to(std::string& out, const ir::Node& n) const override;
  // Products and quotients tight (a*b/c), sums spaced: as POV-Ray's own scenes write them, and shorter.
  bool spaced(ir::Op op) const override { return op != ir::Op::Mul && op != ir::Op::Div; }
  bool spells(const ir::Node& n) const override;
  void spell_to(std::string& out, const ir::NodePtr& n) const override;
  void callee_to(std::string& out, const ir::Node& call) const override;

 private:
  void condition_to(std::string& out, const ir::NodePtr& n) const;
  std::string channel_function(const ir::FunctionPtr& f, int ch) const;
  std::string prefix_;
  std::set<const ir::Function*> own_;
  // Keyed by address: the functions are kept alive, so no other takes their address.
  mutable std::map<const ir::Function*, std::pair<ir::FunctionPtr, bool>> dependent_;
  std::vector<ir::FunctionPtr> alive_;
  mutable int ch_ = 0;                             // the channel being printed
  mutable const std::set<std::string>* finite_ = nullptr;  // for the Selects spelled
};

// `#declare name = function(params) { body }`: one line where it fits, else the
// body on lines of its own.
void declare_function_to(std::string& out, const std::string& name, const std::string& params,
                         const std::string& body);

}  // namespace facet::targets
