// Element parameters declared once: a table whose entries are bound to the
// members of the element's parameter struct. Each entry's default is the
// member's value in a default-constructed struct, so a default is written in
// exactly one place (the struct's member initialiser); `read` fills a struct
// from validated values (registry.h: complete_params has already filled the
// defaults and checked ranges). Parameters that do not map onto one member
// (a file to load, a list turned into objects) are declared with `unbound` and
// read by the element's factory itself.
#pragma once

#include <cmath>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "elements/registry.h"
#include "model/types.h"

namespace evas {

template <class P>
class ParamBinding {
 public:
  /// A number with its default from the struct; components in [min, max].
  ParamBinding& number(double P::*member, const std::string& key, const std::string& unit,
                       const std::string& doc, double min = -1e300, double max = 1e300) {
    specs_.push_back(scalar_param(key, unit, doc, false, P{}.*member, min, max));
    readers_.push_back([member, key](P& p, const ParamValues& v, const std::string&) {
      p.*member = v.scalar(key);
    });
    return *this;
  }

  /// A number the scene must give (no default).
  ParamBinding& required(double P::*member, const std::string& key, const std::string& unit,
                         const std::string& doc, double min = -1e300, double max = 1e300) {
    specs_.push_back(scalar_param(key, unit, doc, true, 0.0, min, max));
    readers_.push_back([member, key](P& p, const ParamValues& v, const std::string&) {
      p.*member = v.scalar(key);
    });
    return *this;
  }

  /// A whole number in [min, max]; a fraction is an input error naming the element.
  ParamBinding& whole(int P::*member, const std::string& key, const std::string& unit,
                      const std::string& doc, double min, double max) {
    specs_.push_back(scalar_param(key, unit, doc, false, P{}.*member, min, max));
    readers_.push_back([member, key](P& p, const ParamValues& v, const std::string& where) {
      const double x = v.scalar(key);
      if (x != std::floor(x))
        throw InputError(where + ": parameter '" + key + "' = " + format_number(x) +
                         " must be an integer");
      p.*member = static_cast<int>(x);
    });
    return *this;
  }

  /// A 3-vector with its default from the struct; components >= min.
  ParamBinding& vec3(Vec3 P::*member, const std::string& key, const std::string& unit,
                     const std::string& doc, double min = -1e300) {
    const Vec3 d = P{}.*member;
    specs_.push_back(
        vector_param(key, ParamSpec::Kind::Vector3, unit, doc, {d.x(), d.y(), d.z()}, min));
    readers_.push_back(
        [member, key](P& p, const ParamValues& v, const std::string&) { p.*member = v.vec3(key); });
    return *this;
  }

  /// A choice of two words (in documentation order) bound to a flag that is
  /// true for `true_word`.
  ParamBinding& flag(bool P::*member, const std::string& key, const std::string& doc,
                     const std::vector<std::string>& words, const std::string& true_word) {
    const std::string& false_word = words.at(0) == true_word ? words.at(1) : words.at(0);
    specs_.push_back(text_param(key, doc, words, P{}.*member ? true_word : false_word));
    readers_.push_back([member, key, true_word](P& p, const ParamValues& v, const std::string&) {
      p.*member = v.text(key) == true_word;
    });
    return *this;
  }

  /// A choice of words (in documentation order) bound to a string member whose
  /// value in the struct is the default.
  ParamBinding& choice(std::string P::*member, const std::string& key, const std::string& doc,
                       const std::vector<std::string>& words) {
    specs_.push_back(text_param(key, doc, words, P{}.*member));
    readers_.push_back(
        [member, key](P& p, const ParamValues& v, const std::string&) { p.*member = v.text(key); });
    return *this;
  }

  /// A parameter the element's factory reads itself.
  ParamBinding& unbound(ParamSpec spec) {
    specs_.push_back(std::move(spec));
    return *this;
  }

  const std::vector<ParamSpec>& specs() const { return specs_; }

  /// The struct from completed values; `where` names the element in errors.
  P read(const ParamValues& v, const std::string& where) const {
    P p{};
    for (const auto& r : readers_) r(p, v, where);
    return p;
  }

 private:
  std::vector<ParamSpec> specs_;
  std::vector<std::function<void(P&, const ParamValues&, const std::string&)>> readers_;
};

}  // namespace evas
