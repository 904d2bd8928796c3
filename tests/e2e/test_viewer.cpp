// preskin-viewer end to end, in a window on a virtual X server (Xvfb, started here on a free
// display) with the test device (lavapipe in CI) and Vulkan validation on:
//  - a scripted run (--frames N --screenshot) writes a screenshot that matches `preskin render`
//    of the same view and size within the golden tolerance (<= 5/255 per channel on >= 99.9% of
//    the pixels), and exits 0 with no validation message;
//  - the run-time shader compiler (the hot-reload path) renders the same image as the built-in
//    SPIR-V, and a shader with an error is reported while the last good pipelines keep running;
//  - bad input (a missing environment, unloadable files dropped on the window) is reported and
//    the viewer keeps running (it still renders and writes its screenshot);
//  - --help works without a display.
// Skips only when Xvfb is not installed (scripts/install-deps.sh installs it) or the viewer is
// not part of the build (PRESKIN_BUILD_VIEWER=OFF).
#include "support/Process.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <dlfcn.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

// Xlib's types and constants only (its functions are looked up at run time); last, since its
// macros (None, Bool, Status, ...) would clash with names in the headers above.
#include <X11/Xlib.h>

extern char** environ;

namespace preskin::test {

namespace {

namespace fs = std::filesystem;

#ifdef PRESKIN_VIEWER_PATH
constexpr const char* kViewerPath = PRESKIN_VIEWER_PATH;
#else
constexpr const char* kViewerPath = "";
#endif

std::optional<fs::path> findInPath(const std::string& name) {
    const char* path = std::getenv("PATH");
    std::stringstream dirs(path ? path : "/usr/bin:/bin");
    std::string dir;
    while (std::getline(dirs, dir, ':')) {
        const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
        if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    }
    return std::nullopt;
}

// An Xvfb server on a display number it picks itself (-displayfd), stopped on destruction.
class VirtualDisplay {
public:
    // Starts Xvfb; on failure returns null and says why in `why`.
    static std::unique_ptr<VirtualDisplay> start(const fs::path& xvfb, std::string& why) {
        int fds[2];
        if (::pipe(fds) != 0) {
            why = "pipe() failed";
            return nullptr;
        }
        const std::string fdText = std::to_string(fds[1]);
        std::vector<std::string> argStore{xvfb.string(), "-displayfd", fdText, "-screen", "0",
                                          "1024x768x24", "-nolisten",  "tcp",  "-noreset"};
        std::vector<char*> argv;
        for (std::string& a : argStore) argv.push_back(a.data());
        argv.push_back(nullptr);
        posix_spawn_file_actions_t actions;
        posix_spawn_file_actions_init(&actions);
        posix_spawn_file_actions_addclose(&actions, fds[0]);
        posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, "/dev/null", O_WRONLY, 0);
        pid_t pid = 0;
        const int spawned = posix_spawn(&pid, xvfb.c_str(), &actions, nullptr, argv.data(), environ);
        posix_spawn_file_actions_destroy(&actions);
        ::close(fds[1]);
        if (spawned != 0) {
            ::close(fds[0]);
            why = std::string("cannot start Xvfb: ") + std::strerror(spawned);
            return nullptr;
        }
        auto display = std::unique_ptr<VirtualDisplay>(new VirtualDisplay(pid));
        // Xvfb writes the display number followed by a newline once it accepts connections.
        std::string number;
        const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
        while (number.find('\n') == std::string::npos && std::chrono::steady_clock::now() < deadline) {
            pollfd p{fds[0], POLLIN, 0};
            if (::poll(&p, 1, 100) <= 0) continue;
            char buffer[32];
            const ssize_t n = ::read(fds[0], buffer, sizeof buffer);
            if (n <= 0) break;  // Xvfb exited without a display
            number.append(buffer, size_t(n));
        }
        ::close(fds[0]);
        const size_t end = number.find('\n');
        if (end == std::string::npos || end == 0) {
            why = "Xvfb did not report a display within 20 s";
            return nullptr;
        }
        display->display_ = ":" + number.substr(0, end);
        return display;
    }

