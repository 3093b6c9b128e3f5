// The subcommands of the `meshwave` CLI. Each Add*Command registers one
// subcommand on `app`; when it runs, it stores its exit status in `exit_code`
// (0 success, 1 failure with a message on stderr).
#ifndef MESHWAVE_TOOLS_COMMANDS_H_
#define MESHWAVE_TOOLS_COMMANDS_H_

#include <CLI/CLI.hpp>

namespace meshwave::cli {

void AddInfoCommand(CLI::App& app, int& exit_code);
void AddCompareCommand(CLI::App& app, int& exit_code);
void AddSubdivideCommand(CLI::App& app, int& exit_code);
void AddRemeshCommand(CLI::App& app, int& exit_code);
void AddEncodeCommand(CLI::App& app, int& exit_code);
void AddDecodeCommand(CLI::App& app, int& exit_code);
void AddRdCommand(CLI::App& app, int& exit_code);
void AddFetchCommand(CLI::App& app, int& exit_code);
void AddRefineCommand(CLI::App& app, int& exit_code);
void AddCatalogCommand(CLI::App& app, int& exit_code);
void AddAnalyzeCommand(CLI::App& app, int& exit_code);
void AddRenderCommand(CLI::App& app, int& exit_code);
void AddRenderCompareCommand(CLI::App& app, int& exit_code);
void AddRegionCommand(CLI::App& app, int& exit_code);
void AddViewCommand(CLI::App& app, int& exit_code);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_COMMANDS_H_
