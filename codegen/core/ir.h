// facet — the expression IR every target is printed from.
//
// A model's formula is written once, in C++, as a tree of `Expr` nodes inside
// named `Function`s (one function per term: D_beckmann, G_v_cavity, F_schlick…).
// The GLSL, OSL and POV-Ray printers walk these trees, and the C++ reference
// evaluates them in double precision, so the four can only differ where the
// printers differ, never in the formula.
//
// Values are of two types: Float (a scalar) and Color (linear RGB, componentwise
// arithmetic). Comparisons take Floats only, so every target can express them.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace facet::ir {

enum class Type { Float, Color };
const char* type_name(Type t);

enum class Op {
  // leaves
  Literal,   // a number or an RGB triple
  Constant,  // a named material constant: printed once, referenced by name
  Arg,       // a parameter of the enclosing function
  Local,     // a `let` of the enclosing function
  // arithmetic (Color op Float broadcasts)
  Neg, Add, Sub, Mul, Div,
  // builtins, componentwise
  Min, Max, Clamp, Sqrt, Exp, Pow, Acos, Atan2, Abs, Sin, Cos, Floor,
  Step,        // step(edge, x): x >= edge ? 1 : 0
  // conditions (Float only); And/Or combine conditions
  Lt, Le, Gt, Ge, And, Or,
  Select,      // cond ? a : b
  Call,        // a call of another Function
};

struct Function;
struct Node;
using NodePtr = std::shared_ptr<const Node>;
using FunctionPtr = std::shared_ptr<const Function>;

struct Node {
  Op op;
  Type type = Type::Float;
  std::array<double, 3> value{};  // Literal, Constant
  std::string name;               // Constant, Arg, Local
  std::vector<NodePtr> args;      // operands
  FunctionPtr callee;             // Call
  bool is_condition() const;
};

// An expression handle with the operators a formula needs.
class Expr {
 public:
  Expr(double v);  // NOLINT(google-explicit-constructor): lets formulas say `1 - x`
  explicit Expr(NodePtr n) : node_(std::move(n)) {}
  const NodePtr& node() const { return node_; }
  Type type() const { return node_->type; }

 private:
  NodePtr node_;
};

// A boolean condition; only usable as the first operand of select().
class Cond {
 public:
  explicit Cond(NodePtr n) : node_(std::move(n)) {}
  const NodePtr& node() const { return node_; }

 private:
  NodePtr node_;
};

Expr color(double r, double g, double b);
Expr operator-(const Expr& a);
Expr operator+(const Expr& a, const Expr& b);
Expr operator-(const Expr& a, const Expr& b);
Expr operator*(const Expr& a, const Expr& b);
Expr operator/(const Expr& a, const Expr& b);
Expr min(const Expr& a, const Expr& b);
Expr max(const Expr& a, const Expr& b);
Expr clamp(const Expr& x, const Expr& lo, const Expr& hi);
Expr sqrt(const Expr& x);
Expr exp(const Expr& x);
Expr pow(const Expr& x, const Expr& e);
Expr acos(const Expr& x);
Expr atan2(const Expr& y, const Expr& x);
Expr abs(const Expr& x);
Expr sin(const Expr& x);
Expr cos(const Expr& x);
Expr floor(const Expr& x);
Expr step(const Expr& edge, const Expr& x);
Cond operator<(const Expr& a, const Expr& b);
Cond operator<=(const Expr& a, const Expr& b);
Cond operator>(const Expr& a, const Expr& b);
Cond operator>=(const Expr& a, const Expr& b);
Cond operator&&(const Cond& a, const Cond& b);
Cond operator||(const Cond& a, const Cond& b);
Expr select(const Cond& c, const Expr& if_true, const Expr& if_false);

// [x] = max(0, x), MODELS.md's bracket.
inline Expr pos(const Expr& x) { return max(x, 0.0); }
// A cosine as a power's base: clamped into [0, 1], where it lies exactly. A target's
// dot product of unit vectors can round past 1, and x^n for n up to 1e6 turns that
// into ∞ (docs/float32.md).
inline Expr unit(const Expr& x) { return clamp(x, 0.0, 1.0); }
inline Expr sq(const Expr& x) { return x * x; }

// A named constant of the material (a parameter value); targets declare it once.
Expr constant(const std::string& name, double v);
Expr constant(const std::string& name, std::array<double, 3> rgb);

struct Param {
  std::string name;
  Type type;
};
struct Let {
  std::string name;
  Expr value;
};

// One function per term. `citation` is printed on the first line of its body.
struct Function {
  std::string name;
  std::string citation;
  std::string doc;
  std::vector<Param> params;
  std::vector<Let> lets;
  Expr result{0.0};
  Type result_type() const { return result.type(); }
};

// Builds a Function: declare parameters, bind intermediate values, return.
class FunctionBuilder {
 public:
  FunctionBuilder(std::string name, std::string citation, std::string doc = {});
  Expr param(const std::string& name, Type type = Type::Float);
  Expr let(const std::string& name, const Expr& value);
  bool has_param(const std::string& name) const;
  Expr arg(const std::string& name) const;  // a parameter declared before
  // Reorders parameters (e.g. shading inputs into their canonical order).
  void order_params(const std::vector<std::string>& order);
  FunctionPtr returns(const Expr& result);

 private:
  Function fn_;
};

Expr call(const FunctionPtr& f, const std::vector<Expr>& args);

// Every function `roots` call, directly or not, callees before callers, each once.
std::vector<FunctionPtr> dependencies(const std::vector<FunctionPtr>& roots);
// Every named constant reachable from `roots`, in first-use order, each once.
std::vector<NodePtr> constants(const std::vector<FunctionPtr>& roots);

}  // namespace facet::ir
