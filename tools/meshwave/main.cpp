// meshwave: the command-line tool of the meshwave codec.
#include <CLI/CLI.hpp>
#include <spdlog/spdlog.h>

#include "commands.h"

int main(int argc, char** argv) {
  CLI::App app{
      "meshwave: progressive wavelet coding of semi-regular triangle meshes"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "meshwave 0.1.0");
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "Log what each step does")
      ->configurable(false);
  app.parse_complete_callback([&] {
    spdlog::set_level(verbose ? spdlog::level::debug : spdlog::level::warn);
  });

  int exit_code = 0;
  meshwave::cli::AddInfoCommand(app, exit_code);
  meshwave::cli::AddCompareCommand(app, exit_code);
  meshwave::cli::AddSubdivideCommand(app, exit_code);
  meshwave::cli::AddRemeshCommand(app, exit_code);
  meshwave::cli::AddEncodeCommand(app, exit_code);
  meshwave::cli::AddDecodeCommand(app, exit_code);
  meshwave::cli::AddRdCommand(app, exit_code);
  meshwave::cli::AddRegionCommand(app, exit_code);
  meshwave::cli::AddViewCommand(app, exit_code);
  meshwave::cli::AddFetchCommand(app, exit_code);
  meshwave::cli::AddRefineCommand(app, exit_code);
  meshwave::cli::AddCatalogCommand(app, exit_code);
  meshwave::cli::AddAnalyzeCommand(app, exit_code);
  meshwave::cli::AddRenderCommand(app, exit_code);
  meshwave::cli::AddRenderCompareCommand(app, exit_code);

  CLI11_PARSE(app, argc, argv);
  return exit_code;
}
