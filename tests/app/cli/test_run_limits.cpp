#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Core>
#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "cli_runner.hpp"
#include "retarget/outcome.hpp"
#include "retarget/run/output_folder.hpp"
#include "test_support.hpp"
#include "validate/report/file_digest.hpp"

namespace fs = std::filesystem;
using gr::test::CliRun;

namespace {

std::string bundled(const std::string& name) {
  return gr::test::project_file("scenes/dress_form/" + name);
}

/// The bundled scene's retarget arguments into `out`, then `extra`.
std::vector<std::string> bundled_retarget(const fs::path& out,
                                          const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"retarget",
                                   "--garment",
                                   bundled("garment.obj"),
                                   "--avatar",
                                   bundled("avatar.obj"),
                                   "--no-fit",
                                   bundled("no-fit.txt"),
                                   "--out",
                                   out.string(),
                                   "--quality",
                                   "fast",
                                   "--threads",
                                   "1",
                                   "--quiet"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

nlohmann::json read_json(const fs::path& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

/// Copies the OBJ `from` to `to` with each vertex position changed by `move`.
void write_moved_copy(const std::string& from, const fs::path& to,
                      const std::function<void(Eigen::Vector3d&)>& move) {
  std::ifstream in(from);
  std::ofstream out(to);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("v ", 0) == 0) {
      Eigen::Vector3d v;
      std::sscanf(line.c_str(), "v %lf %lf %lf", &v.x(), &v.y(), &v.z());
      move(v);
      line = fmt::format("v {:.17g} {:.17g} {:.17g}", v.x(), v.y(), v.z());
    }
    out << line << '\n';
  }
}

/// One error line, naming `text`.
void check_one_error_line(const CliRun& run, const std::string& text) {
  CAPTURE(run.err);
  const auto lines = gr::test::lines_of(run.err);
  REQUIRE(lines.size() == 1);
  CHECK(lines.front().rfind("garment-retarget: error: ", 0) == 0);
  CHECK(lines.front().find(text) != std::string::npos);
}

/// Runs `args` and checks that they were refused as bad input: exit 2, one error line
/// naming `text`, and no folder at `out`.
void check_refused(const std::vector<std::string>& args, const fs::path& out,
                   const std::string& text) {
  const CliRun run = gr::test::run_cli(args, out.parent_path().filename().string());
  CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  check_one_error_line(run, text);
  CHECK_FALSE(fs::exists(out));
}

/// Runs the CLI and returns it with its wall time in seconds.
std::pair<CliRun, double> timed_run(const std::vector<std::string>& args, const std::string& name) {
  const auto start = std::chrono::steady_clock::now();
  CliRun run = gr::test::run_cli(args, name);
  return {run, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

TEST_CASE("Devices, FIFOs and oversized files are refused before they are read", "[cli][limits]") {
  const fs::path dir = gr::test::fresh_temp_dir("limits_files");
  const fs::path fifo = dir / "garment.fifo";
  REQUIRE(::mkfifo(fifo.c_str(), 0644) == 0);
  const fs::path sparse = dir / "huge.obj";
  {
    std::ofstream(sparse) << "v 0 0 0\n";
    fs::resize_file(sparse, 2ull << 30);  // 2 GiB, sparse
  }
  struct Case {
    std::string garment, expected;
  };
  const Case cases[] = {{"/dev/zero", "not a regular file"},
                        {fifo.string(), "not a regular file"},
                        {sparse.string(), "more than the 1024.0 MB allowed"},
                        {dir.string(), "is a folder"}};
  for (const Case& c : cases) {
    CAPTURE(c.garment);
    const fs::path out = dir / "out";
    auto args = bundled_retarget(out);
    args[2] = c.garment;
    const auto [run, seconds] = timed_run(args, "limits_files");
    CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
    check_one_error_line(run, c.expected);
    CHECK(seconds < 2.0);
    CHECK_FALSE(fs::exists(out));
  }
  // The same files given to validate.
  const auto [run, seconds] =
      timed_run({"validate", "--garment", fifo.string(), "--avatar", bundled("avatar.obj")},
                "limits_validate");
  CHECK(run.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  check_one_error_line(run, "not a regular file");
  CHECK(seconds < 2.0);
}

TEST_CASE("Face and memory limits refuse a scene before the solve", "[cli][limits]") {
  const fs::path out = gr::test::fresh_temp_dir("limits_faces") / "out";
  const CliRun faces = gr::test::run_cli(bundled_retarget(out, {"--max-faces", "100"}), "faces");
  CHECK(faces.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  check_one_error_line(faces, "more than --max-faces 100");
  const CliRun memory =
      gr::test::run_cli(bundled_retarget(out, {"--max-memory-mb", "10"}), "memory");
  CHECK(memory.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  check_one_error_line(memory, "more than --max-memory-mb 10");
  CHECK_FALSE(fs::exists(out));
}

TEST_CASE("A run past its timeout ends with exit 9 and writes nothing", "[cli][limits]") {
  const fs::path root = gr::test::fresh_temp_dir("limits_timeout");
  const fs::path out = root / "out";
  const CliRun fresh = gr::test::run_cli(bundled_retarget(out, {"--timeout", "0.05"}), "timeout");
  CHECK(fresh.exit_code == gr::to_exit_code(gr::Outcome::kLimitReached));
  check_one_error_line(fresh, "timed out after");
  CHECK_FALSE(fs::exists(out));

  // Over an earlier result: that result stays, whole.
  REQUIRE(gr::test::run_cli(bundled_retarget(out), "timeout_first").exit_code ==
          gr::to_exit_code(gr::Outcome::kCertified));
  const std::string digest = gr::sha256_of_file((out / "garment.obj").string());
  const CliRun again = gr::test::run_cli(bundled_retarget(out, {"--timeout", "0.05"}), "again");
  CHECK(again.exit_code == gr::to_exit_code(gr::Outcome::kLimitReached));
  CHECK(gr::sha256_of_file((out / "garment.obj").string()) == digest);
  CHECK(read_json(out / "certificate.json")["extra"]["output"]["sha256"] == digest);
  for (const auto& entry : fs::directory_iterator(root))
    CHECK(entry.path().filename().string().find(".tmp-") == std::string::npos);
}

TEST_CASE("A failed run keeps the earlier certified result aside", "[cli][transaction]") {
  const fs::path root = gr::test::fresh_temp_dir("failed_run_previous");
  const fs::path out = root / "out";
  REQUIRE(gr::test::run_cli(bundled_retarget(out), "previous_first").exit_code ==
          gr::to_exit_code(gr::Outcome::kCertified));
  const std::string digest = gr::sha256_of_file((out / "garment.obj").string());
  // One Newton step per round and one round cannot inflate the avatar.
  const CliRun failed = gr::test::run_cli(
      bundled_retarget(out, {"--max-al-rounds", "1", "--max-newton-iterations", "1"}), "failed");
  CAPTURE(failed.out, failed.err);
  REQUIRE(failed.exit_code == gr::to_exit_code(gr::Outcome::kSolverFailure));
  const nlohmann::json report = read_json(out / "report.json");
  CHECK(report["certified"] == false);
  CHECK(report["previous_result"] == (root / "out.previous").string());
  CHECK_FALSE(fs::exists(out / "garment.obj"));
  CHECK_FALSE(fs::exists(out / "certificate.json"));
  CHECK(gr::sha256_of_file((root / "out.previous" / "garment.obj").string()) == digest);
  CHECK(read_json(root / "out.previous" / "certificate.json")["certified"] == true);
}

TEST_CASE("An output folder that holds an input, or is locked, is refused", "[cli][transaction]") {
  const fs::path root = gr::test::fresh_temp_dir("out_refused");
  const fs::path scene = root / "scene";
  fs::create_directories(scene);
  for (const char* name : {"garment.obj", "avatar.obj", "no-fit.txt"})
    fs::copy_file(bundled(name), scene / name);
  std::vector<std::string> args = bundled_retarget(scene);
  args[2] = (scene / "garment.obj").string();
  const std::string before = gr::sha256_of_file((scene / "garment.obj").string());
  const CliRun over_input = gr::test::run_cli(args, "over_input");
  CHECK(over_input.exit_code == gr::to_exit_code(gr::Outcome::kBadInput));
  check_one_error_line(over_input, "holds the input");
  CHECK(gr::sha256_of_file((scene / "garment.obj").string()) == before);

  const fs::path out = root / "out";
  const gr::ResultFolder holder(out.string(), {});
  const CliRun locked = gr::test::run_cli(bundled_retarget(out), "locked");
  CHECK(locked.exit_code == gr::to_exit_code(gr::Outcome::kOutputError));
  check_one_error_line(locked, "another run is writing this folder");
}

TEST_CASE("An inferred no-fit list, even an empty one, is read back", "[cli][limits]") {
  const fs::path root = gr::test::fresh_temp_dir("no_fit_round_trip");
  std::vector<std::string> args = bundled_retarget(root / "first");
  args.erase(args.begin() + 5, args.begin() + 7);  // without --no-fit
  REQUIRE(gr::test::run_cli(args, "infer").exit_code == gr::to_exit_code(gr::Outcome::kCertified));
  const fs::path list = root / "first" / "no-fit.txt";
  REQUIRE(fs::is_regular_file(list));
  std::vector<std::string> again = bundled_retarget(root / "second");
  again[6] = list.string();
  const CliRun reread = gr::test::run_cli(again, "reread");
  CAPTURE(reread.err);
  CHECK(reread.exit_code == gr::to_exit_code(gr::Outcome::kCertified));

  std::ofstream(root / "empty-list.txt") << "# no-fit list inferred by garment-retarget\n";
  again = bundled_retarget(root / "third");
  again[6] = (root / "empty-list.txt").string();
  CHECK(gr::test::run_cli(again, "empty_list").exit_code ==
        gr::to_exit_code(gr::Outcome::kCertified));
}

TEST_CASE("A garment beside the avatar with no skeleton to place it is named, not retargeted",
          "[cli][limits]") {
  // The bundled garment moved four metres aside, two heights of the avatar: without
  // skeletons nothing could bring it onto the body.
  const fs::path root = gr::test::fresh_temp_dir("garment_beside_avatar");
  const fs::path garment = root / "garment.obj";
  write_moved_copy(bundled("garment.obj"), garment, [](Eigen::Vector3d& v) { v.x() += 4.0; });
  std::vector<std::string> args = bundled_retarget(root / "out");
  args[2] = garment.string();
  check_refused(args, root / "out", "lies further from the avatar's bounding box");
}

TEST_CASE("Garment and avatar sizes far apart are named, not retargeted", "[cli][limits]") {
  const fs::path root = gr::test::fresh_temp_dir("extreme_sizes");
  for (const double scale : {1e-9, 1e9}) {
    CAPTURE(scale);
    const fs::path avatar = root / fmt::format("avatar_{:g}.obj", scale);
    write_moved_copy(bundled("avatar.obj"), avatar, [&](Eigen::Vector3d& v) { v *= scale; });
    std::vector<std::string> args = bundled_retarget(root / "out");
    args[4] = avatar.string();
    check_refused(args, root / "out", "times the avatar's size");
  }
}

TEST_CASE("An avatar without the part under the garment is named, not retargeted",
          "[cli][limits]") {
  // The hair onto a body read without its head: nothing there to fit it to.
  const fs::path root = gr::test::fresh_temp_dir("avatar_without_head");
  const std::string hair = gr::test::shared_data("real/female-pose-standing.glb");
  const std::string avatar = gr::test::shared_data("real/female-full-body.glb");
  std::vector<std::string> args = {"retarget",
                                   "--garment",
                                   hair,
                                   "--garment-mesh",
                                   "Wolf3D_Hair.002",
                                   "--avatar",
                                   avatar,
                                   "--avatar-mesh",
                                   "body.001",
                                   "--out",
                                   (root / "out").string(),
                                   "--quiet"};
  check_refused(args, root / "out", "100% of the garment's area lies around bones the avatar has");
  // With its head, the hair is retargeted.
  args.insert(args.end(), {"--avatar-mesh", "head", "--quality", "fast"});
  const CliRun run = gr::test::run_cli(args, "avatar_with_head");
  CHECK(run.exit_code == 0);
  const nlohmann::json coverage = read_json(root / "out" / "report.json")["avatar_coverage"];
  CHECK(coverage["uncovered_share"].get<double>() < 0.1);
}

TEST_CASE("An avatar cut away under part of the garment is warned of, and retargeted",
          "[cli][limits]") {
  // The trousers onto a body cut away under its own dress, at the hips.
  const fs::path out = gr::test::fresh_temp_dir("avatar_cut_at_hips") / "out";
  const CliRun run = gr::test::run_cli(
      {"retarget", "--garment", gr::test::shared_data("real/male-outfit.glb"), "--garment-mesh",
       "Wolf3D_Outfit_Bottom", "--avatar", gr::test::shared_data("real/female-pose-standing.glb"),
       "--avatar-mesh", "Wolf3D_Body.002", "--out", out.string(), "--quality", "fast", "--quiet"},
      "avatar_cut_at_hips");
  CHECK(run.exit_code == 0);
  const nlohmann::json report = read_json(out / "report.json");
  const double share = report["avatar_coverage"]["uncovered_share"].get<double>();
  CHECK(share > 0.1);
  CHECK(share < 0.8);
  const auto bones = report["avatar_coverage"]["uncovered_bones"].get<std::vector<std::string>>();
  REQUIRE_FALSE(bones.empty());
  CHECK(bones.front().rfind("Hips-", 0) == 0);
  bool warned = false;
  for (const std::string& warning : report["warnings"].get<std::vector<std::string>>())
    warned = warned || warning.find("lies around bones the avatar has almost no surface around (" +
                                    bones.front()) != std::string::npos;
  CHECK(warned);
}
