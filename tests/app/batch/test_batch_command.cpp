#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "garment/outfit_meshes.hpp"

namespace fs = std::filesystem;
using gr::test::lines_of;
using gr::test::read_text;
using gr::test::run_cli;

namespace {

/// The bundled scene as a certified job, and a job whose garment is missing.
fs::path write_dress_form_manifest(const fs::path& dir) {
  const std::string scene = gr::test::project_file("scenes/dress_form");
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"dress\", \"garment\": \"" << scene << "/garment.obj\", \"avatar\": \"" << scene
      << "/avatar.obj\", \"no_fit\": \"" << scene << "/no-fit.txt\", \"quality\": \"fast\"}\n"
      << "{\"id\": \"broken\", \"garment\": \"missing.obj\", \"avatar\": \"" << scene
      << "/avatar.obj\"}\n";
  return dir / "manifest.jsonl";
}

std::vector<std::string> summary_row(const fs::path& out, const std::string& id) {
  for (const std::string& line : lines_of(read_text(out / "summary.csv"))) {
    if (line.rfind(id + ",", 0) != 0) continue;
    std::vector<std::string> fields;
    std::stringstream stream(line);
    for (std::string field; std::getline(stream, field, ',');) fields.push_back(field);
    if (line.back() == ',') fields.emplace_back();  // getline drops an empty last field
    return fields;
  }
  return {};
}

}  // namespace

TEST_CASE("batch runs each job in its own folder, records failures and reuses certified results",
          "[batch][cli]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_dress_form");
  const fs::path manifest = write_dress_form_manifest(dir);
  const fs::path out = dir / "out";
  fs::create_directories(out / ".tmp-left-over-1");  // from a killed batch

  const gr::test::CliRun first =
      run_cli({"batch", manifest.string(), "--out", out.string(), "--workers", "2"}, "batch_first");
  INFO(first.out << first.err);
  CHECK(first.exit_code == 8);
  CHECK_THAT(first.out, Catch::Contains("2 jobs: 1 computed, 0 reused, 1 failed"));
  for (const auto& entry : fs::directory_iterator(out))
    CHECK(entry.path().filename().string().rfind(".tmp-", 0) != 0);

  const std::vector<std::string> dress = summary_row(out, "dress");
  REQUIRE(dress.size() == 13);
  CHECK(dress[1] == "certified");
  CHECK(dress[2] == "0");
  CHECK(dress[3] == "no");
  CHECK(std::stod(dress[5]) > 0.0);  // fit error mean
  CHECK(dress[11] == "certified");
  for (const char* file : {"garment.obj", "report.json", "certificate.json", "job.json", "log.txt"})
    CHECK(fs::is_regular_file(out / "dress" / file));
  const nlohmann::json record = nlohmann::json::parse(read_text(out / "dress" / "job.json"));
  CHECK(record["key"].get<std::string>().size() == 64);
  CHECK(record["options"] == nlohmann::json{{"quality", "fast"}});

  const std::vector<std::string> broken = summary_row(out, "broken");
  REQUIRE(broken.size() == 13);
  CHECK(broken[1] == "bad_input");
  CHECK(broken[2] == "2");
  CHECK(broken[11] == "none");
  CHECK_THAT(broken[12], Catch::Contains("missing.obj"));
  CHECK_THAT(read_text(out / "broken" / "log.txt"), Catch::Contains("missing.obj"));

  const std::string garment = read_text(out / "dress" / "garment.obj");
  const gr::test::CliRun second =
      run_cli({"batch", manifest.string(), "--out", out.string(), "--quiet"}, "batch_second");
  INFO(second.out << second.err);
  CHECK(second.exit_code == 8);
  CHECK_THAT(second.out, Catch::Contains("2 jobs: 0 computed, 1 reused, 1 failed"));
  CHECK(second.err.empty());
  CHECK(summary_row(out, "dress")[3] == "yes");
  CHECK(read_text(out / "dress" / "garment.obj") == garment);
  CHECK(nlohmann::json::parse(read_text(out / "dress" / "job.json")) == record);

  // Another option is another job: it runs again and its folder replaces the old one.
  std::string text = read_text(manifest);
  text.replace(text.find("\"quality\""), 0, "\"max_al_rounds\": 40, ");
  std::ofstream(manifest) << text;
  const gr::test::CliRun third =
      run_cli({"batch", manifest.string(), "--out", out.string(), "--quiet"}, "batch_third");
  INFO(third.out << third.err);
  CHECK_THAT(third.out, Catch::Contains("2 jobs: 1 computed, 0 reused, 1 failed"));
  CHECK(summary_row(out, "dress")[3] == "no");
  const nlohmann::json rerun = nlohmann::json::parse(read_text(out / "dress" / "job.json"));
  CHECK(rerun["key"] != record["key"]);
  CHECK(rerun["options"] == nlohmann::json{{"max-al-rounds", 40}, {"quality", "fast"}});
  for (const auto& entry : fs::directory_iterator(out))
    CHECK(entry.path().filename().string().rfind(".tmp-", 0) != 0);
}

