#pragma once

#include "core/energies/distance_field.hpp"

namespace gr::test {

/// Exact signed distance to a sphere (positive outside), smooth away from the centre.
class SphereField : public DistanceField {
 public:
  SphereField(Vector3d centre, double radius) : centre_(centre), radius_(radius) {}
  double evaluate(const Vector3d& p, Vector3d* gradient, Eigen::Matrix3d* hessian) const override {
    const Vector3d d = p - centre_;
    const double r = d.norm();
    const Vector3d n = d / r;
    if (gradient) *gradient = n;
    if (hessian) *hessian = (Eigen::Matrix3d::Identity() - n * n.transpose()) / r;
    return r - radius_;
  }

 private:
  Vector3d centre_;
  double radius_;
};

}  // namespace gr::test