    ~VirtualDisplay() {
        ::kill(pid_, SIGTERM);
        int status = 0;
        ::waitpid(pid_, &status, 0);
    }
    VirtualDisplay(const VirtualDisplay&) = delete;
    VirtualDisplay& operator=(const VirtualDisplay&) = delete;

    const std::string& display() const { return display_; }

private:
    explicit VirtualDisplay(pid_t pid) : pid_(pid) {}
    pid_t pid_;
    std::string display_;
};

// A minimal X client for driving the viewer's window like a user and a window manager would:
// find it by title, resize it, press keys and ask it to close. libX11 is loaded at run time
// (GLFW's X11 backend needs it anyway), so the test binary does not link it.
class XClient {
public:
    static std::unique_ptr<XClient> open(const std::string& displayName, std::string& why) {
        auto x = std::unique_ptr<XClient>(new XClient());
        x->lib_ = ::dlopen("libX11.so.6", RTLD_NOW | RTLD_LOCAL);
        if (!x->lib_) {
            why = "cannot load libX11.so.6";
            return nullptr;
        }
        bool ok = true;
        auto load = [&](auto& fn, const char* name) {
            fn = reinterpret_cast<std::remove_reference_t<decltype(fn)>>(::dlsym(x->lib_, name));
            ok = ok && fn;
        };
        load(x->openDisplay_, "XOpenDisplay");
        load(x->closeDisplay_, "XCloseDisplay");
        load(x->defaultRoot_, "XDefaultRootWindow");
        load(x->queryTree_, "XQueryTree");
        load(x->fetchName_, "XFetchName");
        load(x->free_, "XFree");
        load(x->resizeWindow_, "XResizeWindow");
        load(x->internAtom_, "XInternAtom");
        load(x->sendEvent_, "XSendEvent");
        load(x->sync_, "XSync");
        load(x->keysymToKeycode_, "XKeysymToKeycode");
        load(x->stringToKeysym_, "XStringToKeysym");
        if (!ok) {
            why = "libX11.so.6 lacks a function the test needs";
            return nullptr;
        }
        x->display_ = x->openDisplay_(displayName.c_str());
        if (!x->display_) {
            why = "cannot connect to " + displayName;
            return nullptr;
        }
        return x;
    }
    ~XClient() {
        if (display_) closeDisplay_(display_);
        if (lib_) ::dlclose(lib_);
    }
    XClient(const XClient&) = delete;
    XClient& operator=(const XClient&) = delete;

    // The top-level window titled `title`, or 0.
    unsigned long findWindow(const std::string& title) {
        Window root = defaultRoot_(display_), parent = 0, *children = nullptr;
        unsigned int count = 0;
        unsigned long found = 0;
        if (!queryTree_(display_, root, &root, &parent, &children, &count)) return 0;
        for (unsigned int i = 0; i < count && !found; ++i) {
            char* name = nullptr;
            if (fetchName_(display_, children[i], &name) && name) {
                if (title == name) found = children[i];
                free_(name);
            }
        }
        if (children) free_(children);
        return found;
    }
    void resize(unsigned long window, unsigned width, unsigned height) {
        resizeWindow_(display_, window, width, height);
        sync_(display_, False);
    }
    // Presses and, `holdMs` later, releases a key (by X keysym name, e.g. "v", "F12").
    void tapKey(unsigned long window, const char* keysymName, int holdMs) {
        XEvent event{};
        XKeyEvent& key = event.xkey;
        key.display = display_;
        key.window = window;
        key.root = defaultRoot_(display_);
        key.same_screen = True;
        key.keycode = keysymToKeycode_(display_, stringToKeysym_(keysymName));
        key.type = KeyPress;
        sendEvent_(display_, window, True, KeyPressMask, &event);
        sync_(display_, False);
        std::this_thread::sleep_for(std::chrono::milliseconds(holdMs));
        key.type = KeyRelease;
        sendEvent_(display_, window, True, KeyReleaseMask, &event);
        sync_(display_, False);
    }
    // What a window manager sends when the user closes the window.
    void requestClose(unsigned long window) {
        XEvent event{};
        event.xclient.type = ClientMessage;
        event.xclient.window = window;
        event.xclient.message_type = internAtom_(display_, "WM_PROTOCOLS", False);
        event.xclient.format = 32;
        event.xclient.data.l[0] = long(internAtom_(display_, "WM_DELETE_WINDOW", False));
        event.xclient.data.l[1] = CurrentTime;
        sendEvent_(display_, window, False, NoEventMask, &event);
        sync_(display_, False);
    }

private:
    XClient() = default;

