// preskin: command-line front end of libpreskin (render, bake, bench, reference, compare).
#include "Commands.h"

#include <preskin/Error.h>

#include <fmt/core.h>

#include <cstdio>
#include <exception>

int main(int argc, char** argv) {
    CLI::App app{"preskin: pre-integrated skin shading for forward renderers"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Show help for every subcommand");
    preskin::cli::addRenderCommand(app);
    preskin::cli::addBakeCommand(app);
    preskin::cli::addBenchCommand(app);
    preskin::cli::addReferenceCommand(app);
    preskin::cli::addCompareCommand(app);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    } catch (const preskin::Error& e) {
        fmt::print(stderr, "preskin: error: {}\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        fmt::print(stderr, "preskin: internal error: {}\n", e.what());
        return 2;
    }
    return 0;
}
