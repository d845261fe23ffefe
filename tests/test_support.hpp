#pragma once

#include <filesystem>
#include <string>

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

/// A fresh, empty temporary folder for one test; per process, since CTest runs test
/// cases in parallel processes.
inline std::filesystem::path fresh_temp_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("gr_test_" + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace gr::test