TEST_CASE("batch refuses a manifest naming an option retarget does not have", "[batch][cli]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_bad_option");
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"a\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\"}\n"
      << "{\"id\": \"b\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"w_fitt\": 1}\n"
      << "{\"id\": \"c\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"skirt\": 1}\n";
  const gr::test::CliRun run =
      run_cli({"batch", (dir / "manifest.jsonl").string(), "--out", (dir / "out").string()},
              "batch_bad_option");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains("manifest.jsonl:2") &&
                          Catch::Contains("\"w-fitt\" is not a retarget option"));
  CHECK_FALSE(fs::exists(dir / "out" / "a"));
}

TEST_CASE("batch refuses a value its option does not take before any job runs", "[batch][cli]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_bad_knob");
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"a\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\"}\n"
      << "{\"id\": \"b\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"fit_samples\": 4}\n"
      << "{\"id\": \"c\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"quality\": \"best\"}\n";
  const gr::test::CliRun run =
      run_cli({"batch", (dir / "manifest.jsonl").string(), "--out", (dir / "out").string()},
              "batch_bad_knob");
  CHECK(run.exit_code == 2);
  CHECK_THAT(run.err, Catch::Contains("manifest.jsonl:2") &&
                          Catch::Contains("--fit-samples: must be 1, 3 or 6"));
  CHECK_FALSE(fs::exists(dir / "out" / "a"));
  // The first bad line stops the batch; the next one is refused on its own as well.
  std::ofstream(dir / "quality.jsonl")
      << "{\"id\": \"c\", \"garment\": \"g.obj\", \"avatar\": \"a.obj\", \"quality\": \"best\"}\n";
  const gr::test::CliRun quality =
      run_cli({"batch", (dir / "quality.jsonl").string(), "--out", (dir / "out").string()},
              "batch_bad_quality");
  CHECK(quality.exit_code == 2);
  CHECK_THAT(quality.err, Catch::Contains("quality.jsonl:1") && Catch::Contains("best"));
}

TEST_CASE("batch records a job whose process crashes and goes on", "[batch][cli]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_crash");
  const std::string scene = gr::test::project_file("scenes/dress_form");
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"a\", \"garment\": \"" << scene << "/garment.obj\", \"avatar\": \"" << scene
      << "/avatar.obj\"}\n"
      << "{\"id\": \"b\", \"garment\": \"" << scene << "/garment.obj\", \"avatar\": \"" << scene
      << "/avatar.obj\", \"quality\": \"fast\"}\n";
  // A stand-in for the program that dies of a signal, as a crashing job would.
  std::ofstream(dir / "crash.sh") << "#!/bin/sh\nkill -SEGV $$\n";
  fs::permissions(dir / "crash.sh", fs::perms::owner_all);
  const fs::path out = dir / "out";
  const gr::test::CliRun run = run_cli({"batch", (dir / "manifest.jsonl").string(), "--out",
                                        out.string(), "--program", (dir / "crash.sh").string()},
                                       "batch_crash");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 8);
  CHECK_THAT(run.out, Catch::Contains("2 jobs: 0 computed, 0 reused, 2 failed"));
  for (const char* id : {"a", "b"}) {
    const std::vector<std::string> row = summary_row(out, id);
    REQUIRE(row.size() == 13);
    CHECK(row[1] == "crashed");
    CHECK(row[2] == "-1");
    CHECK_THAT(row[12], Catch::Contains("killed by signal 11"));
  }
}

