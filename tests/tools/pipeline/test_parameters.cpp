#include <stdexcept>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "tools/pipeline/parameters.hpp"

using namespace gr;

TEST_CASE("parameters: presets order the tolerances and share the barrier stiffness",
          "[pipeline][parameters]") {
  const PipelineParameters fast = parameters_for_quality(parse_quality("fast"));
  const PipelineParameters balanced = parameters_for_quality(parse_quality("balanced"));
  const PipelineParameters accurate = parameters_for_quality(parse_quality("accurate"));
  CHECK(fast.solver.newton.gradient_tolerance > balanced.solver.newton.gradient_tolerance);
  CHECK(balanced.solver.newton.gradient_tolerance > accurate.solver.newton.gradient_tolerance);
  CHECK(fast.voxel_size > balanced.voxel_size);
  CHECK(balanced.voxel_size > accurate.voxel_size);
  for (const auto* p : {&fast, &balanced, &accurate}) {
    CHECK(p->solver.w_contact == kPresetBarrierStiffness);
    CHECK(p->solver.dhat == RetargetParameters{}.dhat);
  }
  // Only accurate thins the barrier for the fit.
  CHECK(fast.solver.fit_support() == fast.solver.dhat);
  CHECK(balanced.solver.fit_support() == balanced.solver.dhat);
  CHECK(accurate.solver.fit_support() == 0.5 * accurate.solver.dhat);
  CHECK_THROWS_AS(parse_quality("best"), InputError);
}

TEST_CASE("parameters: overrides replace single knobs and keep the rest",
          "[pipeline][parameters]") {
  PipelineParameters p = parameters_for_quality(parse_quality("balanced"));
  const PipelineParameters before = p;
  ParameterOverrides overrides;
  overrides.fit_dhat = 0.0005;
  overrides.eps_tol = 1e-9;
  overrides.apply_to(p);
  CHECK(p.solver.fit_support() == 0.0005);
  CHECK(p.solver.dhat == before.solver.dhat);
  CHECK(p.solver.newton.gradient_tolerance == 1e-9);
  CHECK(p.solver.newton.energy_tolerance == energy_tolerance_for(1e-9));
  CHECK(p.voxel_size == before.voxel_size);
  CHECK(p.solver.w_contact == before.solver.w_contact);
}
