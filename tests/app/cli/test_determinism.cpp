// The written garment must not depend on the CPU: neither on the BLAS kernels that
// OpenBLAS would pick for it nor on the number of threads. Each scene is retargeted under
// every OpenBLAS kernel this CPU can run and with one thread, and every garment.obj is
// compared byte for byte with the one of the plain run (never with a stored hash: the
// solver may change, the agreement may not).
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_runner.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

/// The CPU's feature flags from /proc/cpuinfo (empty when it cannot be read).
std::set<std::string> cpu_flags() {
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("flags", 0) != 0) continue;
    std::istringstream words(line.substr(line.find(':') + 1));
    std::set<std::string> flags;
    for (std::string word; words >> word;) flags.insert(word);
    return flags;
  }
  return {};
}

/// One run of a scene: what differs from the plain run.
struct Variant {
  std::string name;
  std::vector<gr::test::EnvironmentVariable> environment;
  std::vector<std::string> extra_args;
};

/// The plain run first, then each OpenBLAS kernel this CPU can execute (forcing one it
/// cannot would crash OpenBLAS, were it loaded), then a single thread.
std::vector<Variant> variants() {
  const std::set<std::string> flags = cpu_flags();
  const auto has = [&](const char* flag) { return flags.count(flag) > 0; };
  std::vector<Variant> out{{"default", {}, {}}};
  if (has("avx")) out.push_back({"Sandybridge", {{"OPENBLAS_CORETYPE", "Sandybridge"}}, {}});
  if (has("avx2") && has("fma")) out.push_back({"Haswell", {{"OPENBLAS_CORETYPE", "Haswell"}}, {}});
  if (has("avx512f")) out.push_back({"SkylakeX", {{"OPENBLAS_CORETYPE", "SkylakeX"}}, {}});
  out.push_back({"one thread", {}, {"--threads", "1"}});
  return out;
}

/// Retargets with `args` (without --out) under every variant and checks the garments agree.
void check_same_bytes_everywhere(const std::string& scene, const std::vector<std::string>& args) {
  std::string reference;
  for (const Variant& variant : variants()) {
    const fs::path out = gr::test::fresh_temp_dir("determinism_" + scene);
    std::vector<std::string> run_args = args;
    run_args.insert(run_args.end(), {"--quiet", "--out", out.string()});
    run_args.insert(run_args.end(), variant.extra_args.begin(), variant.extra_args.end());
    const gr::test::CliRun run =
        gr::test::run_cli(run_args, "determinism_" + scene, variant.environment);
    INFO(scene << ", " << variant.name << ": " << run.err);
    REQUIRE(run.exit_code == 0);
    const std::string garment = gr::test::read_text(out / "garment.obj");
    REQUIRE_FALSE(garment.empty());
    if (reference.empty())
      reference = garment;
    else
      CHECK(garment == reference);
  }
}

}  // namespace

TEST_CASE("the bundled scene gives the same garment bytes under every BLAS kernel and thread count",
          "[cli][determinism]") {
  const std::string scene = "scenes/dress_form/";
  check_same_bytes_everywhere(
      "dress_form", {"retarget", "--garment", gr::test::project_file(scene + "garment.obj"),
                     "--avatar", gr::test::project_file(scene + "avatar.obj"), "--no-fit",
                     gr::test::project_file(scene + "no-fit.txt")});
}

TEST_CASE("foxgirl_skirt gives the same garment bytes under every BLAS kernel and thread count",
          "[cli][determinism]") {
  check_same_bytes_everywhere(
      "foxgirl_skirt",
      {"retarget", "--skirt", "--garment", gr::test::shared_data("garments/skirt/garment.obj"),
       "--no-fit", gr::test::shared_data("garments/skirt/no-fit.txt"), "--source-skeleton",
       gr::test::shared_data("garments/skirt/skeleton.obj"), "--avatar",
       gr::test::shared_data("avatars/foxgirl/avatar.obj"), "--target-skeleton",
       gr::test::shared_data("avatars/foxgirl/skeleton.obj")});
}
