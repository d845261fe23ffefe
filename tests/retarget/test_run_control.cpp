#include <string>

#include <catch2/catch.hpp>

#include "retarget/run/progress.hpp"
#include "retarget/run/run_control.hpp"

using namespace gr;

TEST_CASE("a run's control stops with the reason and the stage last started",
          "[run][interrupter]") {
  SECTION("no limit: it goes on") {
    RunControl control;
    control.start("fit");
    CHECK_FALSE(control.was_interrupted());
    CHECK_NOTHROW(control.check());
  }
  SECTION("a deadline passed") {
    RunControl control(1e-9);
    control.start("inflate");
    const std::optional<Interrupted> stop = control.interruption();
    REQUIRE(stop);
    CHECK(stop->reason() == InterruptReason::kTimeout);
    CHECK_THAT(stop->what(), Catch::StartsWith("timed out after") &&
                                 Catch::EndsWith("(--timeout 1e-09) during inflate"));
  }
  SECTION("a stop request, through the progress the stages hand on") {
    RunControl control;
    Progress progress(true, &control);
    progress.start("sign");
    request_stop();
    const std::optional<Interrupted> stop = progress.interruption();
    clear_stop_request();
    REQUIRE(stop);
    CHECK(stop->reason() == InterruptReason::kCancelled);
    CHECK(std::string(stop->what()) == "interrupted during sign");
    CHECK_FALSE(progress.was_interrupted());
  }
}
