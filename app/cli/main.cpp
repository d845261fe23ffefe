#include <cstdio>
#include <exception>
#include <memory>
#include <new>

#include <CLI/CLI.hpp>

#include "app/cli/commands.hpp"
#include "core/common/errors.hpp"
#include "retarget/outcome.hpp"
#include "retarget/run/run_control.hpp"

int main(int argc, char** argv) {
  int exit_code = gr::to_exit_code(gr::Outcome::kCertified);
  const std::unique_ptr<CLI::App> command_line = gr::make_command_line(exit_code);
  CLI::App& app = *command_line;
  // Ctrl-C and SIGTERM end a run at its next check, with its staging folder removed.
  gr::stop_on_signals();

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
    return gr::to_exit_code(gr::Outcome::kBadInput);
  } catch (const gr::InputError& e) {
    std::fprintf(stderr, "garment-retarget: error: %s\n", e.what());
    return gr::to_exit_code(gr::Outcome::kBadInput);
  } catch (const gr::Interrupted& e) {
    return gr::report_stopped_run(e);
  } catch (const gr::OutputError& e) {
    std::fprintf(stderr, "garment-retarget: error: %s\n", e.what());
    return gr::to_exit_code(gr::Outcome::kOutputError);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "garment-retarget: error: out of memory\n");
    return gr::to_exit_code(gr::Outcome::kInternalError);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "garment-retarget: internal error: %s\n", e.what());
    return gr::to_exit_code(gr::Outcome::kInternalError);
  }
  return exit_code;
}
