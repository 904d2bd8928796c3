// preskin: command-line front end of libpreskin (render, bake, bake-curvature, bench, reference, compare).
#include "CommandLine.h"  // samples/common
#include "Commands.h"

#include <preskin/imageio/ImageIo.h>

int main(int argc, char** argv) {
    preskin::imageio::registerCodecs();  // EXR and TIFF in, EXR out
    CLI::App app{"preskin: pre-integrated skin shading for forward renderers"};
    app.require_subcommand(1);
    app.set_help_all_flag("--help-all", "Show help for every subcommand");
    preskin::cli::addRenderCommand(app);
    preskin::cli::addBakeCommand(app);
    preskin::cli::addBakeCurvatureCommand(app);
    preskin::cli::addBenchCommand(app);
    preskin::cli::addReferenceCommand(app);
    preskin::cli::addCompareCommand(app);
    // Every failure, command-line parsing included: one line "preskin: error: ...", exit 1.
    return preskin::cli::runCommandLine(app, argc, argv);
}
