#include "core/ir.h"

#include <algorithm>
#include <functional>
#include <set>
#include <stdexcept>

namespace facet::ir {

const char* type_name(Type t) { return t == Type::Float ? "float" : "color"; }

bool Node::is_condition() const {
  switch (op) {
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::And: case Op::Or:
      return true;
    default:
      return false;
  }
}

namespace {

// Catalog mistakes are programming errors: they surface as exceptions the
// moment a formula is built, and the catalog test builds every formula.
[[noreturn]] void ill_formed(const std::string& what) {
  throw std::logic_error("facet IR: " + what);
}

NodePtr make(Op op, Type type, std::vector<NodePtr> args) {
  auto n = std::make_shared<Node>();
  n->op = op;
  n->type = type;
  n->args = std::move(args);
  for (const auto& a : n->args) {
    if (a->is_condition() && op != Op::Select && op != Op::And && op != Op::Or)
      ill_formed("a condition can only be used by select()");
  }
  return n;
}

Type join(std::initializer_list<Expr> es) {
  for (const auto& e : es)
    if (e.type() == Type::Color) return Type::Color;
  return Type::Float;
}

Expr op(Op o, std::initializer_list<Expr> es) {
  std::vector<NodePtr> args;
  for (const auto& e : es) args.push_back(e.node());
  return Expr(make(o, join(es), std::move(args)));
}

Cond compare(Op o, const Expr& a, const Expr& b) {
  if (a.type() != Type::Float || b.type() != Type::Float)
    ill_formed("comparisons take floats only (every target must be able to print them)");
  return Cond(make(o, Type::Float, {a.node(), b.node()}));
}

NodePtr literal(std::array<double, 3> v, Type t) {
  auto n = std::make_shared<Node>();
  n->op = Op::Literal;
  n->type = t;
  n->value = v;
  return n;
}

}  // namespace

Expr::Expr(double v) : node_(literal({v, v, v}, Type::Float)) {}

Expr color(double r, double g, double b) { return Expr(literal({r, g, b}, Type::Color)); }

Expr operator-(const Expr& a) { return op(Op::Neg, {a}); }
Expr operator+(const Expr& a, const Expr& b) { return op(Op::Add, {a, b}); }
Expr operator-(const Expr& a, const Expr& b) { return op(Op::Sub, {a, b}); }
Expr operator*(const Expr& a, const Expr& b) { return op(Op::Mul, {a, b}); }
Expr operator/(const Expr& a, const Expr& b) { return op(Op::Div, {a, b}); }
Expr min(const Expr& a, const Expr& b) { return op(Op::Min, {a, b}); }
Expr max(const Expr& a, const Expr& b) { return op(Op::Max, {a, b}); }
Expr clamp(const Expr& x, const Expr& lo, const Expr& hi) {
  if (lo.type() != Type::Float || hi.type() != Type::Float) ill_formed("clamp bounds must be floats");
  return op(Op::Clamp, {x, lo, hi});
}
Expr sqrt(const Expr& x) { return op(Op::Sqrt, {x}); }
Expr exp(const Expr& x) { return op(Op::Exp, {x}); }
Expr pow(const Expr& x, const Expr& e) {
  if (e.type() != Type::Float) ill_formed("pow exponents must be floats");
  return op(Op::Pow, {x, e});
}
Expr acos(const Expr& x) { return op(Op::Acos, {x}); }
Expr atan2(const Expr& y, const Expr& x) {
  if (y.type() != Type::Float || x.type() != Type::Float) ill_formed("atan2 takes floats");
  return op(Op::Atan2, {y, x});
}
Expr abs(const Expr& x) { return op(Op::Abs, {x}); }
Expr sin(const Expr& x) { return op(Op::Sin, {x}); }
Expr cos(const Expr& x) { return op(Op::Cos, {x}); }
Expr floor(const Expr& x) { return op(Op::Floor, {x}); }
Expr step(const Expr& edge, const Expr& x) {
  if (edge.type() != Type::Float) ill_formed("step edges must be floats");
  return op(Op::Step, {edge, x});
}

Cond operator<(const Expr& a, const Expr& b) { return compare(Op::Lt, a, b); }
Cond operator<=(const Expr& a, const Expr& b) { return compare(Op::Le, a, b); }
Cond operator>(const Expr& a, const Expr& b) { return compare(Op::Gt, a, b); }
Cond operator>=(const Expr& a, const Expr& b) { return compare(Op::Ge, a, b); }
Cond operator&&(const Cond& a, const Cond& b) { return Cond(make(Op::And, Type::Float, {a.node(), b.node()})); }
Cond operator||(const Cond& a, const Cond& b) { return Cond(make(Op::Or, Type::Float, {a.node(), b.node()})); }

Expr select(const Cond& c, const Expr& if_true, const Expr& if_false) {
  Type t = join({if_true, if_false});
  return Expr(make(Op::Select, t, {c.node(), if_true.node(), if_false.node()}));
}

Expr constant(const std::string& name, double v) {
  auto n = std::make_shared<Node>();
  n->op = Op::Constant;
  n->type = Type::Float;
  n->value = {v, v, v};
  n->name = name;
  return Expr(NodePtr(n));
}

Expr constant(const std::string& name, std::array<double, 3> rgb) {
  auto n = std::make_shared<Node>();
  n->op = Op::Constant;
  n->type = Type::Color;
  n->value = rgb;
  n->name = name;
  return Expr(NodePtr(n));
}

FunctionBuilder::FunctionBuilder(std::string name, std::string citation, std::string doc) {
  fn_.name = std::move(name);
  fn_.citation = std::move(citation);
  fn_.doc = std::move(doc);
}

Expr FunctionBuilder::param(const std::string& name, Type type) {
  if (has_param(name)) return arg(name);
  fn_.params.push_back({name, type});
  auto n = std::make_shared<Node>();
  n->op = Op::Arg;
  n->type = type;
  n->name = name;
  return Expr(NodePtr(n));
}

bool FunctionBuilder::has_param(const std::string& name) const {
  return std::any_of(fn_.params.begin(), fn_.params.end(), [&](const Param& p) { return p.name == name; });
}

Expr FunctionBuilder::arg(const std::string& name) const {
  for (const auto& p : fn_.params) {
    if (p.name != name) continue;
    auto n = std::make_shared<Node>();
    n->op = Op::Arg;
    n->type = p.type;
    n->name = name;
    return Expr(NodePtr(n));
  }
  ill_formed(fn_.name + " has no parameter " + name);
}

Expr FunctionBuilder::let(const std::string& name, const Expr& value) {
  for (const auto& l : fn_.lets)
    if (l.name == name) ill_formed(fn_.name + ": two lets named " + name);
  if (has_param(name)) ill_formed(fn_.name + ": let " + name + " shadows a parameter");
  fn_.lets.push_back({name, value});
  auto n = std::make_shared<Node>();
  n->op = Op::Local;
  n->type = value.type();
  n->name = name;
  return Expr(NodePtr(n));
}

void FunctionBuilder::order_params(const std::vector<std::string>& order) {
  auto rank = [&](const Param& p) {
    auto it = std::find(order.begin(), order.end(), p.name);
    return it == order.end() ? order.size() : size_t(it - order.begin());
  };
  std::stable_sort(fn_.params.begin(), fn_.params.end(),
                   [&](const Param& a, const Param& b) { return rank(a) < rank(b); });
}

FunctionPtr FunctionBuilder::returns(const Expr& result) {
  fn_.result = result;
  // Every Arg and Local must resolve inside this function.
  std::set<std::string> known;
  for (const auto& p : fn_.params) known.insert(p.name);
  std::function<void(const NodePtr&)> check = [&](const NodePtr& n) {
    if ((n->op == Op::Arg || n->op == Op::Local) && !known.count(n->name))
      ill_formed(fn_.name + " uses " + n->name + " before it is defined");
    for (const auto& a : n->args) check(a);
  };
  for (const auto& l : fn_.lets) {
    check(l.value.node());
    known.insert(l.name);
  }
  check(result.node());
  return std::make_shared<const Function>(fn_);
}

Expr call(const FunctionPtr& f, const std::vector<Expr>& args) {
  if (args.size() != f->params.size())
    ill_formed(f->name + " takes " + std::to_string(f->params.size()) + " arguments, not " +
               std::to_string(args.size()));
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i].type() == Type::Color && f->params[i].type == Type::Float)
      ill_formed(f->name + ": a color passed as float parameter " + f->params[i].name);
  }
  auto n = std::make_shared<Node>();
  n->op = Op::Call;
  n->type = f->result_type();
  n->callee = f;
  for (const auto& a : args) n->args.push_back(a.node());
  return Expr(NodePtr(n));
}

