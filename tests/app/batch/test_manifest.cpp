#include <filesystem>
#include <fstream>

#include "app/batch/manifest.hpp"
#include "core/common/errors.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

fs::path write_manifest(const std::string& name, const std::string& text) {
  const fs::path dir = gr::test::fresh_temp_dir("manifest_" + name);
  std::ofstream(dir / "manifest.jsonl") << text;
  return dir / "manifest.jsonl";
}

std::string error_of(const std::string& name, const std::string& text) {
  try {
    gr::read_manifest(write_manifest(name, text).string());
  } catch (const gr::InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("read_manifest resolves paths against the manifest's folder and names options",
          "[batch][manifest]") {
  const fs::path manifest = write_manifest(
      "paths",
      "{\"id\": \"a\", \"garment\": \"g.obj\", \"avatar\": \"/abs/a.obj\", "
      "\"no_fit\": \"sub/n.txt\", \"skirt\": true, \"w_fit\": 10, \"quality\": "
      "\"fast\", \"shape-check\": \"off\"}\n\n"
      "{\"id\": \"b.2\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"skirt\": false}\n");
  const std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest.string());
  REQUIRE(jobs.size() == 2);
  const fs::path folder = manifest.parent_path();
  CHECK(jobs[0].id == "a");
  CHECK(jobs[0].line == 1);
  CHECK(jobs[1].line == 3);
  const nlohmann::json expected = {{"avatar", "/abs/a.obj"},
                                   {"garment", (folder / "g.obj").string()},
                                   {"no_fit", (folder / "sub/n.txt").string()},
                                   {"quality", "fast"},
                                   {"shape-check", "off"},
                                   {"skirt", true},
                                   {"w-fit", 10},
                                   {"out", "."},
                                   {"write-in-place", true},
                                   {"threads", 2}};
  CHECK(gr::job_options(jobs[0], 2) == expected);
  // A flag set to false is left out: the job is the same as without it.
  CHECK(jobs[1].options.empty());
}

TEST_CASE("read_manifest rejects malformed jobs with the manifest line", "[batch][manifest]") {
  const auto error = [](const std::string& name, const std::string& text) {
    const std::string message = error_of(name, text);
    CAPTURE(text, message);
    return message;
  };
  CHECK_THAT(error("not_json", "{\"id\": \"a\",\n"),
             Catch::Contains(":1:") && Catch::Contains("not a JSON object"));
  CHECK_THAT(error("no_id", "{\"garment\": \"g\", \"avatar\": \"a\"}"), Catch::Contains("\"id\""));
  CHECK_THAT(error("bad_id", "{\"id\": \"../x\", \"garment\": \"g\", \"avatar\": \"a\"}"),
             Catch::Contains("\"id\""));
  CHECK_THAT(error("dot_id", "{\"id\": \".tmp\", \"garment\": \"g\", \"avatar\": \"a\"}"),
             Catch::Contains("\"id\""));
  CHECK_THAT(error("no_avatar", "{\"id\": \"a\", \"garment\": \"g\"}"),
             Catch::Contains("no \"avatar\""));
  CHECK_THAT(error("duplicate",
                   "{\"id\": \"a\", \"garment\": \"g\", \"avatar\": \"a\"}\n"
                   "{\"id\": \"a\", \"garment\": \"g\", \"avatar\": \"a\"}\n"),
             Catch::Contains(":2:") && Catch::Contains("duplicate id"));
  CHECK_THAT(
      error("reserved", "{\"id\": \"a\", \"garment\": \"g\", \"avatar\": \"a\", \"out\": \"x\"}"),
      Catch::Contains("set by the batch"));
  CHECK_THAT(
      error("array", "{\"id\": \"a\", \"garment\": \"g\", \"avatar\": \"a\", \"dhat\": [1]}"),
      Catch::Contains("a string, a number or a boolean"));
  CHECK_THAT(error("path_type", "{\"id\": \"a\", \"garment\": 3, \"avatar\": \"a\"}"),
             Catch::Contains("file path"));
  CHECK_THAT(error("empty", "\n\n"), Catch::Contains("no jobs"));
}

TEST_CASE("job_key follows the input bytes and the options, not the paths", "[batch][manifest]") {
  const fs::path dir = gr::test::fresh_temp_dir("manifest_key");
  std::ofstream(dir / "g.obj") << "v 0 0 0\n";
  std::ofstream(dir / "copy.obj") << "v 0 0 0\n";
  std::ofstream(dir / "a.obj") << "v 1 0 0\n";
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"a\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\"}\n"
         "{\"id\": \"b\", \"garment\": \"copy.obj\", \"avatar\": \"a.obj\"}\n"
         "{\"id\": \"c\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"w_fit\": 10}\n"
         "{\"id\": \"d\", \"garment\": \"a.obj\", \"avatar\": \"g.obj\"}\n";
  const std::vector<gr::BatchJob> jobs = gr::read_manifest((dir / "manifest.jsonl").string());
  const std::string key = gr::job_key(jobs[0]);
  CHECK(key.size() == 64);
  CHECK(gr::job_key(jobs[1]) == key);
  CHECK(gr::job_key(jobs[2]) != key);
  CHECK(gr::job_key(jobs[3]) != key);  // the same bytes under other roles
  std::ofstream(dir / "g.obj") << "v 0 0 1\n";
  CHECK(gr::job_key(jobs[0]) != key);
}

TEST_CASE("read_manifest keeps an outfit's garments in order, given as paths",
          "[batch][manifest][outfit]") {
  const fs::path manifest = write_manifest(
      "outfit_paths",
      "{\"id\": \"sleeves\", \"garments\": [\"outer.obj\", \"inner.obj\", \"/abs/middle.obj\"], "
      "\"avatar\": \"a.obj\", \"quality\": \"fast\"}\n");
  const std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest.string());
  REQUIRE(jobs.size() == 1);
  const fs::path folder = manifest.parent_path();
  using Inputs = std::vector<std::pair<std::string, std::string>>;
  CHECK(jobs[0].inputs == Inputs{{"avatar", (folder / "a.obj").string()},
                                 {"garment", (folder / "outer.obj").string()},
                                 {"garment", (folder / "inner.obj").string()},
                                 {"garment", "/abs/middle.obj"}});
  const nlohmann::json expected = {
      {"avatar", (folder / "a.obj").string()},
      {"garment",
       {(folder / "outer.obj").string(), (folder / "inner.obj").string(), "/abs/middle.obj"}},
      {"quality", "fast"},
      {"out", "."},
      {"write-in-place", true},
      {"threads", 1}};
  CHECK(gr::job_options(jobs[0], 1) == expected);
}

