#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "core/io/obj_document.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

bool mentions(const std::vector<std::string>& warnings, const std::string& text) {
  for (const std::string& warning : warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("MTL texture statements name the file after their options", "[io][mtl]") {
  const auto names = material_texture_names(
      "newmtl cloth\n"
      "map_Kd plain.png\n"
      "map_Ka -s 1 1 1 scaled.png\n"
      "map_Ks -o 0.5 offset file.png\r\n"
      "map_Bump -bm 0.3 -clamp on bump map.png\n"
      "map_d -mm 0 1 -s 2 alpha.png\n"
      "norm -type sphere normal.png\n"
      "Kd 1 1 1\n"
      "map_Kd -blendu off\n");
  CHECK(names == std::vector<std::string>{"plain.png", "scaled.png", "offset file.png",
                                          "bump map.png", "alpha.png", "normal.png"});
}

TEST_CASE("Material files are copied only from inside the asset's folder", "[io][mtl]") {
  const fs::path root = test::fresh_temp_dir("asset_references");
  const fs::path asset = root / "asset";
  const fs::path outside = root / "outside";
  write_text(outside / "secret.txt", "not for the output\n");
  write_text(outside / "textures" / "inner.png", "outside texture\n");
  write_text(asset / "tex.png", "inside texture\n");
  write_text(asset / "sub" / "scaled.png", "scaled texture\n");
  fs::create_symlink(outside / "secret.txt", asset / "link.png");
  fs::create_directory_symlink(outside / "textures", asset / "texdir");
  fs::create_symlink(asset / "tex.png", asset / "alias.png");  // a link that stays inside
  REQUIRE(::mkfifo((asset / "pipe.png").c_str(), 0644) == 0);
  write_text(asset / "garment.mtl",
             "newmtl cloth\n"
             "map_Kd tex.png\n"
             "map_Ka -s 1 1 1 sub/scaled.png\n"
             "map_Ks link.png\n"
             "map_d texdir/inner.png\n"
             "map_Ns alias.png\n"
             "bump pipe.png\n"
             "disp ../outside/secret.txt\n"
             "decal " +
                 (outside / "secret.txt").string() + "\n");
  fs::create_symlink(outside / "secret.txt", asset / "escape.mtl");

  ObjDocument document;
  document.source_path = (asset / "garment.obj").string();
  document.material_libraries = {"garment.mtl", "escape.mtl", "missing.mtl"};

  SECTION("by default") {
    const fs::path out = root / "out_default";
    fs::create_directories(out);
    const auto warnings = copy_material_files(document, out.string());
    CAPTURE(warnings);
    CHECK(fs::is_regular_file(out / "garment.mtl"));
    CHECK(fs::is_regular_file(out / "tex.png"));
    CHECK(fs::is_regular_file(out / "sub" / "scaled.png"));
    CHECK(fs::is_regular_file(out / "alias.png"));
    CHECK_FALSE(fs::exists(out / "link.png"));
    CHECK_FALSE(fs::exists(out / "texdir"));
    CHECK_FALSE(fs::exists(out / "pipe.png"));
    CHECK_FALSE(fs::exists(out / "escape.mtl"));
    CHECK_FALSE(fs::exists(root / "outside" / "secret.txt.copy"));
    CHECK(mentions(warnings, "link.png: a symbolic link out of the asset's folder"));
    CHECK(mentions(warnings, "inner.png: a symbolic link out of the asset's folder"));
    CHECK(mentions(warnings, "escape.mtl: a symbolic link out of the asset's folder"));
    CHECK(mentions(warnings, "pipe.png: not a regular file"));
    CHECK(mentions(warnings, "secret.txt: leaves the asset's folder (..)"));
    CHECK(mentions(warnings, "an absolute path"));
    CHECK(mentions(warnings, "missing.mtl: referenced file not found"));
    // No byte of a file outside the asset's folder reaches the output.
    for (const auto& entry : fs::recursive_directory_iterator(out)) {
      if (!entry.is_regular_file()) continue;
      std::ifstream in(entry.path());
      const std::string text{std::istreambuf_iterator<char>(in), {}};
      CAPTURE(entry.path());
      CHECK(text.find("not for the output") == std::string::npos);
      CHECK(text.find("outside texture") == std::string::npos);
    }
  }

  SECTION("an OBJ named without its folder reads its assets from the working folder") {
    const fs::path out = root / "out_relative";
    fs::create_directories(out);
    const fs::path before = fs::current_path();
    fs::current_path(asset);
    ObjDocument relative = document;
    relative.source_path = "garment.obj";
    std::vector<std::string> warnings;
    CHECK_NOTHROW(warnings = copy_material_files(relative, out.string()));
    fs::current_path(before);
    CHECK(fs::is_regular_file(out / "tex.png"));
    CHECK_FALSE(fs::exists(out / "link.png"));
  }

  SECTION("with external assets allowed, links out are followed, the rest still refused") {
    const fs::path out = root / "out_external";
    fs::create_directories(out);
    const auto warnings = copy_material_files(document, out.string(), true);
    CAPTURE(warnings);
    CHECK(fs::is_regular_file(out / "link.png"));
    CHECK(fs::is_regular_file(out / "texdir" / "inner.png"));
    CHECK(fs::is_regular_file(out / "escape.mtl"));
    CHECK_FALSE(fs::exists(out / "pipe.png"));
    CHECK(mentions(warnings, "pipe.png: not a regular file"));
    CHECK(mentions(warnings, "leaves the asset's folder (..)"));
    CHECK(mentions(warnings, "an absolute path"));
  }
}
