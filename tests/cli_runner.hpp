#pragma once

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <sys/wait.h>

#include "test_support.hpp"

namespace gr::test {

/// What one run of the `garment-retarget` program printed and returned.
struct CliRun {
  int exit_code = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// An environment variable set for one run: name and value.
using EnvironmentVariable = std::pair<std::string, std::string>;

/// Runs the command-line program with `args` and, on top of the test's own environment,
/// `environment`, capturing stdout and stderr.
inline CliRun run_cli(const std::vector<std::string>& args, const std::string& capture_name,
                      const std::vector<EnvironmentVariable>& environment = {}) {
  const auto dir = fresh_temp_dir("cli_" + capture_name);
  std::string command;
  for (const auto& [name, value] : environment) command += name + "=" + shell_quote(value) + " ";
  command += shell_quote(GR_CLI_PATH);
  for (const auto& a : args) command += " " + shell_quote(a);
  command += " >" + shell_quote((dir / "out.txt").string()) + " 2>" +
             shell_quote((dir / "err.txt").string()) + " </dev/null";
  const int status = std::system(command.c_str());
  CliRun run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  run.out = read_text(dir / "out.txt");
  run.err = read_text(dir / "err.txt");
  return run;
}

/// Lines of a text, without the empty last one.
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

}  // namespace gr::test
