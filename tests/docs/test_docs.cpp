// The documentation against the tools it documents, so that what a new user copies works:
//  - every command in a shell block of README.md and docs/*.md runs as written (at small image
//    sizes and few repetitions), in a scratch folder laid out like the repository root;
//  - every synopsis line names only options its command has;
//  - every option of `preskin --help-all` and `preskin-viewer --help` is explained somewhere in
//    the README or docs (not only in the generated docs/cli.md), and docs/cli.md is the tools'
//    own help;
//  - figures the README quotes from the code (the host sample's size) and docs/limits.md's
//    limits match the code.
#include "support/Process.h"

#include <preskin/Limits.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace preskin::test {
namespace {

namespace fs = std::filesystem;

const fs::path kSource = PRESKIN_SOURCE_DIR;

struct ShownCommand {
    std::string file;  // relative to the repository root
    int line = 0;
    std::string text;       // the command as shown, comment removed, continuation lines joined
    bool synopsis = false;  // a usage line ([optional] parts, a|b choices), not a command to run
};

std::vector<fs::path> documentationFiles() {
    std::vector<fs::path> files{kSource / "README.md"};
    for (const auto& entry : fs::directory_iterator(kSource / "docs"))
        if (entry.path().extension() == ".md") files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    return files;
}

std::string trim(const std::string& s) {
    const size_t a = s.find_first_not_of(" \t");
    if (a == std::string::npos) return {};
    return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

// A trailing "# comment" outside quotes (a '#' after whitespace).
std::string withoutComment(const std::string& line) {
    bool quoted = false;
    for (size_t i = 0; i < line.size(); ++i) {
        if (line[i] == '"') quoted = !quoted;
        if (!quoted && line[i] == '#' && i > 0 && (line[i - 1] == ' ' || line[i - 1] == '\t')) return line.substr(0, i);
    }
    return line;
}

std::vector<ShownCommand> shownCommands() {
    std::vector<ShownCommand> commands;
    for (const fs::path& file : documentationFiles()) {
        std::ifstream in(file);
        bool inShell = false;
        int number = 0;
        for (std::string line; std::getline(in, line);) {
            ++number;
            const std::string t = trim(line);
            if (t.rfind("```", 0) == 0) {
                inShell = !inShell && (t == "```sh" || t == "```bash");
                continue;
            }
            if (!inShell || t.empty()) continue;
            const std::string command = trim(withoutComment(line));
            const bool continuation = line.find_first_not_of(" \t") > 0 && !commands.empty() &&
                commands.back().file == fs::relative(file, kSource).string() && commands.back().synopsis && t[0] == '[';
            if (continuation || (t[0] == '-' && !commands.empty())) {
                commands.back().text += " " + command;
                continue;
            }
            ShownCommand c;
            c.file = fs::relative(file, kSource).string();
            c.line = number;
            c.text = command;
            c.synopsis = command.find('[') != std::string::npos ||
                std::regex_search(command, std::regex(R"(\s(deon\|burley|[A-Za-z]+\|[A-Za-z]+)\b)"));
            commands.push_back(c);
        }
    }
    return commands;
}

std::vector<std::string> words(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

// The help of `tool` (`preskin` or `preskin-viewer`), run as build/bin/TOOL from `dir`.
std::string helpText(const fs::path& dir, const std::string& tool, const std::string& flag) {
    // Through the shell, so that the usage line names build/bin/TOOL as docs/cli.md does.
    const ProcessResult r = runProcess("/bin/sh", {"-c", "build/bin/" + tool + " " + flag}, {}, dir, 60.0);
    EXPECT_EQ(r.exitCode, 0) << tool << " " << flag << ": " << r.err;
    return r.out;
}

// A scratch folder laid out like the repository root: the build, samples, scripts and LUTs are
// links, outputs (docs/ included) land in the folder itself.
class Docs : public ::testing::Test {
protected:
    void SetUp() override {
        dir_ = fs::temp_directory_path() /
            fmt::format("preskin_docs_{}_{}", ::getpid(),
                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "build");
        fs::create_directory_symlink(fs::path(PRESKIN_BINARY_DIR) / "bin", dir_ / "build" / "bin");
        for (const char* link : {"samples", "scripts", "luts", "shaders"})
            fs::create_directory_symlink(kSource / link, dir_ / link);
        fs::create_directories(dir_ / "docs");
        fs::create_directories(dir_ / "run");
    }
    void TearDown() override {
        std::error_code ec;
        fs::remove_all(dir_, ec);
    }
    bool viewerBuilt() const { return fs::exists(dir_ / "build" / "bin" / "preskin-viewer"); }

    fs::path dir_;
};

// Replaces the value of `option` (the word after it) or appends "option value".
void setOption(std::vector<std::string>& args, const std::string& option, const std::string& value) {
    for (size_t i = 0; i + 1 < args.size(); ++i) {
        if (args[i] == option) {
            args[i + 1] = value;
            return;
        }
    }
    args.push_back(option);
    args.push_back(value);
}

// The value after `option`, or "".
std::string optionValue(const std::vector<std::string>& args, const std::string& option) {
    for (size_t i = 0; i + 1 < args.size(); ++i)
        if (args[i] == option) return args[i + 1];
    return {};
}

// The sections of a `preskin bench` report: its top-level keys that hold measurements.
std::set<std::string> benchSections(const fs::path& report) {
    static const std::set<std::string> header = {
        "tool", "device",        "driver",       "software_device",  "scene",  "width", "height",
        "seed", "light_density", "scene_lights", "cluster_settings", "method", "goals", "elapsed_s"};
    std::set<std::string> out;
    const nlohmann::json j = nlohmann::json::parse(readFile(report), nullptr, false);
    if (!j.is_object()) return {"(not a JSON object)"};
    for (const auto& [key, value] : j.items())
        if (!header.count(key)) out.insert(key);
    return out;
}

std::string joined(const std::set<std::string>& words) {
    std::string out;
    for (const std::string& w : words) out += (out.empty() ? "" : ", ") + w;
    return out.empty() ? "(none)" : out;
}

std::string shellQuoted(const std::vector<std::string>& args) {
    std::string out;
    for (const std::string& a : args) out += (out.empty() ? "" : " ") + a;
    return out;
}

TEST_F(Docs, EveryShownCommandRunsAsWritten) {
    std::vector<std::string> failures;
    int ran = 0, skipped = 0, repeated = 0;
    std::set<std::string> ranLines;
    const bool haveXvfb = std::system("command -v xvfb-run >/dev/null 2>&1") == 0;
    for (const ShownCommand& c : shownCommands()) {
        if (c.synopsis) continue;
        std::vector<std::string> args = words(c.text);
        // The README's two commands (this test runs inside the second), the install, which
        // HostSample.* runs into a fresh prefix, and the GPU kit's run.sh, which GpuKit.* runs
        // from a kit it makes, are not rerun here.
        const bool kitRun = args[0].size() > 7 && args[0].compare(args[0].size() - 7, 7, "/run.sh") == 0;
        if (args[0].rfind("./scripts/", 0) == 0 || args[0] == "cmake" || kitRun) {
            ++skipped;
            continue;
        }
        // The scenes make-fidelity-scenes.py and make-area-light-scenes.py write: into the scratch folder.
        for (std::string& a : args)
            for (const char* folder : {"/tmp/checks", "/tmp/area"})
                if (a.rfind(folder, 0) == 0) a = std::string(folder + 5) + a.substr(std::strlen(folder));
        const bool xvfb = args[0] == "xvfb-run";
        if (xvfb) args.erase(args.begin(), std::find(args.begin(), args.end(), "build/bin/preskin-viewer"));
        const std::string tool = args[0];
        if (tool == "build/bin/preskin") {
            const std::string command = args.size() > 1 ? args[1] : "";
            // Small images and few frames: the commands are checked, not the figures.
            if (command == "render" || command == "compare" || command == "reference") {
                const bool stereo = std::find(args.begin(), args.end(), "--stereo") != args.end();
                setOption(args, "--width", stereo ? "16" : "24");
                setOption(args, "--height", "24");
                if (std::find(args.begin(), args.end(), "--trace-environment") != args.end())
                    setOption(args, "--trace-environment", "8");
            } else if (command == "bench") {
                for (const auto& [option, value] : {std::pair{"--width", "32"},
                                                    {"--height", "18"},
                                                    {"--vr-width", "16"},
                                                    {"--vr-height", "18"},
                                                    {"--reps", "1"},
                                                    {"--warmup", "0"},
                                                    {"--budget-s", "1"},
                                                    {"--skin-counts", "16"},
                                                    {"--profile-lut-size", "16"}})
                    setOption(args, option, value);
            }
        } else if (tool == "build/bin/preskin-viewer") {
            if (std::find(args.begin(), args.end(), "--help") == args.end()) {
                if (!viewerBuilt() || !haveXvfb) {
                    ++skipped;
                    continue;
                }
                setOption(args, "--width", "96");
                setOption(args, "--height", "64");
                setOption(args, "--frames", "2");
                args.insert(args.begin(), {"xvfb-run", "-a", "-s", "\"-screen 0 640x480x24\""});
            }
        } else if (tool == "python3") {
            if (args.size() < 2 ||
                (args[1] != "scripts/make-fidelity-scenes.py" && args[1] != "scripts/make-area-light-scenes.py")) {
                failures.push_back(fmt::format("{}:{}: not a command this test knows: {}", c.file, c.line, c.text));
                continue;
            }
        } else {
            failures.push_back(fmt::format("{}:{}: not a command this test knows: {}", c.file, c.line, c.text));
            continue;
        }
        const std::string line = shellQuoted(args);
        // A command shown in several places (as the small test sizes make it) runs once.
        if (!ranLines.insert(line).second) {
            ++repeated;
            continue;
        }
        const auto start = std::chrono::steady_clock::now();
        const ProcessResult r =
            runProcess("/bin/sh", {"-c", line}, {"XDG_CACHE_HOME=" + (dir_ / "cache").string()}, dir_, 300.0);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        ++ran;
        std::printf("[ docs     ] %s:%d: %s -> %d (%.1f s)\n", c.file.c_str(), c.line, line.c_str(), r.exitCode,
                    seconds);
        if (r.exitCode != 0) {
            const std::string err = r.err.size() > 400 ? r.err.substr(r.err.size() - 400) : r.err;
            failures.push_back(
                fmt::format("{}:{}: {}\n  ran: {}\n  exit {}: {}", c.file, c.line, c.text, line, r.exitCode, err));
        } else if (const std::string out = optionValue(args, "--out");
                   tool == "build/bin/preskin" && args[1] == "bench" && !out.empty() && fs::exists(kSource / out)) {
            // A bench that rewrites a committed report writes the same sections it holds.
            const std::set<std::string> wrote = benchSections(dir_ / out), committed = benchSections(kSource / out);
            if (wrote != committed)
                failures.push_back(fmt::format("{}:{}: {}\n  writes the sections {}; the committed {} holds {}", c.file,
                                               c.line, c.text, joined(wrote), out, joined(committed)));
        }
    }
    std::printf("[ docs     ] %d commands ran, %d repeated, %d not rerun here\n", ran, repeated, skipped);
    EXPECT_GT(ran, 20);
    for (const std::string& f : failures) ADD_FAILURE() << f;
}

TEST_F(Docs, EverySynopsisNamesOnlyOptionsOfItsCommand) {
    const std::string allHelp = helpText(dir_, "preskin", "--help-all");
    const std::string viewerHelp = viewerBuilt() ? helpText(dir_, "preskin-viewer", "--help") : std::string();
    // Each subcommand's own block of --help-all.
    auto commandHelp = [&](const std::string& command) {
        const size_t at = allHelp.find("\n" + command + "\n");
        if (at == std::string::npos) return std::string();
        const size_t next = allHelp.find("\n\n", at + 1);
        return allHelp.substr(at, next == std::string::npos ? std::string::npos : next - at);
    };
    int checked = 0;
    for (const ShownCommand& c : shownCommands()) {
        const std::vector<std::string> args = words(c.text);
        std::string help;
        if (args[0] == "build/bin/preskin" && args.size() > 1)
            help = args[1] == "--help-all" || args[1] == "--version" ? allHelp : commandHelp(args[1]);
        else if (args[0] == "build/bin/preskin-viewer")
            help = viewerHelp;
        else
            continue;
        if (help.empty()) {
            if (args[0] == "build/bin/preskin")
                ADD_FAILURE() << c.file << ":" << c.line << ": unknown command: " << c.text;
            continue;
        }
        for (const std::string& w : args) {
            std::smatch m;
            const size_t start = w.find_first_not_of("[|");
            if (start == std::string::npos) continue;
            const std::string word = w.substr(start);
            if (!std::regex_match(word, m, std::regex(R"((--[a-z][a-z0-9-]*).*)"))) continue;
            ++checked;
            EXPECT_TRUE(std::regex_search(help, std::regex(m[1].str() + R"((\s|,|=|$))")))
                << c.file << ":" << c.line << ": " << m[1] << " is not an option of: " << c.text;
        }
    }
    EXPECT_GT(checked, 50);
}

TEST_F(Docs, EveryOptionIsExplainedAndCliReferenceIsTheToolsOwnHelp) {
    const std::string allHelp = helpText(dir_, "preskin", "--help-all");
    const std::string viewerHelp = viewerBuilt() ? helpText(dir_, "preskin-viewer", "--help") : std::string();
    std::string prose;
    for (const fs::path& file : documentationFiles())
        if (file.filename() != "cli.md") prose += readFile(file);
    std::set<std::string> options;
    const std::regex option(R"(\s(--[a-z][a-z0-9-]*))");
    for (const std::string* help : {&allHelp, &viewerHelp})
        for (std::sregex_iterator it(help->begin(), help->end(), option), end; it != end; ++it)
            options.insert((*it)[1]);
    EXPECT_GT(options.size(), 60u);
    for (const std::string& o : options)
        EXPECT_TRUE(std::regex_search(prose, std::regex(o + R"(([^a-z0-9-]|$))")))
            << o << " appears in no page of the README or docs/ (docs/cli.md aside): say what it does";

    const std::string cli = readFile(kSource / "docs" / "cli.md");
    EXPECT_NE(cli.find("```text\n" + allHelp + "```"), std::string::npos)
        << "docs/cli.md is not `preskin --help-all`: run scripts/make-cli-docs.sh";
    if (viewerBuilt()) {
        EXPECT_NE(cli.find("```text\n" + viewerHelp + "```"), std::string::npos)
            << "docs/cli.md is not `preskin-viewer --help`: run scripts/make-cli-docs.sh";
    }
}

int lineCount(const fs::path& file) {
    const std::string text = readFile(file);
    return int(std::count(text.begin(), text.end(), '\n'));
}

TEST(DocsFigures, HostSampleSizeAndLimitsMatchTheCode) {
    const std::string readme = readFile(kSource / "README.md");
    std::smatch m;
    ASSERT_TRUE(std::regex_search(
        readme, m,
        std::regex(
            R"(The host example is (\d+) lines: `main.cpp` (\d+) .*`Gpu.h` (\d+) .*`host.frag` (\d+), `host.vert` (\d+) and `CMakeLists.txt` (\d+))")))
        << "README no longer states the host example's size";
    const fs::path host = kSource / "samples" / "host";
    const int main = lineCount(host / "main.cpp"), gpu = lineCount(host / "Gpu.h"),
              frag = lineCount(host / "host.frag"), vert = lineCount(host / "host.vert"),
              cmake = lineCount(host / "CMakeLists.txt");
    EXPECT_EQ(std::stoi(m[2]), main);
    EXPECT_EQ(std::stoi(m[3]), gpu);
    EXPECT_EQ(std::stoi(m[4]), frag);
    EXPECT_EQ(std::stoi(m[5]), vert);
    EXPECT_EQ(std::stoi(m[6]), cmake);
    EXPECT_EQ(std::stoi(m[1]), main + gpu + frag + vert + cmake);

    // docs/limits.md states each limit of <preskin/Limits.h> with its value.
    const std::string limitsDoc = readFile(kSource / "docs" / "limits.md");
    auto withCommas = [](uint64_t v) {
        const std::string digits = std::to_string(v);
        std::string out;
        for (size_t i = 0; i < digits.size(); ++i) {
            if (i > 0 && (digits.size() - i) % 3 == 0) out += ',';
            out += digits[i];
        }
        return out;
    };
    for (const auto& [what, value] : {std::pair{"vertices of the scene", limits::kMaxSceneVertices},
                                      {"elements of one accessor", limits::kMaxSceneIndices},
                                      {"triangle-list indices of the scene", limits::kMaxSceneIndices},
                                      {"mesh primitives in the file", limits::kMaxScenePrimitives},
                                      {"drawn triangles", limits::kMaxDrawnTriangles},
                                      {"pixels of one texture", limits::kMaxImagePixels},
                                      {"pixels of all textures of a scene", limits::kMaxSceneImagePixels}}) {
        const size_t row = limitsDoc.find(std::string("| ") + what);
        ASSERT_NE(row, std::string::npos) << what;
        const std::string line = limitsDoc.substr(row, limitsDoc.find('\n', row) - row);
        EXPECT_NE(line.find(withCommas(value)), std::string::npos)
            << line << " (Limits.h: " << withCommas(value) << ")";
    }
    EXPECT_NE(limitsDoc.find("at most " + withCommas(limits::kMaxImageSide) + " per side"), std::string::npos);
}

// The README's listing of the shortest host shader is samples/host/host.frag, character for
// character (the file is what HostSample.* builds and runs).
TEST(DocsFigures, ReadmeHostShaderIsTheSamplesOwn) {
    const std::string readme = readFile(kSource / "README.md");
    const size_t section = readme.find("### Skin in your own forward shader");
    ASSERT_NE(section, std::string::npos);
    const size_t begin = readme.find("```glsl\n", section);
    ASSERT_NE(begin, std::string::npos);
    const size_t end = readme.find("```\n", begin + 8);
    ASSERT_NE(end, std::string::npos);
    EXPECT_EQ(readme.substr(begin + 8, end - begin - 8), readFile(kSource / "samples" / "host" / "host.frag"));
}

// The skin frame's cost as the README and docs/skin-cost.md quote it is the generated figure:
// each quality tier's instructions over the standard frame's from docs/skin-cost-table.md
// (scripts/skin-cost.sh), skin over standard in wall time from docs/bench-lavapipe.json (preskin
// bench). A page that types its own figure, or keeps an old one, fails here.
TEST(DocsFigures, SkinCostFiguresAreTheGeneratedOnes) {
    const std::string table = readFile(kSource / "docs" / "skin-cost-table.md");
    // "| high (every technique) | 1743.3 | 1.69 | ..." in the table's tier section.
    std::map<std::string, std::string> ratio;
    static const std::regex row(R"(\n\| (high|medium|low)[^|]*\| [0-9.]+ \| ([0-9.]+) )");
    for (auto it = std::sregex_iterator(table.begin(), table.end(), row); it != std::sregex_iterator(); ++it)
        ratio[(*it)[1]] = (*it)[2];
    ASSERT_EQ(ratio.size(), 3u) << "docs/skin-cost-table.md has no tier rows: run scripts/skin-cost.sh";
    const std::string tiers = fmt::format("high {}, medium {}, low {}", ratio["high"], ratio["medium"], ratio["low"]);
    const nlohmann::json bench = nlohmann::json::parse(readFile(kSource / "docs" / "bench-lavapipe.json"));
    std::string wall;
    for (const nlohmann::json& r : bench.at("skin_vs_standard"))
        wall += (wall.empty() ? "" : ", ") + fmt::format("{:.2f}", r.at("skin_over_standard").get<double>());
    const std::string readme = readFile(kSource / "README.md");
    EXPECT_NE(readme.find(tiers), std::string::npos) << "README.md should quote the table's tiers: " << tiers;
    EXPECT_NE(readFile(kSource / "docs" / "skin-cost.md").find(tiers), std::string::npos)
        << "docs/skin-cost.md should quote the table's tiers: " << tiers;
    EXPECT_NE(readme.find(wall + " in wall time"), std::string::npos)
        << "README.md should quote docs/bench-lavapipe.json's skin / standard: " << wall << " in wall time";
}

// The README's table of what each technique costs a host quotes docs/skin-cost-table.md's rows:
// each technique's instructions per frame and compare's error with it off (the "all" figure), the
// all-on error and specular IBL's cost.
TEST(DocsFigures, HostCostTableIsTheGeneratedOne) {
    const std::string table = readFile(kSource / "docs" / "skin-cost-table.md");
    const std::string readme = readFile(kSource / "README.md");
    auto tableRow = [&](const std::string& key) {
        const size_t at = table.find("(`" + key + "`) |");
        EXPECT_NE(at, std::string::npos) << key << " has no row in docs/skin-cost-table.md";
        if (at == std::string::npos) return std::vector<std::string>{};
        const size_t begin = table.rfind('\n', at) + 1;
        std::vector<std::string> cells;
        std::istringstream line(table.substr(begin, table.find('\n', at) - begin));
        for (std::string cell; std::getline(line, cell, '|');) {
            const size_t a = cell.find_first_not_of(' '), b = cell.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
        }
        return cells;  // "", name, M, share, wall, cpu, forward, fidelity, per view
    };
    int rows = 0;
    for (const char* key : {"lut_diffuse", "normal_prefilter", "normal_map_levels", "penumbra", "wide_penumbra",
                            "lut_shadow_light", "lut_other_lights", "light_curvature", "full_shadow_filter",
                            "sh_ambient", "transmission", "opposing_light", "dual_specular"}) {
        const std::vector<std::string> cells = tableRow(key);
        if (cells.size() < 8) continue;
        const std::string fidelity = cells[7].substr(0, cells[7].find(' '));
        const size_t at = readme.find(std::string("(`") + key + "`; `--");
        ASSERT_NE(at, std::string::npos) << "README.md's host cost table has no row for " << key;
        const std::string line = readme.substr(at, readme.find('\n', at) - at);
        EXPECT_NE(line.find("| " + cells[2] + " |"), std::string::npos) << line << " (table: " << cells[2] << " M)";
        if (!fidelity.empty()) {  // the specular rows buy nothing compare measures
            EXPECT_NE(line.find("| " + fidelity + " |"), std::string::npos) << line << " (table: " << fidelity << ")";
        }
        ++rows;
    }
    EXPECT_EQ(rows, 13);
    const std::vector<std::string> ibl = tableRow("specular_ibl");
    if (ibl.size() > 2) {
        EXPECT_NE(readme.find("environment (" + ibl[2] + " M)"), std::string::npos) << ibl[2];
    }
    const size_t all = table.find("| skin frame, all techniques on |");
    ASSERT_NE(all, std::string::npos);
    static const std::regex allOn(R"(\| skin frame, all techniques on \| [0-9.]+ \| [0-9]+% \|[ |]*([0-9.]+) /)");
    std::smatch m;
    const std::string allLine = table.substr(all, table.find('\n', all) - all);
    ASSERT_TRUE(std::regex_search(allLine, m, allOn)) << allLine;
    EXPECT_NE(readme.find(std::string(m[1]) + " with all on"), std::string::npos) << m[1];
}

}  // namespace
}  // namespace preskin::test
