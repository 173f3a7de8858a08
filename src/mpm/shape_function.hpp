// Run-time choice of the shape function and the per-point 1D weights it produces.
#pragma once

#include <array>
#include <string_view>

#include "common/choice_table.hpp"
#include "mpm/shape_bspline2.hpp"
#include "mpm/shape_linear.hpp"
#include "mpm/shape_ugimp.hpp"

namespace mpm {

/// Shape function of a run (selected in SolverConfig::shape).
enum class ShapeKind { linear, ugimp, bspline2 };
/// The job's names of the shape functions (mpm.shape_function).
inline constexpr std::array<common::Named<ShapeKind>, 3> kShapeKindNames{
    {{"linear", ShapeKind::linear},
     {"ugimp", ShapeKind::ugimp},
     {"bspline2", ShapeKind::bspline2}}};

/// "linear", "ugimp", "bspline2".
std::string_view to_string(ShapeKind kind);
/// Inverse of to_string; throws common::InputError listing the valid names.
ShapeKind shape_kind_from_string(std::string_view name);
/// Nodes per axis in a stencil (2 for linear, 3 otherwise).
int stencil_width(ShapeKind kind);

/// 1D weights of one point along one axis: nodes base .. base + width - 1.
struct Weights1D {
  int base = 0;
  std::array<double, 3> w{};   ///< S [-]
  std::array<double, 3> dw{};  ///< dS/dx [1/m]
};

/// Weights along one axis for a point at s = (x - origin) / h (cell units), domain half-width
/// lp (cell units, used by uGIMP), cell size h [m]. Entries past the stencil width are zero.
template <class Shape>
Weights1D weights_1d(double s, double lp, double h) {
  Weights1D out;
  out.base = Shape::stencil_base(s, lp);
  for (int a = 0; a < Shape::support; ++a) {
    const double r = s - (out.base + a);
    out.w[a] = Shape::value(r, lp);
    out.dw[a] = Shape::gradient(r, lp) / h;
  }
  return out;
}

/// Same, dispatched on the run-time kind.
Weights1D weights_1d(ShapeKind kind, double s, double lp, double h);

}  // namespace mpm
