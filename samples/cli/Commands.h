// Subcommands of the `preskin` tool. Each adds itself to the app; its callback runs the command
// and throws preskin::Error on bad input (main prints it and exits non-zero).
#pragma once

#include <CLI/CLI.hpp>

namespace preskin::cli {

void addRenderCommand(CLI::App& app);
void addBakeCommand(CLI::App& app);
void addBakeCurvatureCommand(CLI::App& app);
void addBenchCommand(CLI::App& app);
void addReferenceCommand(CLI::App& app);
void addCompareCommand(CLI::App& app);

}  // namespace preskin::cli