TEST_CASE("read_manifest gives each garment object's own files as arrays in the garments' order",
          "[batch][manifest][outfit]") {
  const fs::path manifest = write_manifest(
      "outfit_objects",
      "{\"id\": \"a\", \"avatar\": \"a.glb\", \"target_skeleton\": \"t.obj\", \"garments\": ["
      "{\"garment\": \"outfit.glb\", \"garment_mesh\": \"Shirt\", \"no_fit\": \"shirt.txt\", "
      "\"source_skeleton\": \"s1.obj\", \"source_body\": \"b1.obj\"}, "
      "{\"source_body\": \"b2.obj\", \"garment\": \"outfit.glb\", \"garment_mesh\": "
      "\"Trousers\", \"no_fit\": \"trousers.txt\", \"source_skeleton\": \"s2.obj\"}]}\n");
  const std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest.string());
  REQUIRE(jobs.size() == 1);
  const auto in = [&](const char* name) { return (manifest.parent_path() / name).string(); };
  const nlohmann::json options = gr::job_options(jobs[0], 2);
  CHECK(options["garment"] == nlohmann::json{in("outfit.glb"), in("outfit.glb")});
  CHECK(options["garment-mesh"] == nlohmann::json{"Shirt", "Trousers"});
  CHECK(options["no_fit"] == nlohmann::json{in("shirt.txt"), in("trousers.txt")});
  CHECK(options["source_skeleton"] == nlohmann::json{in("s1.obj"), in("s2.obj")});
  CHECK(options["source_body"] == nlohmann::json{in("b1.obj"), in("b2.obj")});
  CHECK(options["target_skeleton"] == in("t.obj"));  // given once: a text, not an array
  CHECK(options["avatar"] == in("a.glb"));
  // The mesh names are options; the files are inputs, keyed by their bytes.
  CHECK(jobs[0].options == nlohmann::json{{"garment-mesh", {"Shirt", "Trousers"}}});
  CHECK(jobs[0].inputs.size() == 10);
}