TEST_CASE("batch passes each job's limits to it", "[batch][cli][limits]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_limits");
  const std::string scene = gr::test::project_file("scenes/dress_form");
  const std::string inputs = "\"garment\": \"" + scene + "/garment.obj\", \"avatar\": \"" + scene +
                             "/avatar.obj\", \"no_fit\": \"" + scene + "/no-fit.txt\"";
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"late\", " << inputs << ", \"timeout\": 0.05}\n"
      << "{\"id\": \"large\", " << inputs << ", \"max_faces\": 100}\n"
      << "{\"id\": \"fine\", " << inputs << ", \"quality\": \"fast\", \"timeout\": 600}\n";
  const fs::path out = dir / "out";
  const gr::test::CliRun run = run_cli(
      {"batch", (dir / "manifest.jsonl").string(), "--out", out.string(), "--quiet"}, "limits");
  INFO(run.out << run.err);
  CHECK(run.exit_code == 8);
  CHECK(summary_row(out, "late")[1] == "limit_reached");
  CHECK(summary_row(out, "large")[1] == "bad_input");
  CHECK(summary_row(out, "fine")[1] == "certified");
  // The stopped job left its log and record, and no result of its own.
  CHECK(fs::is_regular_file(out / "late" / "job.json"));
  CHECK_FALSE(fs::exists(out / "late" / "garment.obj"));
}

TEST_CASE("batch runs an outfit job: one certified run over every garment",
          "[batch][cli][outfit]") {
  const fs::path dir = gr::test::fresh_temp_dir("batch_outfit");
  gr::test::write_nested_sleeves(dir);
  // Relative to the manifest, given out of order, each made on the same source body.
  std::ofstream(dir / "manifest.jsonl")
      << "{\"id\": \"sleeves\", \"avatar\": \"avatar.obj\", \"garments\": ["
         "{\"garment\": \"middle.obj\", \"source_body\": \"source_body.obj\"}, "
         "{\"garment\": \"outer.obj\", \"source_body\": \"source_body.obj\"}, "
         "{\"garment\": \"inner.obj\", \"source_body\": \"source_body.obj\"}], "
         "\"quality\": \"fast\", \"voxel_size\": 0.05, \"max_newton_iterations\": 300}\n";
  const fs::path out = dir / "out";
  const gr::test::CliRun run = run_cli({"batch", (dir / "manifest.jsonl").string(), "--out",
                                        out.string(), "--threads-per-job", "2", "--quiet"},
                                       "batch_outfit");
  INFO(run.out << run.err << read_text(out / "sleeves" / "log.txt"));
  CHECK(run.exit_code == 0);
  CHECK_THAT(run.out, Catch::Contains("1 jobs: 1 computed, 0 reused, 0 failed"));
  const std::vector<std::string> row = summary_row(out, "sleeves");
  REQUIRE(row.size() == 13);
  CHECK(row[1] == "certified");
  CHECK(row[11] == "certified");

  const fs::path job = out / "sleeves";
  const nlohmann::json report = nlohmann::json::parse(read_text(job / "report.json"));
  REQUIRE(report.contains("outfit"));
  const nlohmann::json& outfit = report["outfit"];
  REQUIRE(outfit["layers"].size() == 3);
  const std::vector<std::string> given = {"middle", "outer", "inner"};
  for (std::size_t k = 0; k < 3; ++k) {
    const nlohmann::json& layer = outfit["layers"][k];
    CAPTURE(k, layer.dump());
    CHECK(layer["name"] == given[k]);
    CHECK(layer["faces"] == 2 * 11 * 32);
    CHECK(layer["written"] == "./" + given[k] + ".obj");
    CHECK(fs::is_regular_file(job / (given[k] + ".obj")));
  }
  CHECK(outfit["order"] == nlohmann::json{"inner", "middle", "outer"});
  CHECK(outfit["order_from"] == "measured");
  CHECK(outfit["order_kept"] == true);
  CHECK(outfit["layer_intersections"] == 0);
  CHECK(outfit["hidden_avatar_faces"]["hidden"].get<int>() > 0);
  CHECK(fs::is_regular_file(job / "hidden-avatar-faces.txt"));
  CHECK_FALSE(fs::exists(job / "garment.obj"));
  const nlohmann::json certificate = nlohmann::json::parse(read_text(job / "certificate.json"));
  CHECK(certificate["certified"] == true);
  CHECK(certificate["garments"].size() == 3);
  CHECK(certificate["garment_pairs"].size() == 3);
  const nlohmann::json record = nlohmann::json::parse(read_text(job / "job.json"));
  CHECK(record["threads"] == 2);
  CHECK(record["status"] == "certified");
}
