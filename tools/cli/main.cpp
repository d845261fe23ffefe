#include <cstdio>
#include <exception>
#include <new>

#include <CLI/CLI.hpp>

#include "core/common/errors.hpp"
#include "tools/cli/commands.hpp"
#include "tools/cli/exit_codes.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "garment-retarget: refit a garment onto another avatar and certify that the "
      "result intersects neither the avatar nor itself."};
  app.require_subcommand(1);
  app.set_version_flag("--version", "garment-retarget " GR_VERSION);
  int exit_code = gr::kExitSuccess;
  gr::add_retarget_command(app, exit_code);
  gr::add_validate_command(app, exit_code);
  gr::add_shrink_command(app, exit_code);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "garment-retarget: error: %s (see --help)\n", e.what());
    return gr::kExitBadInput;
  } catch (const gr::InputError& e) {
    std::fprintf(stderr, "garment-retarget: error: %s\n", e.what());
    return gr::kExitBadInput;
  } catch (const gr::OutputError& e) {
    std::fprintf(stderr, "garment-retarget: error: %s\n", e.what());
    return gr::kExitOutputError;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "garment-retarget: error: out of memory\n");
    return gr::kExitInternalError;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "garment-retarget: internal error: %s\n", e.what());
    return gr::kExitInternalError;
  }
  return exit_code;
}