TEST_CASE("read_manifest names a garment object marked skirt in --skirt-layer",
          "[batch][manifest][outfit]") {
  const fs::path manifest =
      write_manifest("outfit_skirt",
                     "{\"id\": \"a\", \"avatar\": \"a.obj\", \"garments\": ["
                     "{\"skirt\": true, \"garment\": \"skirt.obj\"}, {\"garment\": \"coat.obj\", "
                     "\"skirt\": false}]}\n");
  const std::vector<gr::BatchJob> jobs = gr::read_manifest(manifest.string());
  REQUIRE(jobs.size() == 1);
  CHECK(jobs[0].options ==
        nlohmann::json{{"skirt-layer", (manifest.parent_path() / "skirt.obj").string()}});
}

TEST_CASE("read_manifest refuses malformed garments with the manifest line",
          "[batch][manifest][outfit]") {
  const std::string good = "{\"id\": \"ok\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\"}\n";
  const auto error = [&](const std::string& name, const std::string& garments) {
    const std::string message = error_of(
        name, good + "{\"id\": \"b\", \"avatar\": \"a.obj\", \"garments\": " + garments + "}\n");
    CAPTURE(garments, message);
    CHECK_THAT(message, Catch::Contains("manifest.jsonl:2:"));
    return message;
  };
  CHECK_THAT(error("garments_text", "\"x.obj\""),
             Catch::Contains("\"garments\" must be a non-empty array"));
  CHECK_THAT(error("garments_empty", "[]"),
             Catch::Contains("\"garments\" must be a non-empty array"));
  CHECK_THAT(error("garments_no_garment", "[\"g.obj\", {\"no_fit\": \"n.txt\"}]"),
             Catch::Contains("each of \"garments\" needs its \"garment\""));
  CHECK_THAT(error("garments_unknown_key", "[{\"garment\": \"g.obj\", \"colour\": \"red\"}]"),
             Catch::Contains("\"garments.colour\" is not a garment's own"));
  CHECK_THAT(error("garments_number", "[\"g.obj\", 3]"),
             Catch::Contains("\"garments\" must be a file path"));
  CHECK_THAT(error("garments_empty_path", "[{\"garment\": \"\"}]"),
             Catch::Contains("\"garments.garment\" must be a file path"));
  CHECK_THAT(error("garments_mesh_twice",
                   "[{\"garment\": \"o.glb\", \"garment_mesh\": \"A\"}], \"garment_mesh\": \"B\""),
             Catch::Contains("\"garment_mesh\" given twice"));
}

TEST_CASE("job_key follows the bytes and the order of every garment of an outfit",
          "[batch][manifest][outfit]") {
  const fs::path dir = gr::test::fresh_temp_dir("manifest_outfit_key");
  for (const char* name : {"inner.obj", "outer.obj", "a.obj"})
    std::ofstream(dir / name) << "v 0 0 0\n# " << name << "\n";
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"a\", \"garments\": [\"inner.obj\", \"outer.obj\"], \"avatar\": \"a.obj\"}\n"
         "{\"id\": \"b\", \"garments\": [\"outer.obj\", \"inner.obj\"], \"avatar\": \"a.obj\"}\n"
         "{\"id\": \"c\", \"garments\": [{\"garment\": \"inner.obj\"}, "
         "{\"garment\": \"outer.obj\"}], \"avatar\": \"a.obj\"}\n"
         "{\"id\": \"d\", \"garment\": \"inner.obj\", \"avatar\": \"a.obj\"}\n";
  const std::vector<gr::BatchJob> jobs = gr::read_manifest((dir / "manifest.jsonl").string());
  REQUIRE(jobs.size() == 4);
  const std::string key = gr::job_key(jobs[0]);
  CHECK(gr::job_key(jobs[1]) != key);  // the first garment's frame is the outfit's
  CHECK(gr::job_key(jobs[2]) == key);  // paths or objects: the same job
  CHECK(gr::job_key(jobs[3]) != key);  // without its second garment
  std::ofstream(dir / "outer.obj", std::ios::app) << "# edited\n";
  CHECK(gr::job_key(jobs[0]) != key);
}
