// Inherited crossings through the program: a strap pushed through the bundled skirt.
#include <filesystem>
#include <fstream>
#include <string>

#include <fmt/format.h>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "retarget/outcome.hpp"
#include "test_support.hpp"

using namespace gr;

TEST_CASE("A strap through the bundled skirt is untangled from it and adds no crossing",
          "[inherited][untangle][cli]") {
  const std::filesystem::path dir = test::fresh_temp_dir("strap_through_skirt");
  const std::string scene = test::project_file("scenes/dress_form/");
  // A small quad through the skirt's wall at its waist, a piece of its own.
  {
    std::ifstream in(scene + "garment.obj");
    std::ofstream out(dir / "garment.obj");
    int positions = 0;
    for (std::string line; std::getline(in, line);) {
      positions += line.rfind("v ", 0) == 0;
      out << line << '\n';
    }
    const double x0 = 0.35 + 0.16, x1 = 0.35 + 0.20, z = -0.2;
    out << fmt::format("v {} 1.04 {}\nv {} 1.04 {}\nv {} 1.07 {}\nv {} 1.07 {}\n", x0, z - 0.01, x1,
                       z - 0.01, x1, z + 0.01, x0, z + 0.01);
    const int a = positions + 1;
    out << fmt::format("g strap\nf {} {} {}\nf {} {} {}\n", a, a + 1, a + 2, a, a + 2, a + 3);
  }
  std::filesystem::copy_file(scene + "garment.mtl", dir / "garment.mtl");
  const std::filesystem::path out = dir / "out";
  const test::CliRun run = test::run_cli(
      {"retarget", "--garment", (dir / "garment.obj").string(), "--avatar", scene + "avatar.obj",
       "--no-fit", scene + "no-fit.txt", "--out", out.string(), "--quiet"},
      "strap_through_skirt");
  CAPTURE(run.out, run.err);
  CHECK(run.exit_code == to_exit_code(Outcome::kCertified));
  const auto report = nlohmann::json::parse(test::read_text(out / "report.json"));
  // The strap crosses the skirt's wall by less than the untangle's budget: pushed out of it
  // before the solve, nothing is left to inherit nor to attach.
  CHECK(report["untangle"]["pairs"].get<int>() > 0);
  CHECK(report["untangle"]["remaining"] == 0);
  CHECK(report["inherited_crossings"]["pairs"] == 0);
  CHECK(report["inherited_crossings"]["attached_pieces"] == 0);
  const auto certificate = nlohmann::json::parse(test::read_text(out / "certificate.json"));
  CHECK(certificate["counts"]["garment_self_intersections"] == 0);
  CHECK(certificate["certified"] == true);
}
