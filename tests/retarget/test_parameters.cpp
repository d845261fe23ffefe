#include <optional>
#include <set>
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "retarget/parameters.hpp"

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
    CHECK(p->solver.w_contact == 1e6);
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
  overrides.set("fit_dhat", 0.0005);
  overrides.set("eps_tol", 1e-9);
  overrides.apply_to(p);
  CHECK(p.solver.fit_support() == 0.0005);
  CHECK(p.solver.dhat == before.solver.dhat);
  CHECK(p.solver.newton.gradient_tolerance == 1e-9);
  CHECK(p.solver.newton.energy_tolerance == energy_tolerance_for(1e-9));
  CHECK(p.voxel_size == before.voxel_size);
  CHECK(p.solver.w_contact == before.solver.w_contact);
}

TEST_CASE("parameters: the table sets every preset and checks every override",
          "[pipeline][parameters]") {
  // Every row reads back the value its preset gives it (a row whose getter and setter
  // disagree would report one value and run with another).
  for (const Quality quality : {Quality::kFast, Quality::kBalanced, Quality::kAccurate}) {
    const PipelineParameters preset = parameters_for_quality(quality);
    for (const ParameterRow& row : parameter_table()) {
      CAPTURE(row.name, to_string(quality));
      const std::optional<double>& value = row.preset[static_cast<int>(quality)];
      if (!value || std::string(row.name) == "fit_dhat" ||
          std::string(row.name) == "max_fit_iterations")
        continue;  // unset, or 0 meaning "as dhat" / "as each inflation round"
      CHECK(row.get(preset) == *value);
    }
  }
  CHECK(parameters_for_quality(Quality::kFast).solver.fit_iteration_cap() == 40);
  CHECK(parameters_for_quality(Quality::kBalanced).solver.fit_iteration_cap() == 400);

  ParameterOverrides overrides;
  CHECK_THROWS_AS(overrides.set("no_such_knob", 1.0), std::invalid_argument);
  CHECK_THROWS_AS(overrides.set("step_tolerance", 1e-3), std::invalid_argument);  // preset only
  CHECK_THROWS_AS(overrides.set("dhat", 0.0), std::invalid_argument);
  CHECK_THROWS_AS(overrides.set("fit_samples_per_face", 4.0), std::invalid_argument);
  CHECK_THROWS_AS(overrides.set("max_al_rounds", 2.5), std::invalid_argument);
  CHECK_THROWS_AS(overrides.set("skeleton_pullback", 1.5), std::invalid_argument);
  CHECK(overrides.empty());

  // An iteration cap resets the fit's own cap unless that is given too, in any order.
  overrides.set("max_fit_iterations", 7);
  overrides.set("max_newton_iterations", 50);
  PipelineParameters p = parameters_for_quality(Quality::kFast);
  overrides.apply_to(p);
  CHECK(p.solver.newton.max_iterations == 50);
  CHECK(p.solver.fit_iteration_cap() == 7);

  // Names are unique, and so are the command-line options.
  std::set<std::string> names, options;
  for (const ParameterRow& row : parameter_table()) {
    CHECK(names.insert(row.name).second);
    if (*row.option != '\0') {
      CHECK(options.insert(row.option).second);
      CHECK(find_parameter_option(row.option) == &row);
    }
    CHECK(find_parameter(row.name) == &row);
  }
  CHECK(find_parameter_option("no_self_contact") == find_parameter("self_contact"));
}
