#include "src/core/expression.hpp"

#include <muParser.h>

#include <cmath>

#include "src/core/error.hpp"

namespace sph {

struct Expression::Impl {
  std::string text;
  mu::Parser parser;
  double x = 0.0, y = 0.0, z = 0.0, t = 0.0;
};

Expression::Expression(const std::string& text, const std::string& variables) : impl_(std::make_shared<Impl>()) {
  impl_->text = text;
  std::string names;
  try {
    for (char v : variables) {
      double* slot = v == 'x' ? &impl_->x : v == 'y' ? &impl_->y : v == 'z' ? &impl_->z : &impl_->t;
      impl_->parser.DefineVar(std::string(1, v), slot);
      names += (names.empty() ? "" : ", ") + std::string(1, v);
    }
    // muParser 2.3's own _pi has 13 digits (3.141592653589): pi and _pi are M_PI here.
    impl_->parser.DefineConst("pi", M_PI);
    impl_->parser.DefineConst("_pi", M_PI);
    impl_->parser.SetExpr(text);
    impl_->parser.Eval();  // parses: an unknown name or a syntax error shows here, not at the first step
  } catch (const mu::Parser::exception_type& e) {
    throw Error("'" + text + "' is not an expression of " + names + ": " + e.GetMsg());
  }
}

double Expression::operator()(double x, double y, double z, double t) const {
  Impl& f = *impl_;
  f.x = x, f.y = y, f.z = z, f.t = t;
  try {
    return f.parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw Error("expression '" + f.text + "' failed: " + e.GetMsg());
  }
}

}  // namespace sph
