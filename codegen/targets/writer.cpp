#include "targets/writer.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <stdexcept>

#include <fmt/compile.h>
#include <fmt/format.h>

namespace facet::targets {

using ir::Node;
using ir::NodePtr;
using ir::Op;

int precedence(const Node& n) {
  switch (n.op) {
    case Op::Select: return kSelectPrecedence;
    case Op::Or: return kOrPrecedence;
    case Op::And: return kAndPrecedence;
    case Op::Lt: case Op::Le: case Op::Gt: case Op::Ge: return kComparePrecedence;
    case Op::Add: case Op::Sub: return kSumPrecedence;
    case Op::Mul: case Op::Div: return kProductPrecedence;
    case Op::Neg: return kUnaryPrecedence;
    case Op::Literal: return n.type == ir::Type::Float && n.value[0] < 0 ? kUnaryPrecedence : kAtomPrecedence;
    default: return kAtomPrecedence;
  }
}

const char* infix_operator(Op op) {
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

const char* builtin_name(Op op) {
  switch (op) {
    case Op::Min: return "min";
    case Op::Max: return "max";
    case Op::Clamp: return "clamp";
    case Op::Sqrt: return "sqrt";
    case Op::Exp: return "exp";
    case Op::Pow: return "pow";
    case Op::Acos: return "acos";
    case Op::Atan2: return "atan2";
    case Op::Abs: return "abs";
    case Op::Step: return "step";
    case Op::Sin: return "sin";
    case Op::Cos: return "cos";
    case Op::Floor: return "floor";
    default: return nullptr;
  }
}

// Every printer appends to one string: generate() prints thousands of small
// pieces, and building each as its own std::string cost most of its time.
void number_to(std::string& out, double v) { fmt::format_to(std::back_inserter(out), FMT_COMPILE("{}"), v); }

std::string number(double v) {
  std::string s;
  number_to(s, v);
  return s;
}

void ExprWriter::expr_to(std::string& out, const NodePtr& np, int context) const {
  const Node& n = *np;
  const bool own = spells(n);
  const int p = own ? kAtomPrecedence : precedence(n);
  const bool parens = p < context;
  if (parens) out += '(';
  if (own) {
    spell_to(out, np);
  } else if (n.op == Op::Literal || n.op == Op::Constant || n.op == Op::Arg || n.op == Op::Local) {
    leaf_to(out, n);
  } else if (n.op == Op::Neg) {
    out += '-';
    expr_to(out, n.args[0], p + 1);
  } else if (n.op == Op::Select) {
    expr_to(out, n.args[0], kOrPrecedence);
    out += " ? ";
    operand_to(out, n, 1);
    out += " : ";
    operand_to(out, n, 2);
  } else if (const char* op = infix(n.op)) {
    const bool space = spaced(n.op);
    expr_to(out, n.args[0], p);
    if (space) out += ' ';
    out += op;
    if (space) out += ' ';
    expr_to(out, n.args[1], p + 1);
  } else {
    const char* name = n.op == Op::Call ? nullptr : builtin(n.op);
    if (name) out += name;
    else if (n.op == Op::Call) callee_to(out, n);
    else throw std::logic_error("facet: this target cannot print this operation");
    out += '(';
    for (size_t i = 0; i < n.args.size(); ++i) {
      if (i) out += ", ";
      operand_to(out, n, i);
    }
    if (n.op == Op::Call) extra_args_to(out, n);
    out += ')';
  }
  if (parens) out += ')';
}

// ---------------------------------------------------------------- layout

namespace {

struct Break {
  size_t pos;  // a space
  int depth;   // of brackets around it
  int rank;    // what it separates, loosest first: 0 items, 1 logic, 2 comparisons, 3 sums, 4 products
};

int rank_before(char op, char next) {
  if (op == '&' || op == '|') return 1;
  if (op == '<' || op == '>' || op == '=' || op == '?' || op == ':' || (op == '!' && next == '=')) return 2;
  if (op == '+' || op == '-') return 3;
  return 4;
}

bool operator_char(char c) { return c != 0 && std::strchr("+-*/&|<>=?:", c) != nullptr; }

// Where `t` may break: spaces after a comma or "{", before "}" or an infix
// operator (" + ", " <= "), outside strings and comments.
std::vector<Break> break_points(std::string_view t) {
  std::vector<Break> out;
  int depth = 0;
  bool in_string = false;
  auto at = [&](size_t i) { return i < t.size() ? t[i] : '\0'; };
  for (size_t i = 0; i < t.size(); ++i) {
    char c = t[i];
    if (in_string) {
      in_string = c != '"';
      continue;
    }
    if (c == '"') in_string = true;
    else if (c == '/' && at(i + 1) == '/') break;
    else if (c == '(' || c == '[' || c == '{') ++depth;
    else if (c == ')' || c == ']' || c == '}') --depth;
    else if (c == ' ' && i > 0 && t[i - 1] != ' ') {
      char prev = t[i - 1], next = at(i + 1);
      bool before_operator =
          operator_char(next) && (at(i + 2) == ' ' || (operator_char(at(i + 2)) && at(i + 3) == ' '));
      if (prev == ',' || prev == '{' || next == '}') out.push_back({i, depth, 0});
      else if (before_operator) out.push_back({i, depth, rank_before(next, at(i + 2))});
    }
  }
  return out;
}

void line_to(std::string& out, std::string_view text, size_t indent) {
  out.append(indent, ' ');
  out += text;
  out += '\n';
}

}  // namespace

void wrap_to(std::string& out, std::string_view text, size_t indent, size_t width) {
  if (width == 0 || indent + text.size() <= width) return line_to(out, text, indent);
  const std::vector<Break> breaks = break_points(text);
  // Line by line: of the break points that fit, the outermost loosest one in the
  // line's second half (the last of equals), else in the whole line, else the first.
  auto looser = [](const Break& a, const Break* b) {
    return !b || a.depth < b->depth || (a.depth == b->depth && a.rank <= b->rank);
  };
  size_t start = 0, at = indent;
  while (at + (text.size() - start) > width) {
    const size_t room = width > at ? width - at : 0;
    const Break *late = nullptr, *any = nullptr, *first = nullptr;
    for (const Break& b : breaks) {
      if (b.pos <= start) continue;
      if (!first) first = &b;
      if (b.pos - start > room) break;
      if (looser(b, any)) any = &b;
      if (b.pos - start >= room / 2 && looser(b, late)) late = &b;
    }
    const Break* chosen = late ? late : any ? any : first;
    if (!chosen) break;
    line_to(out, text.substr(start, chosen->pos - start), at);
    start = chosen->pos + 1;
    at = indent + 4;
  }
  line_to(out, text.substr(start), at);
}

void comment_to(std::string& out, std::string_view text, std::string_view indent, std::string_view marker,
                size_t width) {
  // One comment line. A backslash must not end it: in GLSL, HLSL and OSL (C preprocessors) it
  // would splice the next line, code included, into the comment.
  auto line_to = [&](std::string_view line) {
    out.append(indent).append(marker);
    if (!line.empty()) out.append(" ").append(line);
    if (!line.empty() && line.back() == '\\') out += "·";  // "\·": a name's backslash at the end
    out += '\n';
  };
  // A space to break at: not after a backslash where another will do.
  auto fits = [](std::string_view line, size_t cut) { return cut != 0 && line[cut - 1] != '\\'; };
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(start, end - start);
    const size_t lead = indent.size() + marker.size() + 1;
    // Word-wrapped where a width is asked for and a word boundary allows.
    while (width != 0 && lead + line.size() > width) {
      size_t cut = line.rfind(' ', width - lead);
      while (cut != std::string_view::npos && cut != 0 && !fits(line, cut)) cut = line.rfind(' ', cut - 1);
      if (cut == std::string_view::npos || cut == 0) {
        cut = line.find(' ', width - lead);
        while (cut != std::string_view::npos && !fits(line, cut)) cut = line.find(' ', cut + 1);
      }
      if (cut == std::string_view::npos) break;
      line_to(line.substr(0, cut));
      line.remove_prefix(cut + 1);
    }
    line_to(line);
    start = end + 1;
  }
}

std::string indented(std::string_view text, size_t indent) {
  std::string out;
  out.reserve(text.size() + text.size() / 16);
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string_view::npos) end = text.size();
    if (end > start) out.append(indent, ' ').append(text.substr(start, end - start));
    if (end < text.size()) out += '\n';
    start = end + 1;
  }
  return out;
}

std::string fill(const std::vector<std::string>& items, size_t indent, size_t width) {
  std::string out, current;
  for (size_t i = 0; i < items.size(); ++i) {
    std::string item = items[i] + (i + 1 < items.size() ? "," : "");
    if (!current.empty() && (width == 0 || indent + current.size() + 1 + item.size() <= width)) {
      current.append(" ").append(item);
      continue;
    }
    if (!current.empty()) line_to(out, current, indent);
    current = std::move(item);
  }
  if (!current.empty()) line_to(out, current, indent);
  return out;
}

void CodeWriter::line(std::string_view text) { wrap_to(out_, text, indent(), width_); }

void CodeWriter::open(std::string_view text) {
  line(text);
  ++depth_;
}

void CodeWriter::close(std::string_view text) {
  if (depth_ > 0) --depth_;
  line(text);
}

void CodeWriter::comment(std::string_view text, std::string_view marker) {
  comment_to(out_, text, std::string(indent(), ' '), marker, width_);
}

void CodeWriter::text(std::string_view text) { out_ += indented(text, indent()); }

}  // namespace facet::targets
