#include <catch2/catch.hpp>

#include <Eigen/Dense>

#include "core/common/errors.hpp"
#include "core/energies/energy_checks.hpp"
#include "core/energies/position_energy.hpp"
#include "core/mesh/boundary_loops.hpp"
#include "core/test_shapes.hpp"

using namespace gr;

namespace {

MovingBone random_bone(int seed) {
  std::srand(static_cast<unsigned>(seed));
  return {Vector3d::Random(), Vector3d::Random() + Vector3d(0, 0, 2), Vector3d::Random(),
          Vector3d::Random() + Vector3d(0, 0, 3)};
}

/// The skeleton layout of the shared data sets: 15 joints, root 0, spine 0-1, head 1-2,
/// arms from 1, legs 0-9-10-11 and 0-12-13-14.
MatrixX2i data_skeleton_bones() {
  MatrixX2i bones(14, 2);
  bones << 0, 1, 1, 2, 1, 3, 3, 4, 4, 5, 1, 6, 6, 8, 7, 8, 0, 9, 9, 10, 10, 11, 0, 12, 12, 13, 13,
      14;
  return bones;
}

}  // namespace

TEST_CASE("position energy: bone parameter derivatives match finite differences",
          "[energies][position][grad][hess]") {
  const int seed = GENERATE(1, 2, 3);
  const MovingBone bone = random_bone(seed);
  PositionEnergy::LocalVector q;
  q << Vector3d::Random(), 0.37;
  using Local = PositionEnergy::LocalVector;
  const auto s = [&](const Eigen::VectorXd& y) {
    return PositionEnergy::bone_parameter(bone, Local(y), nullptr, nullptr);
  };
  const auto ds = [&](const Eigen::VectorXd& y) {
    Local g;
    PositionEnergy::bone_parameter(bone, Local(y), &g, nullptr);
    return Eigen::VectorXd(g);
  };
  Local g;
  PositionEnergy::LocalMatrix h;
  PositionEnergy::bone_parameter(bone, q, &g, &h);
  CHECK(test::fd_matches(g, test::fd_gradient(s, q), 1e-7));
  CHECK(test::fd_matches(h, test::fd_hessian(ds, q), 1e-6));

  const PositionEnergy::Element element{0, bone, 0.2};
  const auto e = [&](const Eigen::VectorXd& y) {
    return PositionEnergy::element_value(element, Local(y));
  };
  const auto de = [&](const Eigen::VectorXd& y) {
    Local ge;
    PositionEnergy::element_gradient(element, Local(y), ge);
    return Eigen::VectorXd(ge);
  };
  PositionEnergy::element_gradient(element, q, g);
  PositionEnergy::element_hessian(element, q, false, h);
  CHECK(test::fd_matches(g, test::fd_gradient(e, q), 1e-7));
  CHECK(test::fd_matches(h, test::fd_hessian(de, q), 1e-6));
}

TEST_CASE(
    "position energy: zero at rest, assembled derivatives in (t, Vg) match finite differences",
    "[energies][position][grad][hess]") {
  const TriangleMesh cylinder = open_cylinder(0.3, -0.5, 0.5, 3, 8);
  const int n = static_cast<int>(cylinder.vertices.rows());
  const auto loops = boundary_loops(cylinder.faces);
  REQUIRE(loops.size() == 2);
  std::vector<LoopBone> loop_bones;
  const MovingBone bone{{0, 0, -1}, {0, 0, 1}, {0.1, 0, -1.5}, {0, 0.2, 1.2}};
  for (const auto& loop : loops) loop_bones.push_back({loop, bone, 0});

  const DofLayout layout{n, true};
  const PositionEnergy energy(cylinder.vertices, loop_bones, layout);
  CHECK(energy.elements().size() == 16);
  CHECK(energy.value(cylinder.vertices, 0.0) == Approx(0.0).margin(1e-28));

  std::srand(5);
  Eigen::VectorXd x =
      layout.pack(0.6, cylinder.vertices) + 0.05 * Eigen::VectorXd::Random(layout.dof_count());
  test::check_energy_in_layout(energy, layout, x, 1e-7, 1e-6);

  SECTION("with t fixed, t's derivatives are dropped") {
    const DofLayout fixed{n, false, 0.6};
    const PositionEnergy fixed_energy(cylinder.vertices, loop_bones, fixed);
    Eigen::VectorXd g, g_fixed;
    fixed_energy.gradient(layout.garment(x), 0.6, g_fixed);
    energy.gradient(layout.garment(x), 0.6, g);
    CHECK((g.tail(3 * n) - g_fixed).norm() <= 1e-15);
  }
}

TEST_CASE("boundary loops of a grid and a cylinder", "[mesh][loops]") {
  const auto grid_loops = boundary_loops(test::curved_grid(4).faces);
  REQUIRE(grid_loops.size() == 1);
  CHECK(grid_loops[0].size() == 12);
  const auto cylinder_loops = boundary_loops(open_cylinder(1.0, 0.0, 1.0, 4, 10).faces);
  REQUIRE(cylinder_loops.size() == 2);
  CHECK(cylinder_loops[0].size() == 10);
  CHECK(cylinder_loops[1].size() == 10);
  CHECK(boundary_loops(icosphere(1).faces).empty());
}

