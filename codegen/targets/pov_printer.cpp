#include "targets/pov_printer.h"

#include <cctype>
#include <cmath>
#include <functional>
#include <stdexcept>

#include <fmt/format.h>

namespace facet::targets {

using ir::Node;
using ir::NodePtr;
using ir::Op;
using ir::Type;

namespace {

const char* kChannel[3] = {"R", "G", "B"};

bool grey(const std::array<double, 3>& c) { return c[0] == c[1] && c[1] == c[2]; }

NodePtr literal(double v) {
  auto n = std::make_shared<Node>();
  n->op = Op::Literal;
  n->value = {v, v, v};
  return n;
}

NodePtr node(Op op, std::vector<NodePtr> args) {
  auto n = std::make_shared<Node>();
  n->op = op;
  n->args = std::move(args);
  return n;
}

bool is(const NodePtr& n, double v) { return n->op == Op::Literal && n->value[0] == v; }
bool negative_number(const NodePtr& n) { return n->op == Op::Literal && n->value[0] < 0; }

// -y as y, where `n` is -y: a negative number, a minus, or a negative number times y.
NodePtr negated(const NodePtr& n) {
  if (negative_number(n)) return literal(-n->value[0]);
  if (n->op == Op::Neg) return n->args[0];
  if (n->op == Op::Mul && negative_number(n->args[0]))
    return node(Op::Mul, {literal(-n->args[0]->value[0]), n->args[1]});
  return nullptr;
}

// One rewrite of fold()'s list at the root of `n` (operands folded), or null.
NodePtr rewrite(const NodePtr& n, const std::set<std::string>& finite) {
  auto known_finite = [&](const NodePtr& x) {
    return (x->op == Op::Literal && std::isfinite(x->value[0])) || (x->op == Op::Arg && finite.count(x->name));
  };
  const NodePtr& a = n->args.empty() ? n : n->args[0];
  const NodePtr& b = n->args.size() < 2 ? n : n->args[1];
  switch (n->op) {
    case Op::Neg:
      if (a->op == Op::Literal) return literal(-a->value[0]);
      if (a->op == Op::Neg) return a->args[0];
      return nullptr;
    case Op::Mul:
      if (is(b, 1)) return a;
      if (is(a, 1)) return b;
      if (is(b, -1)) return node(Op::Neg, {a});
      if (is(a, -1)) return node(Op::Neg, {b});
      if ((is(a, 0) && known_finite(b)) || (is(b, 0) && known_finite(a))) return literal(0);
      if (a->op == Op::Neg && b->op == Op::Neg) return node(Op::Mul, {a->args[0], b->args[0]});
      return nullptr;
    case Op::Div: return is(b, 1) ? a : nullptr;
    case Op::Add:
      if (is(b, 0)) return a;
      if (is(a, 0)) return b;
      if (NodePtr y = negated(b)) return node(Op::Sub, {a, y});
      return nullptr;
    case Op::Sub:
      if (is(b, 0)) return a;
      if (is(a, 0)) return node(Op::Neg, {b});
      if (NodePtr y = negated(b)) return node(Op::Add, {a, y});
      return nullptr;
    default: return nullptr;
  }
}

// `n` (its operands folded) rewritten at its root until no rewrite applies. A
// rewrite builds new nodes only from folded operands, and those need none.
NodePtr simplified(NodePtr n, const std::set<std::string>& finite) {
  while (NodePtr r = rewrite(n, finite)) n = r;
  return n;
}

}  // namespace

std::string capital(const std::string& s) {
  std::string r = s;
  if (!r.empty()) r[0] = char(std::toupper(static_cast<unsigned char>(r[0])));
  return r;
}

std::string pov_number(double v) {
  if (v == kPi) return "pi";
  if (v == 0) return "0";  // not "-0"
  return number(v);
}

std::string pov_vector(const Vec3& v) {
  return fmt::format("<{}, {}, {}>", pov_number(v.x), pov_number(v.y), pov_number(v.z));
}

std::string pov_rgb(const std::array<double, 3>& c) {
  return fmt::format("<{}, {}, {}>", pov_number(c[0]), pov_number(c[1]), pov_number(c[2]));
}

bool is_scaffold(const ir::Function& f) { return f.name.rfind("Facet_", 0) == 0; }

ir::Expr var(const std::string& name) {
  auto n = std::make_shared<Node>();
  n->op = Op::Arg;
  n->name = name;
  return ir::Expr(NodePtr(n));
}

namespace {
const char* const kDeclaredDoc = "(declared in the scene's SDL)";
}

bool is_declared(const ir::Function& f) { return f.doc == kDeclaredDoc; }

ir::FunctionPtr declared(const std::string& name, size_t params) {
  auto f = std::make_shared<ir::Function>();
  f->name = name;
  f->doc = kDeclaredDoc;
  for (size_t i = 0; i < params; ++i) f->params.push_back({"p" + std::to_string(i), Type::Float});
  return f;
}

const std::set<std::string>& pov_finite_variables() {
  static const std::set<std::string> names = {"x", "y", "z", "Nx", "Ny", "Nz", "Lx", "Ly", "Lz"};
  return names;
}

NodePtr fold(const NodePtr& n, int ch, const std::set<std::string>& finite) {
  if (n->op == Op::Literal) return n->type == Type::Float ? n : literal(n->value[size_t(ch)]);
  if (n->args.empty()) return n;
  std::vector<NodePtr> args;
  bool changed = false;
  for (const auto& a : n->args) {
    args.push_back(fold(a, ch, finite));
    changed |= args.back() != a;
  }
  NodePtr out = n;
  if (changed) {
    auto copy = std::make_shared<Node>(*n);
    copy->args = std::move(args);
    out = copy;
  }
  return simplified(out, finite);
}

// ---------------------------------------------------------------- PovPrinter

bool PovPrinter::channel_dependent(const ir::FunctionPtr& f) const {
  if (auto it = dependent_.find(f.get()); it != dependent_.end()) return it->second.second;
  bool dep = false;
  std::function<void(const NodePtr&)> walk = [&](const NodePtr& n) {
    if ((n->op == Op::Constant || n->op == Op::Literal) && n->type == Type::Color && !grey(n->value)) dep = true;
    if (n->op == Op::Call && channel_dependent(n->callee)) dep = true;
    for (const auto& a : n->args) walk(a);
  };
  for (const auto& l : f->lets) walk(l.value.node());
  walk(f->result.node());
  dependent_[f.get()] = {f, dep};
  return dep;
}

std::string PovPrinter::name(const ir::FunctionPtr& f, int channel) const {
  std::string n = own_.count(f.get()) ? prefix_ + capital(f->name) : capital(f->name);
  return channel_dependent(f) ? n + "_" + kChannel[channel] : n;
}

std::string PovPrinter::constant_name(const Node& c, int channel) const {
  std::string n = prefix_ + capital(c.name);
  return c.type == Type::Color && !grey(c.value) ? n + "_" + kChannel[channel] : n;
}

std::string PovPrinter::constants(const std::vector<NodePtr>& cs) const {
  std::string s;
  for (const auto& c : cs) {
    int channels = c->type == Type::Color && !grey(c->value) ? 3 : 1;
    for (int ch = 0; ch < channels; ++ch)
      s += fmt::format("#declare {} = {};\n", constant_name(*c, ch), pov_number(c->value[size_t(ch)]));
  }
  return s;
}

namespace {
// A parameter's or let's name: x, y and z as POV-Ray's own, others capitalised.
std::string local(const std::string& n) { return n == "x" || n == "y" || n == "z" ? n : capital(n); }
}  // namespace

std::string PovPrinter::expr(const NodePtr& n, int ch, const std::set<std::string>& finite) const {
  ch_ = ch;
  finite_ = &finite;
  std::string s;
  expr_to(s, fold(n, ch, finite), 0);
  return s;
}

void PovPrinter::leaf_to(std::string& out, const Node& n) const {
  if (n.op == Op::Literal) out += pov_number(n.value[size_t(ch_)]);
  else if (n.op == Op::Constant) out += constant_name(n, ch_);
  else out += local(n.name);
}

bool PovPrinter::spells(const Node& n) const {
  switch (n.op) {
    case Op::Select: case Op::Step: case Op::Clamp:
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: case Op::And: case Op::Or: return true;
    default: return false;
  }
}

// A condition as a number, 1 where it holds: POV-Ray's comparisons and & | return 0 or 1.
void PovPrinter::condition_to(std::string& out, const NodePtr& n) const {
  out += '(';
  if (n->op == Op::And || n->op == Op::Or) {
    condition_to(out, n->args[0]);
    out += n->op == Op::And ? " & " : " | ";
    condition_to(out, n->args[1]);
  } else {
    expr_to(out, n->args[0], 0);
    out.append(" ").append(infix(n->op)).append(" ");
    expr_to(out, n->args[1], 0);
  }
  out += ')';
}

void PovPrinter::spell_to(std::string& out, const NodePtr& n) const {
  auto print = [&](const NodePtr& x) {
    std::string s;
    expr_to(s, x, 0);
    return s;
  };
  switch (n->op) {
    case Op::Step: {  // step(edge, x) = x >= edge
      out += '(' + print(n->args[1]) + " >= " + print(n->args[0]) + ')';
      return;
    }
    case Op::Clamp:
      out += "min(max(" + print(n->args[0]) + ", " + print(n->args[1]) + "), " + print(n->args[2]) + ")";
      return;
    case Op::Select: break;
    default: condition_to(out, n); return;
  }
  // select(A, B, C[, D]): A < 0 → B; A = 0 → C; A > 0 → D (or C).
  const NodePtr& c = n->args[0];
  std::string t = print(n->args[1]), f = print(n->args[2]);
  const bool compound = c->op == Op::And || c->op == Op::Or;
  std::string x = compound ? "" : print(simplified(node(Op::Sub, {c->args[0], c->args[1]}), *finite_));
  switch (c->op) {
    case Op::Lt: out += fmt::format("select({}, {}, {})", x, t, f); break;
    case Op::Le: out += fmt::format("select({}, {}, {}, {})", x, t, t, f); break;
    case Op::Gt: out += fmt::format("select({}, {}, {}, {})", x, f, f, t); break;
    case Op::Ge: out += fmt::format("select({}, {}, {})", x, f, t); break;
    default: {
      std::string cond;
      condition_to(cond, c);
      out += fmt::format("select({} - 0.5, {}, {})", cond, f, t);
    }
  }
}

void PovPrinter::callee_to(std::string& out, const Node& call) const { out += name(call.callee, ch_); }

namespace {

// The names each let reads.
void locals_read(const NodePtr& n, std::set<std::string>& out) {
  if (n->op == Op::Local) out.insert(n->name);
  for (const auto& a : n->args) locals_read(a, out);
}

// The lets in levels: each level's lets read only lets of the levels before it,
// so each helper of the chain takes a level's lets at once. Returns where each level ends.
std::vector<size_t> let_levels(const ir::Function& f) {
  std::vector<size_t> ends;
  std::set<std::string> current;
  for (size_t i = 0; i < f.lets.size(); ++i) {
    std::set<std::string> reads;
    locals_read(f.lets[i].value.node(), reads);
    bool depends = false;
    for (const auto& r : reads) depends |= current.count(r) > 0;
    if (depends) {
      ends.push_back(i);
      current.clear();
    }
    current.insert(f.lets[i].name);
  }
  if (!f.lets.empty()) ends.push_back(f.lets.size());
  return ends;
}

}  // namespace

void declare_function_to(std::string& out, const std::string& name, const std::string& params,
                         const std::string& body) {
  std::string head = "#declare " + name + " = function(" + params + ") {";
  if (head.size() + body.size() + 3 <= kPovWidth) {
    out.append(head).append(" ").append(body).append(" }\n");
    return;
  }
  wrap_to(out, head, 0, kPovWidth);
  wrap_to(out, body, 2, kPovWidth);
  out += "}\n";
}

namespace {

// The names `n` reads.
void reads(const NodePtr& n, std::set<std::string>& out) {
  if (n->op == Op::Arg || n->op == Op::Local) out.insert(n->name);
  for (const auto& a : n->args) reads(a, out);
}

// What each step of the chain takes, as indices into params then lets: step 0
// is the function (every parameter), step k > 0 the parameters and lets that
// it or a later step reads. A let nothing reads is not computed.
std::vector<std::vector<size_t>> chain_signatures(const ir::Function& f, const std::vector<size_t>& ends) {
  const size_t P = f.params.size();
  std::map<std::string, size_t> index;
  for (size_t i = 0; i < P; ++i) index[f.params[i].name] = i;
  for (size_t i = 0; i < f.lets.size(); ++i) index[f.lets[i].name] = P + i;
  auto add_reads = [&](const NodePtr& n, std::set<size_t>& out) {
    std::set<std::string> names;
    reads(n, names);
    for (const auto& name : names) out.insert(index.at(name));
  };
  std::vector<std::vector<size_t>> sig(ends.size() + 1);
  std::set<size_t> need;
  add_reads(f.result.node(), need);
  for (size_t k = ends.size(); k > 0; --k) {
    sig[k].assign(need.begin(), need.end());
    if (sig[k].empty() && P > 0) sig[k].push_back(0);  // POV-Ray functions take at least one parameter
    const size_t lo = P + (k >= 2 ? ends[k - 2] : 0), hi = P + ends[k - 1];
    std::set<size_t> before;
    for (size_t i : sig[k]) {
      if (i < lo || i >= hi) before.insert(i);
      else add_reads(f.lets[i - P].value.node(), before);
    }
    need = std::move(before);
  }
  for (size_t i = 0; i < P; ++i) sig[0].push_back(i);
  return sig;
}

}  // namespace

std::string PovPrinter::channel_function(const ir::FunctionPtr& f, int ch) const {
  const std::set<std::string> finite = is_scaffold(*f) ? pov_finite_variables() : std::set<std::string>{};
  const std::string base = name(f, ch);
  const std::vector<size_t> ends = let_levels(*f);
  const std::vector<std::vector<size_t>> sig = chain_signatures(*f, ends);
  const size_t P = f->params.size();
  auto name_of = [&](size_t i) { return local(i < P ? f->params[i].name : f->lets[i - P].name); };
  auto first_let = [&](size_t level) { return P + (level >= 2 ? ends[level - 2] : 0); };
  // The steps: the function, then each level with a let that is read.
  std::vector<size_t> steps = {0};
  for (size_t k = 1; k <= ends.size(); ++k)
    for (size_t i : sig[k])
      if (i >= first_let(k) && i < P + ends[k - 1]) {
        steps.push_back(k);
        break;
      }
  auto step_name = [&](size_t j) { return j == 0 ? base : fmt::format("{}__{}", base, j); };
  std::string out;
  if (!f->citation.empty()) comment_to(out, f->citation, "", "//", kPovWidth);
  if (!f->doc.empty()) comment_to(out, f->doc, "", "//", kPovWidth);
  // Declared deepest first: POV-Ray functions are declared before they are called.
  for (size_t j = steps.size(); j-- > 0;) {
    std::string params, body;
    for (size_t i : sig[steps[j]]) params.append(params.empty() ? "" : ", ").append(name_of(i));
    if (j + 1 == steps.size()) {
      body = expr(f->result.node(), ch, finite);
    } else {
      const size_t next = steps[j + 1];
      body = step_name(j + 1) + "(";
      for (size_t a = 0; a < sig[next].size(); ++a) {
        const size_t i = sig[next][a];
        body.append(a ? ", " : "").append(i >= first_let(next) ? expr(f->lets[i - P].value.node(), ch, finite) : name_of(i));
      }
      body += ")";
    }
    declare_function_to(out, step_name(j), params, body);
  }
  return out;
}

std::string PovPrinter::function(const ir::FunctionPtr& f) const {
  std::string out;
  for (int ch = 0; ch < (channel_dependent(f) ? 3 : 1); ++ch) out += channel_function(f, ch);
  return out;
}

}  // namespace facet::targets
