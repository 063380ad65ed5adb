#include "targets/cfamily.h"

#include <cmath>
#include <functional>
#include <sstream>
#include <stdexcept>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "core/vec.h"

namespace facet::targets {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

namespace {

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
  out.reserve(text.size() + 16);
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    out.append(indent).append(marker);
    if (end > start) out.append(" ").append(text, start, end - start);
    out += '\n';
    start = end + 1;
  }
  return out;
}

// Every printer appends to one string: generate() prints thousands of small
// pieces, and building each as its own std::string cost most of its time.

void CPrinter::literal_to(std::string& out, double v) const {
  if (v == kPi) {
    out += d_.pi_name;
    return;
  }
  size_t start = out.size();
  fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}"), v);
  // "2" → "2.0": ESSL has no implicit int → float.
  if (out.find_first_of(".eEn", start) == std::string::npos) out += ".0";
}

std::string CPrinter::literal(double v) const {
  std::string s;
  literal_to(s, v);
  return s;
}

void CPrinter::color_literal_to(std::string& out, const std::array<double, 3>& c) const {
  out += d_.color_ctor;
  out += '(';
  literal_to(out, c[0]);
  if (c[0] != c[1] || c[1] != c[2]) {
    out += ", ";
    literal_to(out, c[1]);
    out += ", ";
    literal_to(out, c[2]);
  }
  out += ')';
}

std::string CPrinter::color_literal(const std::array<double, 3>& c) const {
  std::string s;
  color_literal_to(s, c);
  return s;
}

void CPrinter::as_to(std::string& out, const NodePtr& n, Type wanted) const {
  if (wanted == Type::Color && n->type == Type::Float) {
    out += d_.color_ctor;
    out += '(';
    if (n->op == Op::Literal) literal_to(out, n->value[0]);
    else expr_to(out, n, 0);
    out += ')';
    return;
  }
  expr_to(out, n, 0);
}

std::string CPrinter::as(const NodePtr& n, Type wanted) const {
  std::string s;
  as_to(s, n, wanted);
  return s;
}

std::string CPrinter::expr(const NodePtr& n) const {
  std::string s;
  expr_to(s, n, 0);
  return s;
}

void CPrinter::call_args_to(std::string& out, const NodePtr& n) const {
  for (size_t i = 0; i < n->args.size(); ++i) {
    if (i) out += ", ";
    as_to(out, n->args[i], n->callee->params[i].type);
  }
  if (d_.constants_as_params) {
    bool first = n->args.empty();
    for (const auto& c : free_constants(n->callee)) {
      if (!first) out += ", ";
      out += c->name;
      first = false;
    }
  }
}

void CPrinter::expr_to(std::string& out, const NodePtr& n, int context) const {
  const int p = precedence(*n);
  const bool parens = p < context;
  if (parens) out += '(';
  switch (n->op) {
    case Op::Literal:
      if (n->type == Type::Color) color_literal_to(out, n->value);
      else literal_to(out, n->value[0]);
      break;
    case Op::Constant:
    case Op::Arg:
    case Op::Local:
      out += n->name;
      break;
    case Op::Neg:
      out += '-';
      expr_to(out, n->args[0], p + 1);
      break;
    case Op::Add: case Op::Sub: case Op::Mul: case Op::Div:
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::And: case Op::Or:
      // Left-associative; the right operand keeps its parentheses at equal
      // precedence so the target evaluates in the IR's order.
      expr_to(out, n->args[0], p);
      out += ' ';
      out += binary_op(n->op);
      out += ' ';
      expr_to(out, n->args[1], p + 1);
      break;
    case Op::Atan2:
      out += d_.atan2_name;
      out += '(';
      expr_to(out, n->args[0], 0);
      out += ", ";
      expr_to(out, n->args[1], 0);
      out += ')';
      break;
    case Op::Select:
      expr_to(out, n->args[0], 2);
      out += " ? ";
      as_to(out, n->args[1], n->type);
      out += " : ";
      as_to(out, n->args[2], n->type);
      break;
    case Op::Call:
      out += n->callee->name;
      out += '(';
      call_args_to(out, n);
      out += ')';
      break;
    default: {
      const char* name = builtin(n->op);
      if (!name) throw std::logic_error("facet: the C printer cannot print this operation");
      out += name;
      out += '(';
      for (size_t i = 0; i < n->args.size(); ++i) {
        if (i) out += ", ";
        as_to(out, n->args[i], n->type);
      }
      out += ')';
    }
  }
  if (parens) out += ')';
}

const std::vector<NodePtr>& CPrinter::free_constants(const ir::FunctionPtr& f) const {
  if (auto it = free_cache_.find(f.get()); it != free_cache_.end()) return it->second;
  std::vector<NodePtr> out;
  // A function reads a handful of constants: a linear search beats a set.
  auto add = [&](const NodePtr& c) {
    for (const auto& o : out)
      if (o->name == c->name) return;
    out.push_back(c);
  };
  std::function<void(const NodePtr&)> walk = [&](const NodePtr& n) {
    if (n->op == Op::Constant) add(n);
    if (n->op == Op::Call)
      for (const auto& c : free_constants(n->callee)) add(c);
    for (const auto& a : n->args) walk(a);
  };
  for (const auto& l : f->lets) walk(l.value.node());
  walk(f->result.node());
  return free_cache_[f.get()] = std::move(out);
}

std::string CPrinter::function(const ir::FunctionPtr& f) const {
  std::string s;
  s.reserve(1024);
  auto declare = [&](Type t, const std::string& name) {
    s += type(t);
    s += ' ';
    s += name;
  };
  declare(f->result_type(), f->name);
  s += '(';
  bool first = true;
  for (const auto& p : f->params) {
    if (!first) s += ", ";
    declare(p.type, p.name);
    first = false;
  }
  if (d_.constants_as_params)
    for (const auto& c : free_constants(f)) {
      if (!first) s += ", ";
      declare(c->type, c->name);
      first = false;
    }
  s += ")\n{\n";
  s += comment_lines(f->citation, "    ");
  if (!f->doc.empty()) s += comment_lines(f->doc, "    ");
  for (const auto& l : f->lets) {
    s += "    ";
    declare(l.value.type(), l.name);
    s += " = ";
    expr_to(s, l.value.node(), 0);
    s += ";\n";
  }
  const NodePtr& r = f->result.node();
  if (r->op == Op::Select) {
    // A guard reads better as an early return.
    s += "    if (";
    expr_to(s, r->args[0], 0);
    s += ") return ";
    as_to(s, r->args[1], r->type);
    s += ";\n    return ";
    as_to(s, r->args[2], r->type);
  } else {
    s += "    return ";
    as_to(s, r, f->result_type());
  }
  s += ";\n}\n";
  return s;
}

}  // namespace facet::targets
