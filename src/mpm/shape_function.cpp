// Run-time dispatch over the shape-function structs.
#include "mpm/shape_function.hpp"

#include <string>

#include "common/errors.hpp"

namespace mpm {

std::string_view to_string(ShapeKind kind) { return common::name_of(kShapeKindNames, kind); }

ShapeKind shape_kind_from_string(std::string_view name) {
  if (const auto k = common::value_of(kShapeKindNames, name)) return *k;
  throw common::InputError("mpm shape function '" + std::string(name) + "': must be one of " +
                           common::names_list(kShapeKindNames));
}

int stencil_width(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::linear:
      return LinearShape::support;
    case ShapeKind::ugimp:
      return UgimpShape::support;
    case ShapeKind::bspline2:
      return BSpline2Shape::support;
  }
  return 0;
}

Weights1D weights_1d(ShapeKind kind, double s, double lp, double h) {
  switch (kind) {
    case ShapeKind::linear:
      return weights_1d<LinearShape>(s, lp, h);
    case ShapeKind::ugimp:
      return weights_1d<UgimpShape>(s, lp, h);
    case ShapeKind::bspline2:
      return weights_1d<BSpline2Shape>(s, lp, h);
  }
  return {};
}

}  // namespace mpm
