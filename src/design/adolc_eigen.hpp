// ADOL-C's taped adouble (reverse-mode automatic differentiation, Debian's libadolc-dev) as an Eigen scalar,
// for the design's gradients (basin_tape.cpp). Included by src/design only.
//
// Why ADOL-C: the gradient of one objective with respect to every hull vertex (3n variables, n up to
// thousands) costs a few times the function in reverse mode; Eigen's forward AutoDiffScalar would cost 3n
// times (docs/inverse-design.md has the figures).
#pragma once

#include <adolc/adouble.h>

#include <Eigen/Core>

namespace Eigen {
template <>
struct NumTraits<adouble> : NumTraits<double> {
  using Real = adouble;
  using NonInteger = adouble;
  using Nested = adouble;
  using Literal = adouble;
  enum {
    IsComplex = 0,
    IsInteger = 0,
    IsSigned = 1,
    RequireInitialization = 1,
    ReadCost = 1,
    AddCost = 3,
    MulCost = 3
  };
};
template <typename BinaryOp>
struct ScalarBinaryOpTraits<adouble, double, BinaryOp> {
  using ReturnType = adouble;
};
template <typename BinaryOp>
struct ScalarBinaryOpTraits<double, adouble, BinaryOp> {
  using ReturnType = adouble;
};
namespace internal {
// Eigen's cross product conjugates a product, which ADOL-C returns as its temporary adub (not copyable).
template <>
struct conj_retval<adub> {
  using type = adouble;
};
template <>
struct conj_default_impl<adub, false> {
  static adouble run(const adub& x) { return adouble(x); }
};
}  // namespace internal
}  // namespace Eigen

// ADOL-C names it fabs; the spherical helpers call abs (found by argument-dependent lookup).
inline adouble abs(const badouble& x) { return fabs(x); }
