// facet — what every printer shares (GLSL, OSL and POV-Ray): one operator
// precedence table and the parenthesisation it implies, number formatting,
// indentation and line wrapping.
//
// A dialect derives from ExprWriter and prints the leaves (literals, names) and
// the operations it spells its own way (POV-Ray's select(), a call's name); the
// walk, the precedence and the parentheses are the same for every target.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "core/ir.h"

namespace facet::targets {

// ---- Precedence: one table for every target, higher binds tighter.
enum Precedence : int {
  kSelectPrecedence = 1,   // c ? a : b
  kOrPrecedence = 2,       // ||
  kAndPrecedence = 3,      // &&
  kComparePrecedence = 4,  // < <= > >=
  kSumPrecedence = 5,      // + -
  kProductPrecedence = 6,  // * /
  kUnaryPrecedence = 7,    // -x, and a negative number
  kAtomPrecedence = 9,     // names, numbers, calls, anything in parentheses
};

// The precedence of `n` in the shared forms: infix operators, prefix minus, the
// ternary select, and calls (atoms). A negative number literal binds as a minus.
int precedence(const ir::Node& n);
// The C spelling of a binary operator ("+", "<=", "&&"); null for other operations.
const char* infix_operator(ir::Op op);
// The builtin function every target spells the same ("min", "sqrt"); null for others.
const char* builtin_name(ir::Op op);

// ---- Numbers

// The shortest decimal text that reads back as exactly `v` ("0.1", "1e-05", "-0", "2").
void number_to(std::string& out, double v);
std::string number(double v);

// ---- Expressions

class ExprWriter {
 public:
  virtual ~ExprWriter() = default;
  // `n` where the surrounding operator binds with precedence `context`: in
  // parentheses where `n` binds less tightly. A binary operator's left operand
  // takes its own precedence as context and the right one its precedence + 1, so
  // the target evaluates in the IR's order (left-associative).
  void expr_to(std::string& out, const ir::NodePtr& n, int context = 0) const;

 protected:
  // Literal, Constant, Arg, Local.
  virtual void leaf_to(std::string& out, const ir::Node& n) const = 0;
  // True for operations the dialect prints itself (spell_to), as an atom.
  virtual bool spells(const ir::Node&) const { return false; }
  virtual void spell_to(std::string&, const ir::NodePtr&) const {}
  virtual const char* infix(ir::Op op) const { return infix_operator(op); }
  // Whether the infix operator `op` stands between spaces (lines break only at spaced ones).
  virtual bool spaced(ir::Op) const { return true; }
  virtual const char* builtin(ir::Op op) const { return builtin_name(op); }
  // A call's function name, and arguments after the callee's parameters.
  virtual void callee_to(std::string& out, const ir::Node& call) const { out += call.callee->name; }
  virtual void extra_args_to(std::string&, const ir::Node&) const {}
  // Operand i of a builtin, a call or a select's branch (C promotes float → colour here).
  virtual void operand_to(std::string& out, const ir::Node& parent, size_t i) const { expr_to(out, parent.args[i], 0); }
};

// ---- Layout

// `text` as lines of at most `width` columns (0: no limit), the first with
// `indent` spaces before it, continuation lines 4 deeper, each ending in '\n'.
// Lines break at spaces after a comma or "{", before "}" or an infix operator;
// of those that fit, at the outermost and loosest (items, then logic,
// comparisons, sums, products) in the line's second half. Strings and comments
// are never broken; text without a break point stays on one line.
void wrap_to(std::string& out, std::string_view text, size_t indent, size_t width);

// "// text" lines, one per line of `text` (and, with a width, word-wrapped to it),
// each with `indent` before it. No line ends in a backslash (a C preprocessor would splice
// the next line into the comment): lines break elsewhere, and one that ends in a name's
// backslash gets a "·" after it.
void comment_to(std::string& out, std::string_view text, std::string_view indent, std::string_view marker = "//",
                size_t width = 0);

// Every line of `text` with `indent` spaces before it (empty lines stay empty).
std::string indented(std::string_view text, size_t indent);

// `items` separated by ", " and filled into lines of at most `width` columns,
// each with `indent` spaces before it and ending in '\n' (a comma ends every line but the last).
std::string fill(const std::vector<std::string>& items, size_t indent, size_t width);

// Code as lines: statements at the current indentation, blocks, comments.
class CodeWriter {
 public:
  // width: the longest line (0: no limit); unit: one level of indentation.
  explicit CodeWriter(size_t width = 0, std::string unit = "  ") : width_(width), unit_(std::move(unit)) {}
  void line(std::string_view text);     // one statement, wrapped to the width
  void open(std::string_view text);     // a line, then one level deeper ("texture {")
  void close(std::string_view text);    // one level up, then a line ("}")
  void comment(std::string_view text, std::string_view marker = "//");
  void text(std::string_view text);     // lines as they are, each at the current indentation
  void raw(std::string_view text) { out_ += text; }
  void blank() { out_ += '\n'; }
  size_t width() const { return width_; }
  size_t indent() const { return depth_ * unit_.size(); }
  const std::string& str() const { return out_; }
  std::string take() { return std::move(out_); }

 private:
  size_t width_;
  std::string unit_;
  size_t depth_ = 0;
  std::string out_;
};

}  // namespace facet::targets