    void* lib_ = nullptr;
    Display* display_ = nullptr;
    decltype(&XOpenDisplay) openDisplay_ = nullptr;
    decltype(&XCloseDisplay) closeDisplay_ = nullptr;
    decltype(&XDefaultRootWindow) defaultRoot_ = nullptr;
    decltype(&XQueryTree) queryTree_ = nullptr;
    decltype(&XFetchName) fetchName_ = nullptr;
    decltype(&XFree) free_ = nullptr;
    decltype(&XResizeWindow) resizeWindow_ = nullptr;
    decltype(&XInternAtom) internAtom_ = nullptr;
    decltype(&XSendEvent) sendEvent_ = nullptr;
    decltype(&XSync) sync_ = nullptr;
    decltype(&XKeysymToKeycode) keysymToKeycode_ = nullptr;
    decltype(&XStringToKeysym) stringToKeysym_ = nullptr;
};

struct Rgba8 {
    int width = 0;
    int height = 0;
    std::vector<unsigned char> pixels;  // RGBA
};

std::optional<Rgba8> readPng(const fs::path& path) {
    auto in = OIIO::ImageInput::open(path.string());
    if (!in) return std::nullopt;
    const OIIO::ImageSpec& spec = in->spec();
    Rgba8 image;
    image.width = spec.width;
    image.height = spec.height;
    image.pixels.assign(size_t(spec.width) * size_t(spec.height) * 4, 255);
    const int channels = std::min(spec.nchannels, 4);
    if (!in->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, image.pixels.data(), 4)) return std::nullopt;
    return image;
}

// Fraction of pixels where some channel differs by more than `tolerance` (out of 255).
double differingFraction(const Rgba8& a, const Rgba8& b, int tolerance) {
    size_t differing = 0;
    for (size_t i = 0; i < a.pixels.size(); i += 4)
        for (size_t c = 0; c < 4; ++c)
            if (std::abs(int(a.pixels[i + c]) - int(b.pixels[i + c])) > tolerance) {
                ++differing;
                break;
            }
    return double(differing) / double(a.pixels.size() / 4);
}

bool mentionsValidation(const ProcessResult& r) {
    return r.out.find("validation") != std::string::npos || r.err.find("validation") != std::string::npos;
}

