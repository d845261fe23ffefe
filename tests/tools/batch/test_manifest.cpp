#include <filesystem>
#include <fstream>

#include "core/common/errors.hpp"
#include "test_support.hpp"
#include "tools/batch/manifest.hpp"

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
