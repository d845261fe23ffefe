#pragma once

#include <filesystem>
#include <mutex>
#include <string>
#include <system_error>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>

namespace gr::test {

/// A file under ../shared/data; the test fails (not skips) when the data is absent.
inline std::string shared_data(const std::string& relative) {
  const std::filesystem::path path = std::filesystem::path(GR_SHARED_DATA_DIR) / relative;
  INFO("shared test data expected at " << path.string());
  REQUIRE(std::filesystem::exists(path));
  return path.string();
}

/// A file committed with the project, relative to the source root.
inline std::string project_file(const std::string& relative) {
  return (std::filesystem::path(GR_SOURCE_DIR) / relative).string();
}

/// Removes, when the test process ends, every folder that fresh_temp_dir made. CTest runs
/// each test case in a process of its own, so a test leaves nothing in the temporary folder
/// (a crash or a kill still can); a folder may be used until then, e.g. by a static run
/// shared between sections.
class TempDirCleaner {
 public:
  static TempDirCleaner& instance() {
    static TempDirCleaner cleaner;
    return cleaner;
  }
  void add(const std::filesystem::path& dir) {
    const std::lock_guard<std::mutex> lock(mutex_);
    dirs_.push_back(dir);
  }
  ~TempDirCleaner() {
    for (const auto& dir : dirs_) {
      std::error_code ignored;  // nothing useful to do about a folder that will not go
      std::filesystem::remove_all(dir, ignored);
    }
  }

 private:
  TempDirCleaner() = default;
  std::mutex mutex_;
  std::vector<std::filesystem::path> dirs_;
};

/// A fresh, empty temporary folder for one test; per process, since CTest runs test
/// cases in parallel processes. Removed with its contents when the process ends.
inline std::filesystem::path fresh_temp_dir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("gr_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  TempDirCleaner::instance().add(dir);
  return dir;
}

}  // namespace gr::test
