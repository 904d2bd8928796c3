// preskin-viewer's command line (see ViewerOptions.h).
#include "ViewerOptions.h"
#include "CommandLine.h"  // samples/common

namespace preskin::viewer {

void addViewerOptions(CLI::App& app, ViewerOptions& o) {
    app.add_option("scene", o.scene, "glTF scene (.gltf or .glb); default: the bundled head scene");
    app.add_option("--width", o.widthPx, "Window width in pixels")
        ->capture_default_str()
        ->check(cli::wholeNumberIn(64, 16384));
    app.add_option("--height", o.heightPx, "Window height in pixels")
        ->capture_default_str()
        ->check(cli::wholeNumberIn(64, 16384));
    app.add_flag("--no-vsync", o.noVsync, "Present without waiting for vertical blank (MAILBOX or IMMEDIATE)");
    auto* camera = app.add_option("--camera", o.camera, "Start with the scene's camera of this name");
    auto* orbit = app.add_option("--orbit", o.orbit,
                                 "Start orbiting at YAW,PITCH,DIST in degrees, degrees, metres (DIST 0: fit)");
    camera->excludes(orbit);
    app.add_option("--frames", o.frames,
                   "Scripted run: draw this many frames (and on until loads, bakes and shader builds are done), "
                   "then exit (0: run until closed)")
        ->check(cli::wholeNumberIn(0, 1 << 24));
    app.add_option("--screenshot", o.screenshot,
                   "Write the last frame as PNG, without the panels: the last of --frames, else the one drawn when "
                   "the window closes");
    app.add_flag("--screenshot-ui", o.screenshotUi, "The screenshot includes the panels");
    app.add_flag("--hide-ui", o.hideUi, "Start with the panels hidden (F1 shows them)");
    app.add_flag("--no-shader-reload", o.noShaderReload,
                 "Do not watch shaders/ for changes (F5 and the panel still reload on request)");
    app.add_flag("--compile-shaders", o.compileShaders,
                 "Compile shaders/ from source at start and use them, as a hot reload does");
    app.add_option("--drop", o.drops, "Load this file at start as if it was dropped on the window (repeatable)");
    app.add_option("--profile", o.profile,
                   "Diffusion profile baked at start (in the background, as the panel does): deon or burley; "
                   "default: the LUT set of --luts or the bundled one")
        ->check(cli::oneOf({"deon", "burley"}));
    app.add_option("--albedo", o.albedo, "burley: surface albedo per channel, R,G,B in (0, 1]")->capture_default_str();
    app.add_option("--mfp", o.mfp, "burley: mean free path per channel in mm, R,G,B")->capture_default_str();
    app.add_option("--lut-size", o.lutSize, "Samples along every LUT axis for --profile and the panel")
        ->capture_default_str()
        ->check(cli::oneOf({"64", "128", "256", "512"}));
    cli::addStereoOptions(app, o.stereo);
    app.add_option("--animation", o.animation, "Start with this animation (name or index)");
    app.add_option("--time", o.timeS, "Start at this time of the animation, seconds")->check(cli::numberIn(-1e6, 1e6));
    app.add_flag("--play", o.play, "Start playing the animation");
    cli::addCommonOptions(app, o.common);
}

}  // namespace preskin::viewer
