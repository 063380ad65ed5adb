#include "targets/cfamily.h"

#include <functional>
#include <stdexcept>

#include <fmt/format.h>

#include "core/vec.h"

namespace facet::targets {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

std::string comment_lines(const std::string& text, const std::string& indent, const std::string& marker) {
  std::string out;
  out.reserve(text.size() + 16);
  comment_to(out, text, indent, marker);
  return out;
}

void CPrinter::literal_to(std::string& out, double v) const {
  if (v == kPi) {
    out += d_.pi_name;
    return;
  }
  size_t start = out.size();
  number_to(out, v);
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
  if (!d_.splat_ctor || c[0] != c[1] || c[1] != c[2]) {
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
  if (wanted == Type::Color && n->type == Type::Float && !d_.splat_ctor) {
    if (n->op == Op::Literal) {
      color_literal_to(out, {n->value[0], n->value[0], n->value[0]});
      return;
    }
    out += "(" + d_.color_type + ")(";
    expr_to(out, n, 0);
    out += ')';
    return;
  }
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

std::string CPrinter::expr(const NodePtr& n) const {
  std::string s;
  expr_to(s, n, 0);
  return s;
}

void CPrinter::leaf_to(std::string& out, const Node& n) const {
  if (n.op != Op::Literal) out += n.name;
  else if (n.type == Type::Color) color_literal_to(out, n.value);
  else literal_to(out, n.value[0]);
}

const char* CPrinter::builtin(Op op) const { return op == Op::Atan2 ? d_.atan2_name.c_str() : builtin_name(op); }

// A call's arguments take its parameters' types, a builtin's and a select's its own.
void CPrinter::operand_to(std::string& out, const Node& parent, size_t i) const {
  as_to(out, parent.args[i], parent.op == Op::Call ? parent.callee->params[i].type : parent.type);
}

void CPrinter::extra_args_to(std::string& out, const Node& call) const {
  if (!d_.constants_as_params) return;
  bool first = call.args.empty();
  for (const auto& c : free_constants(call.callee)) {
    if (!first) out += ", ";
    out += c->name;
    first = false;
  }
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
  s.reserve(256);
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
  s += ')';
  CodeWriter w(0, "    ");
  w.line(s);
  w.open("{");
  w.comment(f->citation);
  if (!f->doc.empty()) w.comment(f->doc);
  for (const auto& l : f->lets) {
    s.clear();
    declare(l.value.type(), l.name);
    s += " = ";
    expr_to(s, l.value.node(), 0);
    s += ';';
    w.line(s);
  }
  const NodePtr& r = f->result.node();
  s.clear();
  if (r->op == Op::Select) {
    // A guard reads better as an early return.
    s += "if (";
    expr_to(s, r->args[0], 0);
    s += ") return ";
    as_to(s, r->args[1], r->type);
    s += ';';
    w.line(s);
    s = "return ";
    as_to(s, r->args[2], r->type);
  } else {
    s += "return ";
    as_to(s, r, f->result_type());
  }
  s += ';';
  w.line(s);
  w.close("}");
  return w.take();
}

std::string material_constants(const MaterialProgram& p, const CPrinter& printer, const std::string& qualifier) {
  const Material& m = p.material;
  const std::string color = printer.type(ir::Type::Color);
  std::string constants;
  auto add_constant = [&](const std::string& type, const std::string& name, const std::string& value) {
    constants += fmt::format("{} {} {} = {};\n", qualifier, type, name, value);
  };
  if (!m.ambient_texture) add_constant(color, kAmbientInput, printer.color_literal(m.ambient));
  if (!m.emission_texture) add_constant(color, kEmissionInput, printer.color_literal(m.emission));
  add_constant(color, "tangent_axis", printer.color_literal(normalize(Vec3(m.tangent_axis)).array()));
  for (const auto& c : p.constants()) {
    add_constant(printer.type(c->type), c->name,
                 c->type == ir::Type::Color ? printer.color_literal(c->value) : printer.literal(c->value[0]));
  }
  return constants;
}

}  // namespace facet::targets
