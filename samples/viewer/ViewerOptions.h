// Command-line options of preskin-viewer: the shared sample options (environment, device,
// validation, skin toggles, debug view, lights, LUTs; samples/common/Options.h) plus the window,
// the starting view and the scripted mode (--frames N --screenshot FILE; --drop and
// --compile-shaders drive the drag-and-drop and hot-reload paths from scripts and tests).
// Limits: read once at start; the panels change the live state, not these values.
#pragma once

#include "Options.h"  // samples/common

#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace preskin::viewer {

struct ViewerOptions {
    std::string scene;  // default: the bundled head
    uint32_t widthPx = 1280;
    uint32_t heightPx = 720;
    bool noVsync = false;
    std::string camera;         // a glTF camera's name
    std::string orbit;          // YAW,PITCH,DIST (degrees, degrees, metres; DIST 0 fits)
    uint32_t frames = 0;        // > 0: draw this many frames, then exit
    std::string screenshot;     // from the last of `frames`; without frames, from a frame drawn at closing
    bool screenshotUi = false;  // the screenshot includes the panels
    bool hideUi = false;
    bool noShaderReload = false;
    bool compileShaders = false;                     // compile shaders/ at start, as a hot reload would
    std::vector<std::string> drops;                  // files loaded at start as if dropped on the window
    std::string profile;                             // "deon" or "burley": re-bake the LUTs at start, as the panel does
    std::string albedo = cli::kDefaultBurleyAlbedo;  // burley: R,G,B surface albedo
    std::string mfp = cli::kDefaultBurleyMfp;        // burley: R,G,B mean free path, mm
    int lutSize = 256;
    cli::StereoOptions stereo;  // --stereo starts the side-by-side preview, --eye shows one eye
    std::string animation;      // start with this animation (name or index) at --time
    std::optional<float> timeS;
    bool play = false;  // start playing it
    cli::CommonOptions common;
};

void addViewerOptions(CLI::App& app, ViewerOptions& options);

}  // namespace preskin::viewer
