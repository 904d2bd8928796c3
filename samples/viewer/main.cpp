// preskin-viewer: interactive viewer of glTF scenes with the pre-integrated skin renderer.
// Usage: preskin-viewer [scene.gltf] [--env FILE.hdr] [options]; --help lists them all.
// Scripted runs: --frames N --screenshot FILE.png draws N frames, writes the last one (without
// the panels unless --screenshot-ui) and exits: 0, 1 on an error, 2 on Vulkan validation messages.
// Limits: needs an X11 display (Debian's GLFW 3.3 build; Xvfb works) and a Vulkan 1.3 device
// that can present to it.
#include "Viewer.h"
#include "ViewerOptions.h"

#include "CommandLine.h"  // samples/common

#include <preskin/imageio/ImageIo.h>

#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
    preskin::imageio::registerCodecs();  // EXR environments and textures, EXR screenshots
    preskin::viewer::ViewerOptions options;
    CLI::App app{"preskin-viewer: interactive pre-integrated skin viewer (GLFW + Dear ImGui)"};
    app.footer(
        "Mouse: drag to orbit (or look, in fly mode), wheel to zoom. Keys: Tab orbit/fly, W/A/S/D/Q/E move, "
        "Home reset view, F12 or P screenshot, V vsync, F5 reload shaders, F1 panels. Drop .gltf/.glb/.hdr/.exr "
        "files onto the window to load them.");
    preskin::viewer::addViewerOptions(app, options);
    // A failure to parse or to start: one line "preskin: error: ...", exit 1. Problems while it
    // runs go to the Messages panel (and stderr); see Viewer::run for the exit status then.
    return preskin::cli::runCommandLine(app, argc, argv, [&options] {
        preskin::viewer::Viewer viewer(options);
        return viewer.run();
    });
}