TEST_CASE("leg joints are the two chains hanging from the branching joint", "[skeleton]") {
  const LegJoints legs = find_leg_joints(data_skeleton_bones(), 15, "skeleton");
  CHECK(std::min(legs.hips[0], legs.hips[1]) == 9);
  CHECK(std::max(legs.hips[0], legs.hips[1]) == 12);
  CHECK(legs.knees[0] == (legs.hips[0] == 9 ? 10 : 13));
  CHECK(legs.knees[1] == (legs.hips[1] == 9 ? 10 : 13));

  MatrixX2i chain(3, 2);
  chain << 0, 1, 1, 2, 2, 3;
  CHECK_THROWS_AS(find_leg_joints(chain, 4, "chain"), InputError);
}

TEST_CASE("loop bones: the closest bone within 60 degrees of the loop normal", "[skeleton]") {
  // A vertical cylinder (loops with normals along z) around a vertical bone; a horizontal
  // bone passes closer to the lower loop's centre but is perpendicular to it.
  const TriangleMesh cylinder = open_cylinder(0.3, 0.0, 1.0, 2, 8);
  MatrixX3d joints(4, 3);
  joints << 0.05, 0, -1, 0.05, 0, 2, -1, 0, 0.01, 1, 0, 0.01;
  MatrixX2i bones(2, 2);
  bones << 0, 1, 2, 3;
  const auto loops = boundary_loops(cylinder.faces);
  const auto assigned = assign_loop_bones(cylinder.vertices, loops, joints, joints, bones);
  REQUIRE(assigned.size() == 2);
  CHECK(assigned[0].bone_index == 0);
  CHECK(assigned[1].bone_index == 0);

  // A skeleton with legs (hips at z = -0.1, knees at -0.6) for the skirt's virtual bone.
  MatrixX3d skeleton = MatrixX3d::Zero(15, 3);
  for (int j = 0; j < 15; ++j) skeleton.row(j) << 0.01 * j, 0.02 * j, 0.5 - 0.1 * j;
  skeleton.row(9) << -0.2, 0, -0.1;
  skeleton.row(12) << 0.2, 0, -0.1;
  skeleton.row(10) << -0.2, 0, -0.6;
  skeleton.row(13) << 0.2, 0, -0.6;

  SECTION("a skirt uses the virtual bone between the legs") {
    const std::vector<char> all(static_cast<std::size_t>(cylinder.vertices.rows()), 1);
    const auto skirt = assign_loop_bones(cylinder.vertices, loops, skeleton, 2.0 * skeleton,
                                         data_skeleton_bones(), all);
    REQUIRE(skirt.size() == 2);
    CHECK(skirt[0].bone_index == -1);
    CHECK((skirt[0].bone.source_a - Vector3d(0, 0, -0.1)).norm() < 1e-15);
    CHECK((skirt[0].bone.source_b - Vector3d(0, 0, -0.6)).norm() < 1e-15);
    CHECK((skirt[0].bone.target_b - Vector3d(0, 0, -1.2)).norm() < 1e-15);
  }

  SECTION("in an outfit only the skirt's loops take the virtual bone") {
    // The cylinder's lower loop is a skirt's (as if it were another garment), the upper
    // one a jacket's: the jacket's loop keeps its own bone, the spine it goes round.
    std::vector<char> lower(static_cast<std::size_t>(cylinder.vertices.rows()), 0);
    for (Eigen::Index v = 0; v < cylinder.vertices.rows(); ++v)
      lower[static_cast<std::size_t>(v)] = cylinder.vertices(v, 2) < 0.5;
    skeleton.row(1) << 0.0, 0.0, 1.1;
    const auto mixed = assign_loop_bones(cylinder.vertices, loops, skeleton, 2.0 * skeleton,
                                         data_skeleton_bones(), lower);
    REQUIRE(mixed.size() == 2);
    const bool first_is_lower = cylinder.vertices(loops[0].front(), 2) < 0.5;
    const LoopBone& skirt_loop = first_is_lower ? mixed[0] : mixed[1];
    const LoopBone& jacket_loop = first_is_lower ? mixed[1] : mixed[0];
    CHECK(skirt_loop.bone_index == -1);
    CHECK(jacket_loop.bone_index >= 0);
  }
}

TEST_CASE("loop bones: a loop takes only a bone it goes round", "[skeleton]") {
  // A small ring (an eyelet, normal along z) beside a vertical bone it does not go round,
  // and a cuff around the bone's line far past its end: neither takes the bone. A cuff
  // around the bone does.
  MatrixX3d joints(2, 3);
  joints << 0, 0, 0, 0, 0, 1;
  MatrixX2i bones(1, 2);
  bones << 0, 1;
  const auto assigned_to = [&](const TriangleMesh& ring) {
    const auto assigned =
        assign_loop_bones(ring.vertices, boundary_loops(ring.faces), joints, joints, bones);
    return assigned.size();
  };
  TriangleMesh eyelet = open_cylinder(0.02, 0.45, 0.5, 2, 8);
  eyelet.vertices.col(0).array() += 0.3;
  CHECK(assigned_to(eyelet) == 0);
  CHECK(assigned_to(open_cylinder(0.1, 4.0, 4.2, 2, 8)) == 0);
  CHECK(assigned_to(open_cylinder(0.1, 0.4, 0.6, 2, 8)) == 2);
  // Past the bone's end, by less than half its length: a hem below the hips.
  CHECK(assigned_to(open_cylinder(0.1, 1.2, 1.4, 2, 8)) == 2);
}