class Viewer : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        if (!*kViewerPath || !fs::exists(kViewerPath)) return;
        const auto xvfb = findInPath("Xvfb");
        if (!xvfb) return;
        display_ = VirtualDisplay::start(*xvfb, startError_).release();
    }
    static void TearDownTestSuite() {
        delete display_;
        display_ = nullptr;
    }

    void SetUp() override {
        if (!*kViewerPath || !fs::exists(kViewerPath))
            GTEST_SKIP() << "preskin-viewer is not built (PRESKIN_BUILD_VIEWER=OFF)";
        std::ostringstream name;
        name << "preskin_viewer_" << ::getpid() << "_"
             << ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path() / name.str();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }
    void TearDown() override {
        std::error_code ec;
        if (!HasFailure()) fs::remove_all(dir_, ec);
    }

    // Skips when Xvfb is not installed; fails when it is but does not start.
    void requireDisplay() {
        if (!findInPath("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (scripts/install-deps.sh installs xvfb)";
        ASSERT_NE(display_, nullptr) << "Xvfb is installed but did not start: " << startError_;
    }

    ProcessResult viewer(const std::vector<std::string>& args, const std::vector<std::string>& env = {}) {
        std::vector<std::string> fullEnv{"DISPLAY=" + (display_ ? display_->display() : std::string())};
        fullEnv.insert(fullEnv.end(), env.begin(), env.end());
        return runProcess(kViewerPath, args, fullEnv, dir_, 120.0);
    }

    ProcessResult headlessRender(const fs::path& out, int width, int height, const std::vector<std::string>& extra) {
        std::vector<std::string> args{"render",
                                      "--out",
                                      out.string(),
                                      "--width",
                                      std::to_string(width),
                                      "--height",
                                      std::to_string(height),
                                      "--device",
                                      testDevice(),
                                      "--validation"};
        args.insert(args.end(), extra.begin(), extra.end());
        return preskin::test::runCli(args, dir_, 120.0);
    }

    static std::string describe(const ProcessResult& r) {
        return "exit " + std::to_string(r.exitCode) + (r.timedOut ? " (timed out)" : "") + "\nstdout:\n" + r.out +
            "\nstderr:\n" + r.err;
    }

    // `extra`: more `preskin render` options for the same setup as the viewer's.
    void expectMatchesHeadless(const fs::path& screenshot, int width, int height,
                               const std::vector<std::string>& extra = {}) {
        const fs::path reference = dir_ / "headless.png";
        const ProcessResult cli = headlessRender(reference, width, height, extra);
        ASSERT_EQ(cli.exitCode, 0) << describe(cli);
        const auto a = readPng(screenshot);
        const auto b = readPng(reference);
        ASSERT_TRUE(a) << "cannot read " << screenshot;
        ASSERT_TRUE(b) << "cannot read " << reference;
        ASSERT_EQ(a->width, width);
        ASSERT_EQ(a->height, height);
        ASSERT_EQ(b->width, width);
        ASSERT_EQ(b->height, height);
        // Not trivially equal: the head covers a good part of the frame (the background is flat).
        size_t unlike = 0;
        for (size_t i = 0; i < a->pixels.size(); i += 4)
            unlike += std::abs(int(a->pixels[i]) - int(a->pixels[0])) > 20 ? 1 : 0;
        EXPECT_GT(double(unlike) / double(width * height), 0.1) << "the screenshot shows (almost) no scene";
        const double fraction = differingFraction(*a, *b, 5);
        EXPECT_LE(fraction, 0.001) << fraction * 100.0 << "% of the pixels differ by more than 5/255 (kept in " << dir_
                                   << ")";
    }

    static VirtualDisplay* display_;
    static std::string startError_;
    fs::path dir_;
};

VirtualDisplay* Viewer::display_ = nullptr;
std::string Viewer::startError_;

constexpr int kWidth = 200;
constexpr int kHeight = 150;

std::vector<std::string> scriptedArgs(const fs::path& screenshot, int frames) {
    return {"--width",  std::to_string(kWidth), "--height",     std::to_string(kHeight),
            "--frames", std::to_string(frames), "--screenshot", screenshot.string(),
            "--device", testDevice(),           "--validation", "--no-shader-reload"};
}

TEST_F(Viewer, ScreenshotMatchesHeadlessRender) {
    requireDisplay();
    const fs::path shot = dir_ / "viewer.png";
    const ProcessResult r = viewer(scriptedArgs(shot, 6));
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    EXPECT_NE(r.out.find("screenshot written"), std::string::npos) << describe(r);
    EXPECT_NE(r.out.find("frames at 200x150"), std::string::npos) << describe(r);
    ASSERT_TRUE(fs::exists(shot)) << describe(r);
    expectMatchesHeadless(shot, kWidth, kHeight);
}

// The side-by-side stereo preview with MSAA is the headless stereo render (eyes side by side) of
// the same camera, IPD and sample count.
TEST_F(Viewer, StereoPreviewMatchesHeadlessStereoRender) {
    requireDisplay();
    const fs::path shot = dir_ / "stereo.png";
    std::vector<std::string> args = scriptedArgs(shot, 4);
    args.insert(args.end(), {"--stereo", "--ipd", "0.08", "--msaa", "4"});
    const ProcessResult r = viewer(args);
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    const fs::path reference = dir_ / "headless.png";
    const ProcessResult cli =
        headlessRender(reference, kWidth / 2, kHeight, {"--stereo", "--ipd", "0.08", "--msaa", "4"});
    ASSERT_EQ(cli.exitCode, 0) << describe(cli);
    const auto a = readPng(shot);
    const auto b = readPng(reference);
    ASSERT_TRUE(a && b);
    ASSERT_EQ(a->width, kWidth);
    ASSERT_EQ(b->width, kWidth);
    ASSERT_EQ(a->height, b->height);
    const double fraction = differingFraction(*a, *b, 5);
    EXPECT_LE(fraction, 0.001) << fraction * 100.0 << "% of the pixels differ by more than 5/255 (kept in " << dir_
                               << ")";
    // The halves are two different eyes of one head.
    size_t lit = 0, unlike = 0;
    for (int y = 0; y < kHeight; ++y)
        for (int x = 0; x < kWidth / 2; ++x) {
            const size_t l = (size_t(y) * kWidth + size_t(x)) * 4;
            const size_t rr = l + size_t(kWidth / 2) * 4;
            lit += std::abs(int(a->pixels[l]) - int(a->pixels[0])) > 20;
            unlike += std::abs(int(a->pixels[l]) - int(a->pixels[rr])) > 10;
        }
    EXPECT_GT(lit, size_t(kWidth / 2 * kHeight / 10));
    EXPECT_GT(unlike, 50u);
}

// An animation started at a time (--animation, --time) poses the scene as `preskin render` does.
TEST_F(Viewer, AnimatedSceneMatchesHeadlessRenderAtTheSameTime) {
    requireDisplay();
    const std::string tube = std::string(PRESKIN_SOURCE_DIR) + "/samples/assets/tube/tube.gltf";
    const fs::path shot = dir_ / "tube.png";
    std::vector<std::string> args = scriptedArgs(shot, 3);
    args.insert(args.begin(), tube);
    args.insert(args.end(), {"--animation", "bend", "--time", "0.8"});
    const ProcessResult r = viewer(args);
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    const fs::path reference = dir_ / "headless.png";
    const ProcessResult cli =
        headlessRender(reference, kWidth, kHeight, {tube, "--animation", "bend", "--time", "0.8"});
    ASSERT_EQ(cli.exitCode, 0) << describe(cli);
    const fs::path rest = dir_ / "rest.png";
    ASSERT_EQ(headlessRender(rest, kWidth, kHeight, {tube}).exitCode, 0);
    const auto a = readPng(shot);
    const auto b = readPng(reference);
    const auto c = readPng(rest);
    ASSERT_TRUE(a && b && c);
    EXPECT_LE(differingFraction(*a, *b, 5), 0.001);
    EXPECT_GT(differingFraction(*b, *c, 5), 0.01) << "the bend should show";
}

TEST_F(Viewer, RunTimeCompiledShadersRenderLikeBuiltIn) {
    requireDisplay();
    const fs::path shot = dir_ / "compiled.png";
    std::vector<std::string> args = scriptedArgs(shot, 3);
    args.push_back("--compile-shaders");
    const ProcessResult r = viewer(args, {std::string("PRESKIN_DATA_DIR=") + PRESKIN_SOURCE_DIR});
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_NE(r.out.find("shaders reloaded"), std::string::npos) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    expectMatchesHeadless(shot, kWidth, kHeight);
}

TEST_F(Viewer, ShaderErrorIsReportedAndLastGoodPipelinesKeepRunning) {
    requireDisplay();
    // A copy of the shader sources whose forward pass does not compile.
    const fs::path data = dir_ / "data";
    fs::create_directories(data);
    fs::copy(fs::path(PRESKIN_SOURCE_DIR) / "shaders", data / "shaders", fs::copy_options::recursive);
    {
        std::ofstream broken(data / "shaders" / "forward.frag", std::ios::app);
        broken << "\nthis line is not GLSL;\n";
    }
    const fs::path shot = dir_ / "broken.png";
    std::vector<std::string> args = scriptedArgs(shot, 3);
    args.insert(args.begin(), (fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head.gltf").string());
    args.insert(args.end(), {"--compile-shaders", "--luts", (fs::path(PRESKIN_SOURCE_DIR) / "luts").string()});
    const ProcessResult r = viewer(args, {"PRESKIN_DATA_DIR=" + data.string()});
    EXPECT_EQ(r.exitCode, 1) << "a scripted run with an error exits 1\n" << describe(r);
    EXPECT_NE(r.err.find("did not compile; the last good pipelines keep running"), std::string::npos) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    ASSERT_TRUE(fs::exists(shot)) << describe(r);
    expectMatchesHeadless(shot, kWidth, kHeight);  // still the built-in shaders
}

TEST_F(Viewer, EditedShaderFilesReloadAndABrokenEditKeepsTheLastGoodPipelines) {
    requireDisplay();
    std::string why;
    const auto x = XClient::open(display_->display(), why);
    ASSERT_TRUE(x) << why;
    const fs::path data = dir_ / "data";
    fs::create_directories(data);
    fs::copy(fs::path(PRESKIN_SOURCE_DIR) / "shaders", data / "shaders", fs::copy_options::recursive);
    Process process(kViewerPath,
                    {(fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head.gltf").string(), "--luts",
                     (fs::path(PRESKIN_SOURCE_DIR) / "luts").string(), "--width", "160", "--height", "120", "--device",
                     testDevice(), "--validation"},
                    {"DISPLAY=" + display_->display(), "PRESKIN_DATA_DIR=" + data.string()}, dir_);
    ASSERT_TRUE(process.waitForOutput("first frame drawn", 60.0)) << describe(process.wait(10.0));
    // An edit of an include file that still compiles: every entry point is rebuilt and swapped in.
    std::ofstream(data / "shaders" / "preskin" / "brdf.glsl", std::ios::app) << "\n// edited while running\n";
    EXPECT_TRUE(process.waitForOutput("shaders reloaded (preskin/brdf.glsl)", 30.0)) << process.output();
    // An edit that does not compile: reported, the last good pipelines keep drawing.
    std::ofstream(data / "shaders" / "forward.frag", std::ios::app) << "\nthis line is not GLSL;\n";
    EXPECT_TRUE(process.waitForOutput("did not compile; the last good pipelines keep running", 30.0))
        << process.errors();
    std::this_thread::sleep_for(std::chrono::milliseconds(300));  // a few more frames
    const unsigned long window = x->findWindow("preskin-viewer");
    ASSERT_NE(window, 0ul);
    x->requestClose(window);
    const ProcessResult r = process.wait(60.0);
    EXPECT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
}

TEST_F(Viewer, BadInputIsReportedAndViewerKeepsRunning) {
    requireDisplay();
    const fs::path notes = dir_ / "notes.txt";
    std::ofstream(notes) << "not a scene\n";
    const fs::path shot = dir_ / "bad.png";
    std::vector<std::string> args = scriptedArgs(shot, 3);
    args.insert(args.end(),
                {"--screenshot-ui", "--env", (dir_ / "missing.hdr").string(), "--drop",
                 (fs::path(PRESKIN_SOURCE_DIR) / "tests/data/gltf/truncated.glb").string(), "--drop", notes.string(),
                 "--drop", (dir_ / "missing.exr").string()});
    const ProcessResult r = viewer(args);
    EXPECT_EQ(r.exitCode, 1) << "a scripted run with an error exits 1\n" << describe(r);
    EXPECT_NE(r.err.find("environment not loaded"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("scene not loaded, keeping the current one"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("truncated.glb"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("notes.txt: not a scene"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("missing.exr"), std::string::npos) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    EXPECT_TRUE(readPng(shot)) << "the viewer kept running and rendered (with its panels)\n" << describe(r);
}

// Files dropped together (or given as --drop, repeatable) load one after another in their order:
// a scene, then an environment that replaces the one the scene brings.
TEST_F(Viewer, DroppedSceneAndEnvironmentLoadInTheirOrder) {
    requireDisplay();
    const fs::path shot = dir_ / "drops.png";
    const fs::path scene = fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/head/head_softbox.gltf";
    const fs::path sky = fs::path(PRESKIN_SOURCE_DIR) / "samples/assets/sky/sunny_sky_1k.hdr";
    std::vector<std::string> args = scriptedArgs(shot, 3);
    args.insert(args.end(), {"--drop", scene.string(), "--drop", sky.string()});
    const ProcessResult r = viewer(args);
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_EQ(r.err.find("still loading"), std::string::npos) << describe(r);
    const size_t sceneLoaded = r.out.find("head_softbox.gltf loaded");
    const size_t lastEnvironment = r.out.rfind("preskin-viewer: environment ");
    ASSERT_NE(sceneLoaded, std::string::npos) << describe(r);
    ASSERT_NE(lastEnvironment, std::string::npos) << describe(r);
    EXPECT_LT(sceneLoaded, lastEnvironment) << describe(r);
    const std::string skyLine = "preskin-viewer: environment " + sky.string();
    EXPECT_EQ(r.out.substr(lastEnvironment, skyLine.size()), skyLine)
        << "the dropped sky is the environment in the end\n"
        << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
}

// A scene that is not found is reported, and the log does not call the empty scene loaded.
TEST_F(Viewer, MissingSceneIsNotCalledLoaded) {
    requireDisplay();
    std::vector<std::string> args{(dir_ / "missing.gltf").string()};
    for (const std::string& a : scriptedArgs(dir_ / "missing.png", 2)) args.push_back(a);
    const ProcessResult r = viewer(args);
    EXPECT_EQ(r.exitCode, 1) << describe(r);
    EXPECT_NE(r.err.find("scene not loaded"), std::string::npos) << describe(r);
    EXPECT_NE(r.err.find("missing.gltf"), std::string::npos) << describe(r);
    EXPECT_EQ(r.out.find("(scene loaded)"), std::string::npos) << describe(r);
    EXPECT_NE(r.out.find("renderer built (empty scene: the scene was not loaded)"), std::string::npos) << describe(r);
}

TEST_F(Viewer, LiveBurleyBakeMatchesBakedLutFiles) {
    requireDisplay();
    const std::string albedo = "0.8,0.5,0.35";
    const std::string mfp = "1.0,0.4,0.2";
    const fs::path luts = dir_ / "burley_luts";
    const ProcessResult bake = runProcess(
        PRESKIN_CLI_PATH, {"bake", "--profile", "burley", "--albedo", albedo, "--mfp", mfp, "--out", luts.string()}, {},
        dir_, 120.0);
    ASSERT_EQ(bake.exitCode, 0) << describe(bake);
    const fs::path shot = dir_ / "burley.png";
    std::vector<std::string> args = scriptedArgs(shot, 2);
    args.insert(args.end(), {"--profile", "burley", "--albedo", albedo, "--mfp", mfp});
    const ProcessResult r = viewer(args);
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_NE(r.out.find("LUTs Christensen & Burley"), std::string::npos) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    expectMatchesHeadless(shot, kWidth, kHeight, {"--luts", luts.string()});
}

// An MSAA count the device does not offer is refused at start, naming --msaa and what is offered,
// instead of a window that never draws.
TEST_F(Viewer, MsaaTheDeviceDoesNotOfferIsRefusedAtStart) {
    requireDisplay();
    if (testDevice() != "llvmpipe") GTEST_SKIP() << "lavapipe offers 1 and 4 samples; other devices differ";
    const fs::path shot = dir_ / "msaa.png";
    std::vector<std::string> args = scriptedArgs(shot, 2);
    args.insert(args.end(), {"--msaa", "2"});
    const ProcessResult r = viewer(args);
    EXPECT_EQ(r.exitCode, 1) << describe(r);
    EXPECT_NE(r.err.find("preskin: error: --msaa: value: 2 samples are not offered by llvmpipe"), std::string::npos)
        << describe(r);
    EXPECT_NE(r.err.find("(offered: 1, 4)"), std::string::npos) << describe(r);
    EXPECT_FALSE(fs::exists(shot));
}

TEST_F(Viewer, HelpListsTheScriptedOptions) {
    const ProcessResult r = runProcess(kViewerPath, {"--help"}, {}, dir_, 30.0);
    EXPECT_EQ(r.exitCode, 0) << describe(r);
    for (const char* option : {"--frames", "--screenshot", "--env", "--no-vsync", "--drop", "--validation"})
        EXPECT_NE(r.out.find(option), std::string::npos) << option << "\n" << describe(r);
}

TEST_F(Viewer, SurvivesResizeVsyncToggleScreenshotKeyAndClose) {
    requireDisplay();
    std::string why;
    const auto x = XClient::open(display_->display(), why);
    ASSERT_TRUE(x) << why;
    const fs::path shot = dir_ / "closed.png";
    Process process(kViewerPath,
                    {"--width", "200", "--height", "150", "--screenshot", shot.string(), "--device", testDevice(),
                     "--validation", "--no-shader-reload"},
                    {"DISPLAY=" + display_->display()}, dir_);
    // The first frame pays for pipeline creation; later ones at this size take milliseconds.
    ASSERT_TRUE(process.waitForOutput("first frame drawn", 60.0)) << describe(process.wait(10.0));
    const unsigned long window = x->findWindow("preskin-viewer");
    ASSERT_NE(window, 0ul) << "no viewer window\n" << describe(process.wait(10.0));
    // Each step is held long enough for several frames, so the viewer sees every state.
    const auto settle = [] { std::this_thread::sleep_for(std::chrono::milliseconds(500)); };
    settle();
    x->tapKey(window, "v", 500);  // vsync off
    settle();
    x->resize(window, 320, 200);
    settle();
    x->resize(window, 1, 1);
    settle();
    x->resize(window, 90, 300);
    settle();
    x->tapKey(window, "F12", 500);  // the screenshot key
    settle();
    x->resize(window, 160, 120);
    settle();
    x->tapKey(window, "v", 500);  // vsync on again
    settle();
    x->requestClose(window);
    const ProcessResult r = process.wait(60.0);
    ASSERT_EQ(r.exitCode, 0) << describe(r);
    EXPECT_FALSE(mentionsValidation(r)) << describe(r);
    const bool vsyncOff = r.out.find("present mode: MAILBOX") != std::string::npos ||
        r.out.find("present mode: IMMEDIATE") != std::string::npos;
    EXPECT_TRUE(vsyncOff) << "V did not switch vsync off\n" << describe(r);
    EXPECT_NE(r.out.find("present mode: FIFO"), std::string::npos) << "V did not switch vsync on\n" << describe(r);
    // The screenshot key wrote a timestamped PNG into the working folder.
    std::optional<fs::path> keyShot;
    for (const auto& entry : fs::directory_iterator(dir_))
        if (entry.path().filename().string().rfind("preskin-viewer-", 0) == 0) keyShot = entry.path();
    ASSERT_TRUE(keyShot) << "F12 wrote no screenshot\n" << describe(r);
    EXPECT_TRUE(readPng(*keyShot)) << *keyShot;
    // The frame drawn at closing, at the last size, is the headless render of that size.
    ASSERT_TRUE(fs::exists(shot)) << describe(r);
    expectMatchesHeadless(shot, 160, 120);
}

}  // namespace

}  // namespace preskin::test
