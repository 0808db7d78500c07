#pragma once
// An expression of some of x, y, z and t that a scene gives as text, e.g. an inlet's velocity profile
// "6 * y * (0.41 - y) / 0.41^2". Parsed once by muParser (a well-kept library: its operators,
// functions sin, exp, sqrt, abs, min, max, ..., the constant _e, and pi); evaluating it is not
// thread-safe (one set of variables per expression), so the callers evaluate it in serial loops.
#include <memory>
#include <string>

namespace sph {

class Expression {
 public:
  Expression() = default;
  // `variables`: the names it may use, each one letter of "xyzt". Throws sph::Error with muParser's
  // message when `text` is not an expression of those.
  Expression(const std::string& text, const std::string& variables);

  double operator()(double x, double y, double z, double t) const;

 private:
  struct Impl;
  std::shared_ptr<Impl> impl_;  // shared by copies: the parser binds its variables by address
};

}  // namespace sph
