#include "cfamily.h"

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <fmt/format.h>

namespace facet::targets {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

namespace {

const double kPi = 3.14159265358979323846;

// Operator precedence, higher binds tighter.
int precedence(const Node& n) {
  switch (n.op) {
    case Op::Select: return 1;
    case Op::Or: return 2;
    case Op::And: return 3;
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: return 4;
    case Op::Add: case Op::Sub: return 5;
    case Op::Mul: case Op::Div: return 6;
    case Op::Neg: return 7;
    case Op::Literal: return n.type == Type::Float && n.value[0] < 0 ? 7 : 9;
    default: return 9;
  }
}

const char* binary_op(Op op) {
  switch (op) {
    case Op::Add: return "+";
    case Op::Sub: return "-";
    case Op::Mul: return "*";
    case Op::Div: return "/";
    case Op::Lt: return "<";
    case Op::Le: return "<=";
    case Op::Gt: return ">";
    case Op::Ge: return ">=";
    case Op::And: return "&&";
    case Op::Or: return "||";
    default: return nullptr;
  }
}

const char* builtin(Op op) {
  switch (op) {
    case Op::Min: return "min";
    case Op::Max: return "max";
    case Op::Clamp: return "clamp";
    case Op::Sqrt: return "sqrt";
    case Op::Exp: return "exp";
    case Op::Pow: return "pow";
    case Op::Acos: return "acos";
    case Op::Abs: return "abs";
    case Op::Step: return "step";
    case Op::Sin: return "sin";
    case Op::Cos: return "cos";
    case Op::Floor: return "floor";
    default: return nullptr;
  }
}

}  // namespace

std::string comment_lines(const std::string& text, const std::string& indent, const std::string& marker) {
  std::string out;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) out += indent + marker + (line.empty() ? "" : " ") + line + "\n";
  return out;
}

std::string CPrinter::literal(double v) const {
  if (v == kPi) return d_.pi_name;
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";  // "2" → "2.0" (ESSL has no implicit int → float)
  return s;
}

std::string CPrinter::color_literal(const std::array<double, 3>& c) const {
  if (c[0] == c[1] && c[1] == c[2]) return d_.color_ctor + "(" + literal(c[0]) + ")";
  return fmt::format("{}({}, {}, {})", d_.color_ctor, literal(c[0]), literal(c[1]), literal(c[2]));
}

std::string CPrinter::as(const NodePtr& n, Type wanted) const {
  if (wanted == Type::Color && n->type == Type::Float) {
    if (n->op == Op::Literal) return d_.color_ctor + "(" + literal(n->value[0]) + ")";
    return d_.color_ctor + "(" + expr(n, 0) + ")";
  }
  return expr(n, 0);
}

std::string CPrinter::expr(const NodePtr& n) const { return expr(n, 0); }

std::string CPrinter::call_args(const NodePtr& n) const {
  std::string s;
  for (size_t i = 0; i < n->args.size(); ++i) {
    if (i) s += ", ";
    s += as(n->args[i], n->callee->params[i].type);
  }
  if (d_.constants_as_params) {
    for (const auto& c : free_constants(n->callee)) s += (s.empty() ? "" : ", ") + c->name;
  }
  return s;
}

std::string CPrinter::expr(const NodePtr& n, int context) const {
  int p = precedence(*n);
  std::string s;
  switch (n->op) {
    case Op::Literal:
      s = n->type == Type::Color ? color_literal(n->value) : literal(n->value[0]);
      break;
    case Op::Constant:
    case Op::Arg:
    case Op::Local:
      s = n->name;
      break;
    case Op::Neg:
      s = "-" + expr(n->args[0], p + 1);
      break;
    case Op::Add: case Op::Sub: case Op::Mul: case Op::Div:
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::And: case Op::Or:
      // Left-associative; the right operand keeps its parentheses at equal
      // precedence so the target evaluates in the IR's order.
      s = expr(n->args[0], p) + " " + binary_op(n->op) + " " + expr(n->args[1], p + 1);
      break;
    case Op::Atan2:
      s = d_.atan2_name + "(" + expr(n->args[0], 0) + ", " + expr(n->args[1], 0) + ")";
      break;
    case Op::Select:
      s = expr(n->args[0], 2) + " ? " + as(n->args[1], n->type) + " : " + as(n->args[2], n->type);
      break;
    case Op::Call:
      s = n->callee->name + "(" + call_args(n) + ")";
      break;
    default: {
      const char* name = builtin(n->op);
      if (!name) throw std::logic_error("facet: the C printer cannot print this operation");
      s = std::string(name) + "(";
      for (size_t i = 0; i < n->args.size(); ++i) {
        if (i) s += ", ";
        s += as(n->args[i], n->type);
      }
      s += ")";
    }
  }
  return p < context ? "(" + s + ")" : s;
}

std::vector<NodePtr> CPrinter::free_constants(const ir::FunctionPtr& f) const {
  if (auto it = free_cache_.find(f.get()); it != free_cache_.end()) return it->second;
  std::vector<NodePtr> out;
  std::set<std::string> seen;
  auto add = [&](const NodePtr& c) {
    if (seen.insert(c->name).second) out.push_back(c);
  };
  std::function<void(const NodePtr&)> walk = [&](const NodePtr& n) {
    if (n->op == Op::Constant) add(n);
    if (n->op == Op::Call)
      for (const auto& c : free_constants(n->callee)) add(c);
    for (const auto& a : n->args) walk(a);
  };
  for (const auto& l : f->lets) walk(l.value.node());
  walk(f->result.node());
  free_cache_[f.get()] = out;
  return out;
}

std::string CPrinter::function(const ir::FunctionPtr& f) const {
  std::string params;
  for (const auto& p : f->params) params += (params.empty() ? "" : ", ") + type(p.type) + " " + p.name;
  if (d_.constants_as_params)
    for (const auto& c : free_constants(f)) params += (params.empty() ? "" : ", ") + type(c->type) + " " + c->name;
  std::string s = fmt::format("{} {}({})\n{{\n", type(f->result_type()), f->name, params);
  s += comment_lines(f->citation, "    ");
  if (!f->doc.empty()) s += comment_lines(f->doc, "    ");
  for (const auto& l : f->lets) s += fmt::format("    {} {} = {};\n", type(l.value.type()), l.name, expr(l.value.node()));
  const NodePtr& r = f->result.node();
  if (r->op == Op::Select) {
    // A guard reads better as an early return.
    s += fmt::format("    if ({}) return {};\n", expr(r->args[0]), as(r->args[1], r->type));
    s += fmt::format("    return {};\n", as(r->args[2], r->type));
  } else {
    s += fmt::format("    return {};\n", as(r, f->result_type()));
  }
  s += "}\n";
  return s;
}

}  // namespace facet::targets
