// dem::contact_stiffness_tangent: the homogenised contact-stiffness operator of a periodic packing
// under affine kinematics, C = (1/V) sum_c l_c^2 [k_n n(x)n(x)n(x)n + a k_s (I - n(x)n)(x)n(x)n]
// (minor-symmetrised), as in Guo & Zhao 2014, doi:10.1002/nme.4702 (FEMxDEM); used to predict the
// stress of an RVE that is not stepped (farm::SparedMicro, docs/design/sparing.md).
#pragma once

#include <Eigen/Core>

#include "common/types.hpp"
#include "dem/simulation.hpp"

namespace dem {

/// A fourth-order tangent on the row-major 9-vectors of 3x3 tensors:
/// dsigma(3 i + j) = sum_kl C(3 i + j, 3 k + l) deps(3 k + l) [Pa].
using Tangent = Eigen::Matrix<double, 9, 9>;

/// The affine contact-stiffness tangent of the contacts active at the last force computation
/// (Contacts::active, props, branch): every contact deforms with the strain increment (its
/// relative displacement is deps . branch) and sticks (k_n normally, k_s tangentially, with the
/// law's factor a = (R1 + R2) / |branch|). Rolling and twisting springs see no relative rotation
/// under affine kinematics and add nothing. Tension positive, extension positive; symmetric in
/// (i, j) and in (k, l). It ignores non-affine relaxation and sliding: an upper bound on the
/// packing's stiffness (measured against the DEM in docs/design/sparing.md). No contacts: zero.
/// Geometric terms of order sigma deps (the forces' rotation, the volume change) are left out.
[[nodiscard]] Tangent contact_stiffness_tangent(const Simulation& sim);

/// C : deps as a 3x3 tensor [Pa] (deps symmetric, or its symmetric part is what counts).
[[nodiscard]] common::Mat3 apply_tangent(const Tangent& c, const common::Mat3& deps);

}  // namespace dem
