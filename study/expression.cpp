// A recursive-descent parser and evaluator of expressions of t (expression.h).
#include "study/expression.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>

#include "model/types.h"

namespace evas::study {

struct Expression::Node {
  char op = 0;         // '#' number, 't' time, '+', '-', '*', '/', '^', 'n' negate, 'f' function
  double value = 0.0;  // '#'
  double (*fn)(double) = nullptr;  // 'f'
  std::unique_ptr<Node> a, b;
};

namespace {

using Node = Expression::Node;

const std::map<std::string, double (*)(double)>& functions() {
  static const std::map<std::string, double (*)(double)> f = {{"sin", [](double x) { return std::sin(x); }},
                                                              {"cos", [](double x) { return std::cos(x); }},
                                                              {"tan", [](double x) { return std::tan(x); }},
                                                              {"exp", [](double x) { return std::exp(x); }},
                                                              {"log", [](double x) { return std::log(x); }},
                                                              {"sqrt", [](double x) { return std::sqrt(x); }},
                                                              {"abs", [](double x) { return std::abs(x); }},
                                                              {"sinh", [](double x) { return std::sinh(x); }},
                                                              {"cosh", [](double x) { return std::cosh(x); }},
                                                              {"tanh", [](double x) { return std::tanh(x); }},
                                                              {"atan", [](double x) { return std::atan(x); }}};
  return f;
}

class Parser {
 public:
  Parser(const std::string& text, const std::string& what) : s_(text), what_(what) {}

  std::unique_ptr<Node> parse() {
    auto n = sum();
    skip();
    if (i_ < s_.size()) fail("unexpected '" + std::string(1, s_[i_]) + "'");
    return n;
  }

 private:
  [[noreturn]] void fail(const std::string& why) const {
    throw InputError(what_ + ": '" + s_ + "': " + why + " at column " + std::to_string(i_ + 1) +
                     " (numbers, t, pi, e, + - * / ^, parentheses, sin cos tan exp log sqrt abs "
                     "sinh cosh tanh atan)");
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  static std::unique_ptr<Node> make(char op, std::unique_ptr<Node> a, std::unique_ptr<Node> b) {
    auto n = std::make_unique<Node>();
    n->op = op;
    n->a = std::move(a);
    n->b = std::move(b);
    return n;
  }
  std::unique_ptr<Node> sum() {
    auto n = product();
    for (;;) {
      skip();
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) {
        const char op = s_[i_++];
        n = make(op, std::move(n), product());
      } else {
        return n;
      }
    }
  }
  std::unique_ptr<Node> product() {
    auto n = unary();
    for (;;) {
      skip();
      if (i_ < s_.size() && (s_[i_] == '*' || s_[i_] == '/')) {
        const char op = s_[i_++];
        n = make(op, std::move(n), unary());
      } else {
        return n;
      }
    }
  }
  std::unique_ptr<Node> unary() {
    skip();
    if (i_ < s_.size() && s_[i_] == '-') {
      ++i_;
      return make('n', unary(), nullptr);
    }
    if (i_ < s_.size() && s_[i_] == '+') {
      ++i_;
      return unary();
    }
    return power();
  }
  std::unique_ptr<Node> power() {
    auto base = atom();
    skip();
    if (i_ < s_.size() && s_[i_] == '^') {
      ++i_;
      return make('^', std::move(base), unary());  // right-associative, binds below unary minus
    }
    return base;
  }
  std::unique_ptr<Node> atom() {
    skip();
    if (i_ >= s_.size()) fail("an operand is missing");
    const char c = s_[i_];
    if (c == '(') {
      ++i_;
      auto n = sum();
      skip();
      if (i_ >= s_.size() || s_[i_] != ')') fail("')' is missing");
      ++i_;
      return n;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const char* b = s_.c_str() + i_;
      char* end = nullptr;
      const double x = std::strtod(b, &end);
      if (end == b) fail("not a number");
      i_ += static_cast<std::size_t>(end - b);
      auto n = std::make_unique<Node>();
      n->op = '#';
      n->value = x;
      return n;
    }
    if (std::isalpha(static_cast<unsigned char>(c))) {
      const std::size_t start = i_;
      while (i_ < s_.size() && std::isalnum(static_cast<unsigned char>(s_[i_]))) ++i_;
      const std::string name = s_.substr(start, i_ - start);
      auto n = std::make_unique<Node>();
      if (name == "t") {
        n->op = 't';
        return n;
      }
      if (name == "pi" || name == "e") {
        n->op = '#';
        n->value = name == "pi" ? M_PI : M_E;
        return n;
      }
      const auto f = functions().find(name);
      if (f == functions().end()) {
        i_ = start;
        fail("unknown name '" + name + "'");
      }
      skip();
      if (i_ >= s_.size() || s_[i_] != '(') fail("'(' after " + name + " is missing");
      ++i_;
      n->op = 'f';
      n->fn = f->second;
      n->a = sum();
      skip();
      if (i_ >= s_.size() || s_[i_] != ')') fail("')' is missing");
      ++i_;
      return n;
    }
    fail("unexpected '" + std::string(1, c) + "'");
  }

  const std::string& s_;
  std::string what_;
  std::size_t i_ = 0;
};

double eval(const Node& n, double t) {
  switch (n.op) {
    case '#':
      return n.value;
    case 't':
      return t;
    case 'n':
      return -eval(*n.a, t);
    case 'f':
      return n.fn(eval(*n.a, t));
    case '+':
      return eval(*n.a, t) + eval(*n.b, t);
    case '-':
      return eval(*n.a, t) - eval(*n.b, t);
    case '*':
      return eval(*n.a, t) * eval(*n.b, t);
    case '/':
      return eval(*n.a, t) / eval(*n.b, t);
    case '^':
      return std::pow(eval(*n.a, t), eval(*n.b, t));
  }
  return 0.0;
}

}  // namespace

Expression::Expression(const std::string& text, const std::string& what)
    : text_(text), root_(Parser(text_, what).parse()) {}
Expression::~Expression() = default;
Expression::Expression(Expression&&) noexcept = default;
Expression& Expression::operator=(Expression&&) noexcept = default;

double Expression::operator()(double t) const { return eval(*root_, t); }

}  // namespace evas::study
