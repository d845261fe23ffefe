#pragma once

#include "core/common/types.hpp"
#include "core/distance/stencil.hpp"

namespace gr {

// The three smooth forms every squared distance reduces to once its closest features are
// known, written in difference vectors (a = point - origin, u and v = edge directions).
// Each returns the value and, when the pointers are non-null, the gradient and Hessian
// with respect to the stacked differences. Derived by hand with the quotient rule; the
// tests check every one against finite differences.

/// |a|²: point–point. Gradient 2a, Hessian 2I.
double point_point_form(const Vector3d& a, Vector3d* gradient = nullptr,
                        Eigen::Matrix3d* hessian = nullptr);

/// |u × v|² = |u|²|v|² - (u·v)², with derivatives in (u, v). Also the edge–edge
/// mollifier's argument.
double cross_sq_form(const Vector3d& u, const Vector3d& v, Vector6d* gradient = nullptr,
                     Matrix6d* hessian = nullptr);

/// |a × u|² / |u|²: squared distance from a point to the line through the origin along u,
/// derivatives in (a, u). @pre u ≠ 0.
double point_line_form(const Vector3d& a, const Vector3d& u, Vector6d* gradient = nullptr,
                       Matrix6d* hessian = nullptr);

/// (a · (u × v))² / |u × v|²: squared distance from a point to the plane through the
/// origin spanned by u and v, derivatives in (a, u, v). @pre u × v ≠ 0.
double point_plane_form(const Vector3d& a, const Vector3d& u, const Vector3d& v,
                        Vector9d* gradient = nullptr, Matrix9d* hessian = nullptr);

}  // namespace gr
