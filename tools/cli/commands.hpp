#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace gr {

struct ScenePaths;

/// The options naming a scene's files: --garment, --avatar, --out (all required), and the
/// optional --source-skeleton / --target-skeleton pair and --skin-weights.
void add_scene_options(CLI::App& command, ScenePaths& inputs, std::string& out_dir);

/// Each subcommand registers itself on the root app; its callback stores the exit code.
void add_retarget_command(CLI::App& root, int& exit_code);
void add_validate_command(CLI::App& root, int& exit_code);
void add_shrink_command(CLI::App& root, int& exit_code);

}  // namespace gr
