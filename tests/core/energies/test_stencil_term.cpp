#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/energies/energy_checks.hpp"
#include "core/energies/stencil_term.hpp"

using namespace gr;

namespace {

/// A term written only through StencilTerm's local pieces, with a t dof and an indefinite
/// Hessian: each vertex keeps its distance L from a point moving as p(t) = a + t (b - a),
/// 1/4 sum (|x - p(t)|^2 - L^2)^2.
class MovingRingEnergy : public StencilTerm<MovingRingEnergy, 4> {
 public:
  struct Element {
    int vertex;
    Vector3d a, b;
    double radius;
  };

  MovingRingEnergy(std::vector<Element> elements, const DofLayout& layout)
      : elements_(std::move(elements)) {
    build_stencils(layout);
  }

  const std::vector<Element>& elements() const { return elements_; }
  const char* name() const override { return "moving ring"; }

  static StencilDofs<kStencilSize> element_dofs(const Element& element, const DofLayout& layout) {
    StencilDofs<kStencilSize> dofs =
        vertex_dofs<kStencilSize>(std::array<int, 1>{element.vertex}, layout);
    dofs[3] = layout.t_index();
    return dofs;
  }
  static LocalVector gather(const Element& element, const Eigen::Ref<const MatrixX3d>& V,
                            double t) {
    LocalVector q;
    q << V.row(element.vertex).transpose(), t;
    return q;
  }
  static double element_value(const Element& element, const LocalVector& q) {
    const double c = offset(element, q).squaredNorm() - element.radius * element.radius;
    return 0.25 * c * c;
  }
  static double element_gradient(const Element& element, const LocalVector& q, LocalVector& g) {
    const Vector3d r = offset(element, q);
    const double c = r.squaredNorm() - element.radius * element.radius;
    g = jacobian(element).transpose() * (c * r);
    return 0.25 * c * c;
  }
  static void element_hessian(const Element& element, const LocalVector& q, bool, LocalMatrix& h) {
    const Vector3d r = offset(element, q);
    const double c = r.squaredNorm() - element.radius * element.radius;
    const Eigen::Matrix3d A = 2.0 * r * r.transpose() + c * Eigen::Matrix3d::Identity();
    const Eigen::Matrix<double, 3, 4> J = jacobian(element);
    h = J.transpose() * A * J;
  }
  static constexpr HessianProjection kProjection = HessianProjection::generic;

 private:
  /// x - p(t), and its Jacobian [I, -(b - a)] in (x, t).
  static Vector3d offset(const Element& e, const LocalVector& q) {
    return q.head<3>() - (e.a + q[3] * (e.b - e.a));
  }
  static Eigen::Matrix<double, 3, 4> jacobian(const Element& e) {
    Eigen::Matrix<double, 3, 4> J;
    J << Eigen::Matrix3d::Identity(), -(e.b - e.a);
    return J;
  }

  std::vector<Element> elements_;
};

std::vector<MovingRingEnergy::Element> ring_elements() {
  std::srand(41);
  std::vector<MovingRingEnergy::Element> elements;
  for (int v : {0, 2, 3, 2})
    elements.push_back({v, Vector3d::Random(), Vector3d::Random(), 0.8 + 0.1 * v});
  return elements;
}

}  // namespace

TEST_CASE("stencil term: assembled derivatives in (t, Vg) match finite differences",
          "[energies][stencil][grad][hess]") {
  const int n = 4;
  const DofLayout layout{n, true};
  const MovingRingEnergy energy(ring_elements(), layout);
  for (const auto& element : energy.elements())
    test::check_element_derivatives<MovingRingEnergy>(
        element, MovingRingEnergy::LocalVector::Random(), 1e-6);

  std::srand(42);
  const Eigen::VectorXd x = Eigen::VectorXd::Random(layout.dof_count());
  test::check_energy_in_layout(energy, layout, x, 1e-7, 1e-6);
  Eigen::VectorXd g;
  energy.gradient(layout.garment(x), layout.t(x), g);
  const Eigen::MatrixXd H = energy.hessian(layout.garment(x), layout.t(x), false);
  CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(H).eigenvalues().minCoeff() < 0.0);

  SECTION("the generic projection makes the Hessian PSD") {
    const Eigen::MatrixXd P = energy.hessian(layout.garment(x), layout.t(x), true);
    CHECK(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues().minCoeff() >=
          -1e-12 * P.norm());
  }
  SECTION("the value is the sum of the element values in element order") {
    double sum = 0.0;
    for (const auto& element : energy.elements())
      sum += MovingRingEnergy::element_value(
          element, MovingRingEnergy::gather(element, layout.garment(x), layout.t(x)));
    CHECK(energy.value(layout.garment(x), layout.t(x)) == sum);
  }
  SECTION("with t fixed, t's derivatives are dropped") {
    const MovingRingEnergy fixed(ring_elements(), DofLayout{n, false, layout.t(x)});
    Eigen::VectorXd g_fixed;
    fixed.gradient(layout.garment(x), layout.t(x), g_fixed);
    CHECK(g_fixed == g.tail(3 * n));
    const Eigen::MatrixXd H_fixed = fixed.hessian(layout.garment(x), layout.t(x), false);
    CHECK(H_fixed == H.bottomRightCorner(3 * n, 3 * n));
  }
}