namespace {
// Plain recursion rather than a std::function per node: generate() walks every
// function's tree several times.
template <typename Visit>
void walk_nodes(const NodePtr& n, Visit& fn) {
  fn(n);
  for (const auto& a : n->args) walk_nodes(a, fn);
}

template <typename Visit>
void visit_nodes(const FunctionPtr& f, Visit fn) {
  for (const auto& l : f->lets) walk_nodes(l.value.node(), fn);
  walk_nodes(f->result.node(), fn);
}
}  // namespace

std::vector<FunctionPtr> dependencies(const std::vector<FunctionPtr>& roots) {
  std::vector<FunctionPtr> order;
  std::set<const Function*> seen;
  std::function<void(const FunctionPtr&)> visit = [&](const FunctionPtr& f) {
    if (!seen.insert(f.get()).second) return;
    visit_nodes(f, [&](const NodePtr& n) {
      if (n->op == Op::Call) visit(n->callee);
    });
    order.push_back(f);
  };
  for (const auto& r : roots) visit(r);
  return order;
}

std::vector<NodePtr> constants(const std::vector<FunctionPtr>& roots) {
  std::vector<NodePtr> out;
  std::set<std::string> seen;
  for (const auto& f : dependencies(roots)) {
    visit_nodes(f, [&](const NodePtr& n) {
      if (n->op == Op::Constant && seen.insert(n->name).second) out.push_back(n);
    });
  }
  return out;
}

}  // namespace facet::ir
