#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>

#include "core/common/errors.hpp"
#include "retarget/run/output_folder.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using namespace gr;

namespace {

void write_text(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), {}};
}

/// Names in `folder` that start with `prefix`.
int count_starting_with(const fs::path& folder, const std::string& prefix) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(folder))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) ++count;
  return count;
}

/// A folder holding a complete earlier result.
fs::path earlier_result(const fs::path& root) {
  const fs::path dir = root / "result";
  fs::create_directories(dir);
  write_text(dir / "report.json", "{\"run\": \"earlier\"}\n");
  write_text(dir / "garment.obj", "earlier garment\n");
  return dir;
}

}  // namespace

TEST_CASE("A result folder appears whole at commit, and not before", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_fresh");
  const fs::path dir = root / "result";
  {
    ResultFolder folder(dir.string(), {});
    CHECK_FALSE(folder.has_previous());
    CHECK(fs::is_directory(folder.staging()));
    CHECK(folder.staging().parent_path() == root);
    CHECK(fs::exists(root / ".result.lock"));
    write_text(folder.staging() / "report.json", "{}\n");
    CHECK_FALSE(fs::exists(dir));
    folder.commit(false);
    CHECK(fs::is_regular_file(dir / "report.json"));
    CHECK(folder.final_path("report.json") == (dir / "report.json").string());
  }
  // Neither the staging folder nor the lock stays behind.
  CHECK(count_starting_with(root, ".result") == 0);
}

TEST_CASE("A result folder left without commit leaves DIR as it was", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_abort");
  const fs::path dir = earlier_result(root);
  {
    ResultFolder folder(dir.string(), {});
    CHECK(folder.has_previous());
    write_text(folder.staging() / "garment.obj", "half a garment");
  }
  CHECK(read_text(dir / "garment.obj") == "earlier garment\n");
  CHECK(count_starting_with(root, ".result") == 0);
}

TEST_CASE("A commit replaces an earlier result, or keeps it aside", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_replace");
  const fs::path dir = earlier_result(root);
  SECTION("removed after a certified run") {
    ResultFolder folder(dir.string(), {});
    write_text(folder.staging() / "report.json", "{\"run\": \"new\"}\n");
    folder.commit(false);
    CHECK(read_text(dir / "report.json") == "{\"run\": \"new\"}\n");
    CHECK_FALSE(fs::exists(dir / "garment.obj"));
    CHECK_FALSE(fs::exists(folder.previous_path()));
  }
  SECTION("kept at DIR.previous after a failed run") {
    ResultFolder folder(dir.string(), {});
    write_text(folder.staging() / "report.json", "{\"run\": \"failed\"}\n");
    folder.commit(true);
    CHECK(folder.previous_path() == (root / "result.previous").string());
    CHECK(read_text(dir / "report.json") == "{\"run\": \"failed\"}\n");
    CHECK_FALSE(fs::exists(dir / "garment.obj"));
    CHECK(read_text(root / "result.previous" / "garment.obj") == "earlier garment\n");
  }
  CHECK(count_starting_with(root, ".result") == 0);
}

TEST_CASE("A second run into a locked folder is refused", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_lock");
  const fs::path dir = root / "result";
  ResultFolder first(dir.string(), {});
  CHECK_THROWS_AS(ResultFolder(dir.string(), {}), OutputError);
  CHECK_THROWS_WITH(ResultFolder(dir.string(), {}),
                    Catch::Contains("another run is writing this folder"));
  // The refused run did not disturb the first one's staging folder.
  CHECK(fs::is_directory(first.staging()));
}

TEST_CASE("Staging folders of killed runs are removed by the next run", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_stale");
  const fs::path stale = root / ".result.tmp-12345-deadbeef";
  fs::create_directories(stale);
  write_text(stale / "garment.obj", "from a killed run");
  const fs::path other = root / ".other.tmp-1-2";  // another folder's staging: not ours
  fs::create_directories(other);
  ResultFolder folder((root / "result").string(), {});
  CHECK_FALSE(fs::exists(stale));
  CHECK(fs::exists(other));
}

TEST_CASE("A folder that is not a result, or holds an input, is refused", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_refused");
  SECTION("foreign files") {
    const fs::path dir = root / "documents";
    fs::create_directories(dir);
    write_text(dir / "notes.txt", "mine");
    CHECK_THROWS_WITH(ResultFolder(dir.string(), {}), Catch::Contains("not a result folder"));
    CHECK(read_text(dir / "notes.txt") == "mine");
  }
  SECTION("an empty folder is fine") {
    fs::create_directories(root / "empty");
    ResultFolder folder((root / "empty").string(), {});
    folder.commit(false);
    CHECK(fs::is_directory(root / "empty"));
  }
  SECTION("the input's own folder, with or without a result in it") {
    const fs::path dir = earlier_result(root);
    write_text(dir / "input.obj", "v 0 0 0\n");
    const std::string input = (dir / "input.obj").string();
    CHECK_THROWS_AS(ResultFolder(dir.string(), {input}), InputError);
    CHECK_THROWS_WITH(ResultFolder((root / "result/.").string(), {input}),
                      Catch::Contains("holds the input"));
    CHECK_THROWS_WITH(ResultFolder(root.string(), {input}), Catch::Contains("holds the input"));
    CHECK(read_text(dir / "input.obj") == "v 0 0 0\n");
  }
  SECTION("a file where the folder should be") {
    write_text(root / "file", "x");
    CHECK_THROWS_WITH(ResultFolder((root / "file").string(), {}), Catch::Contains("not a folder"));
  }
}

TEST_CASE("In place, a result folder is the caller's own", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("result_folder_in_place");
  const fs::path dir = root / "job";
  fs::create_directories(dir);
  write_text(dir / "log.txt", "the caller's file");
  ResultFolder folder(dir.string(), {}, true);
  CHECK(folder.staging() == dir);
  folder.commit(false);
  CHECK(read_text(dir / "log.txt") == "the caller's file");
  CHECK(count_starting_with(root, ".job") == 0);
}

TEST_CASE("Staged files replace their targets together, or not at all", "[output][transaction]") {
  const fs::path root = test::fresh_temp_dir("staged_files");
  write_text(root / "report.json", "old report");
  write_text(root / "page.html", "old page");
  {
    StagedFiles outputs;
    write_text(outputs.stage((root / "report.json").string()), "new report");
    // The run fails before the page is written: nothing changes.
  }
  CHECK(read_text(root / "report.json") == "old report");
  CHECK(count_starting_with(root, ".report.json.staged") == 0);
  {
    StagedFiles outputs;
    write_text(outputs.stage((root / "report.json").string()), "new report");
    write_text(outputs.stage((root / "page.html").string()), "new page");
    CHECK(read_text(root / "page.html") == "old page");
    outputs.commit();
  }
  CHECK(read_text(root / "report.json") == "new report");
  CHECK(read_text(root / "page.html") == "new page");
  CHECK(count_starting_with(root, ".") == 0);
}
