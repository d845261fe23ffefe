#include <filesystem>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "core/io/gltf_document.hpp"
#include "retarget/outcome.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

TEST_CASE("validate picks glTF garment meshes, one per layer or every mesh of a file",
          "[cli][validate][shared]") {
  const std::string outfit = gr::test::shared_data("real/male-outfit.glb");
  const fs::path dir = gr::test::fresh_temp_dir("validate_meshes");
  const std::string report = (dir / "report.json").string();
  const gr::test::CliRun two =
      gr::test::run_cli({"validate", "--garment", outfit, "--garment-mesh", "Wolf3D_Outfit_Top",
                         "Wolf3D_Outfit_Bottom", "--avatar", outfit, "--avatar-mesh", "Wolf3D_Body",
                         "--report", report},
                        "validate_two_meshes");
  CAPTURE(two.err);
  CHECK(two.exit_code ==
        gr::to_exit_code(gr::Outcome::kNotCertified));  // production outfits cross their body
  const auto json = nlohmann::json::parse(gr::test::read_text(report));
  REQUIRE(json["garments"].size() == 2);
  CHECK(json["garments"][0]["mesh"] == "Wolf3D_Outfit_Top");
  CHECK(json["garments"][1]["mesh"] == "Wolf3D_Outfit_Bottom");
  CHECK(json["garment_pairs"].size() == 1);

  const gr::test::CliRun all =
      gr::test::run_cli({"validate", "--garment", outfit, "--garment-mesh", "all", "--avatar",
                         outfit, "--avatar-mesh", "Wolf3D_Body", "--report", report},
                        "validate_all_meshes");
  const auto every = nlohmann::json::parse(gr::test::read_text(report));
  // Every mesh of the file but the body: outfit, hair, head, eyes, teeth.
  CHECK(every["garments"].size() == gr::gltf_mesh_names(outfit).size() - 1);
  for (const auto& g : every["garments"]) CHECK(g["mesh"] != "Wolf3D_Body");

  // A body of several meshes: repeat --avatar-mesh; "all" then leaves each of them out.
  const gr::test::CliRun body_and_head = gr::test::run_cli(
      {"validate", "--garment", outfit, "--garment-mesh", "all", "--avatar", outfit,
       "--avatar-mesh", "Wolf3D_Body", "--avatar-mesh", "Wolf3D_Head", "--report", report},
      "validate_body_and_head");
  const auto layers = nlohmann::json::parse(gr::test::read_text(report));
  CHECK(layers["garments"].size() == gr::gltf_mesh_names(outfit).size() - 2);
  CHECK(layers["inputs"]["avatar"]["faces"].get<int>() >
        every["inputs"]["avatar"]["faces"].get<int>());
  const gr::test::CliRun unnamed = gr::test::run_cli(
      {"validate", "--garment", outfit, "--garment-mesh", "all", "--avatar", outfit},
      "validate_all_unnamed_body");
  CHECK(unnamed.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  CHECK_THAT(unnamed.err, Catch::Contains("needs --avatar-mesh"));

  const gr::test::CliRun mismatch =
      gr::test::run_cli({"validate", "--garment", outfit, "--garment", outfit, "--garment-mesh",
                         "a", "b", "c", "--avatar", outfit},
                        "validate_mesh_mismatch");
  CHECK(mismatch.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  CHECK_THAT(mismatch.err, Catch::Contains("3 --garment-mesh names for 2 --garment files"));
}
