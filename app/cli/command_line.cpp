#include <filesystem>

#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"

namespace gr {

std::string current_program_path() {
  std::error_code ec;
  const std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) throw OutputError("cannot find the running program's path: " + ec.message());
  return path.string();
}

std::unique_ptr<CLI::App> make_command_line(int& exit_code) {
  auto app = std::make_unique<CLI::App>(
      "garment-retarget: refit a garment onto another avatar and certify that the "
      "result intersects neither the avatar nor itself.");
  app->require_subcommand(1);
  app->set_version_flag("--version", "garment-retarget " GR_VERSION);
  add_retarget_command(*app, exit_code);
  add_validate_command(*app, exit_code);
  add_shrink_command(*app, exit_code);
  add_batch_command(*app, exit_code);
  add_run_job_command(*app, exit_code);
  return app;
}

}  // namespace gr
