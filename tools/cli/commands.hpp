#pragma once

#include <CLI/CLI.hpp>

namespace gr {

/// Each subcommand registers itself on the root app; its callback stores the exit code.
void add_retarget_command(CLI::App& root, int& exit_code);
void add_validate_command(CLI::App& root, int& exit_code);
void add_shrink_command(CLI::App& root, int& exit_code);

}  // namespace gr
