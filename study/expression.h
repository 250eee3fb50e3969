// Expressions of time for analytic references (`evas study --reference-expr
// 'CHANNEL=EXPR'`): numbers (1e-3), t (the time [s]), pi, e, + - * / ^
// (right-associative power), unary minus, parentheses and the functions
// sin cos tan exp log sqrt abs sinh cosh tanh atan. Parsed once, evaluated
// at every output time.
#pragma once

#include <memory>
#include <string>

namespace evas::study {

class Expression {
 public:
  /// Parses `text`; throws InputError "<what>: <text>: <problem> at column N".
  Expression(const std::string& text, const std::string& what);
  ~Expression();
  Expression(Expression&&) noexcept;
  Expression& operator=(Expression&&) noexcept;
  double operator()(double t) const;
  const std::string& text() const { return text_; }

  struct Node;

 private:
  std::string text_;
  std::unique_ptr<Node> root_;
};

}  // namespace evas::study
