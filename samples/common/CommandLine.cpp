// Command-line validation and error reporting of the sample programs (see CommandLine.h).
#include "CommandLine.h"

#include <preskin/Error.h>
#include <preskin/Limits.h>
#include <preskin/Version.h>

#include <fmt/core.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <new>
#include <system_error>
#include <vector>

namespace preskin::cli {

namespace {

// User text inside a message: one line, at most `limit` characters.
std::string shown(const std::string& text, size_t limit = 80) {
    std::string out;
    for (const char c : text) {
        if (out.size() >= limit) return out + "...";
        out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? '?' : c;
    }
    return out;
}

// A message for stderr on one line (a path may hold a line break).
std::string oneLine(const std::string& text) {
    std::string out;
    for (const char c : text) out += static_cast<unsigned char>(c) < 0x20 || c == 0x7f ? ' ' : c;
    return out;
}

std::string number(double value) {
    if (value == std::floor(value) && std::abs(value) < 1e15) return std::to_string(static_cast<int64_t>(value));
    char buffer[32];
    const auto [end, ec] = std::to_chars(buffer, buffer + sizeof(buffer), value);
    return ec == std::errc() ? std::string(buffer, end) : std::to_string(value);
}

std::string afterPrefix(const std::string& text, const std::string& prefix) {
    return text.rfind(prefix, 0) == 0 ? text.substr(prefix.size()) : std::string();
}

// Edits (insertions, deletions, substitutions, swaps of neighbours) from a to b.
size_t editDistance(const std::string& a, const std::string& b) {
    std::vector<std::vector<size_t>> d(a.size() + 1, std::vector<size_t>(b.size() + 1));
    for (size_t i = 0; i <= a.size(); ++i) d[i][0] = i;
    for (size_t j = 0; j <= b.size(); ++j) d[0][j] = j;
    for (size_t i = 1; i <= a.size(); ++i) {
        for (size_t j = 1; j <= b.size(); ++j) {
            d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] == b[j - 1] ? 0 : 1)});
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
                d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);
        }
    }
    return d[a.size()][b.size()];
}

// ", did you mean X?" for the candidate nearest to `word`, when it is near enough to be a typo.
std::string nearest(const std::string& word, const std::vector<std::string>& candidates) {
    std::string best;
    size_t bestDistance = std::max<size_t>(2, word.size() / 3) + 1;
    for (const std::string& c : candidates) {
        const size_t distance = editDistance(word, c);
        if (distance < bestDistance) {
            best = c;
            bestDistance = distance;
        }
    }
    return best.empty() || word.size() < 4 ? std::string() : ", did you mean " + best + "?";
}

bool looksLikeNumber(const std::string& text) {
    double value = 0.0;
    const auto [last, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    return ec == std::errc() && last != text.data();
}

std::vector<std::string> optionNames(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::Option* option : app.get_options()) {
        for (const std::string& n : option->get_lnames()) names.push_back("--" + n);
        for (const std::string& n : option->get_snames()) names.push_back("-" + n);
    }
    return names;
}

std::vector<std::string> commandNames(const CLI::App& app) {
    std::vector<std::string> names;
    for (const CLI::App* sub : app.get_subcommands({})) names.push_back(sub->get_name());
    return names;
}

// The first option on the command line that the command it is given to does not have, as
// "<option>: option: unknown ...", or "". CLI11 hands an unknown option to the positionals or
// reports a later argument (or a missing required option) instead, so this runs first.
std::string findUnknownOption(CLI::App& app, int argc, char** argv) {
    CLI::App* command = &app;
    const bool hasCommands = !app.get_subcommands({}).empty();
    for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg == "--") return {};
        if (arg.size() < 2 || arg[0] != '-' || looksLikeNumber(arg)) {
            if (command == &app && hasCommands) {
                CLI::App* sub = nullptr;
                for (CLI::App* candidate : app.get_subcommands({}))
                    if (candidate->check_name(arg)) sub = candidate;
                if (!sub) return {};  // CLI11 names the unknown command
                command = sub;
            }
            continue;
        }
        const size_t eq = arg.find('=');
        const std::string name = arg.substr(0, eq);
        const CLI::Option* option = command->get_option_no_throw(name);
        if (!option && command != &app) option = app.get_option_no_throw(name);
        if (!option) {
            std::vector<std::string> names = optionNames(*command);
            if (command != &app) {
                for (const std::string& n : optionNames(app)) names.push_back(n);
            }
            const std::string program = std::filesystem::path(argv[0]).filename().string();
            const std::string where = program + (command == &app ? "" : " " + command->get_name()) + " --help";
            return shown(name) + ": option: unknown" + nearest(name, names) + " (see " + where + ")";
        }
        // Skip the option's value: "--width 64" (a value may start with '-': "--env-rotation -30").
        if (eq == std::string::npos && option->get_type_size_max() > 0 && i + 1 < argc) ++i;
    }
    return {};
}

}  // namespace

CLI::Validator numberIn(double min, double max) {
    const std::string range = "[" + number(min) + ", " + number(max) + "]";
    return CLI::Validator(
        [min, max, range](std::string& text) -> std::string {
            double value = 0.0;
            const char* end = text.data() + text.size();
            const auto [last, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || last != end || !std::isfinite(value)) {
                return "value: '" + shown(text) + "' is not a finite number";
            }
            if (value < min || value > max) return "value: " + shown(text) + " is outside " + range;
            return {};
        },
        "in " + range);
}

CLI::Validator wholeNumberIn(int64_t min, int64_t max) {
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    return CLI::Validator(
        [min, max, range](std::string& text) -> std::string {
            int64_t value = 0;
            const char* end = text.data() + text.size();
            const auto [last, ec] = std::from_chars(text.data(), end, value);
            if (text.empty() || ec != std::errc() || last != end) {
                return "value: '" + shown(text) + "' is not a whole number in " + range;
            }
            if (value < min || value > max) return "value: " + shown(text) + " is outside " + range;
            return {};
        },
        "in " + range);
}

CLI::Validator zeroOrWholeNumberIn(int64_t min, int64_t max) {
    const std::string range = "[" + std::to_string(min) + ", " + std::to_string(max) + "]";
    return CLI::Validator(
        [inRange = wholeNumberIn(min, max), range](std::string& text) -> std::string {
            std::string copy = text;
            if (text == "0" || inRange(copy).empty()) return {};
            return "value: '" + shown(text) + "' is neither 0 nor a whole number in " + range;
        },
        "0 or in " + range);
}

CLI::Validator oneOf(std::initializer_list<std::string> words) {
    std::string list;
    for (const std::string& w : words) list += (list.empty() ? "" : ", ") + w;
    std::vector<std::string> allowed(words);
    return CLI::Validator(
        [allowed, list](std::string& text) -> std::string {
            for (const std::string& w : allowed)
                if (text == w) return {};
            return "value: '" + shown(text) + "' is not one of " + list;
        },
        "one of " + list);
}

std::string describeParseError(const CLI::ParseError& error, const CLI::App& app) {
    // The validators' messages show the user's text cut short already; the lists of valid
    // values they add are kept whole.
    const std::string what = shown(error.what(), 400);
    if (dynamic_cast<const CLI::ExtrasError*>(&error)) {
        // "The following argument was not expected: X" / "The following arguments were not expected: X Y"
        const size_t colon = what.find(": ");
        std::string first = colon == std::string::npos ? what : what.substr(colon + 2);
        first = first.substr(0, first.find(' '));
        if (!first.empty() && first[0] == '-') return first + ": option: unknown here (see --help)";
        return first + ": argument: not expected (see --help)";
    }
    if (dynamic_cast<const CLI::RequiredError*>(&error)) {
        if (what.find("subcommand") != std::string::npos) {
            const std::vector<std::string> rest = app.remaining();
            if (!rest.empty() && !rest.front().empty()) {
                return shown(rest.front()) +
                    (rest.front()[0] == '-'
                         ? ": option: unknown here (see --help)"
                         : ": command: unknown" + nearest(rest.front(), commandNames(app)) + " (see --help)");
            }
            return "command: subcommand: missing (see --help)";
        }
        const size_t is = what.find(" is required");
        if (is != std::string::npos) return what.substr(0, is) + ": option: required";
        return "command line: options: " + what;
    }
    if (dynamic_cast<const CLI::ArgumentMismatch*>(&error)) {
        const size_t colon = what.find(": ");
        if (colon != std::string::npos && what.find("missing") != std::string::npos)
            return what.substr(0, colon) + ": value: missing";
        if (colon != std::string::npos && what.find("At Most 1 required") != std::string::npos)
            return what.substr(0, colon) + ": option: given more than once";
        if (colon != std::string::npos) return what.substr(0, colon) + ": value: " + what.substr(colon + 2);
        return "command line: values: " + what;
    }
    if (dynamic_cast<const CLI::ValidationError*>(&error)) {
        // Our validators word the rest as "<field>: <problem>".
        const size_t colon = what.find(": ");
        const std::string rest = colon == std::string::npos ? what : what.substr(colon + 2);
        if (rest.rfind("value: ", 0) == 0) return what;
        return colon == std::string::npos ? "command line: values: " + what
                                          : what.substr(0, colon) + ": value: " + rest;
    }
    if (dynamic_cast<const CLI::ConversionError*>(&error)) {
        // "Could not convert: NAME = VALUE"
        const std::string rest = afterPrefix(what, "Could not convert: ");
        const size_t eq = rest.find(" = ");
        if (eq != std::string::npos)
            return rest.substr(0, eq) + ": value: '" + rest.substr(eq + 3) + "' cannot be read as this option's type";
        return "command line: values: " + what;
    }
    if (dynamic_cast<const CLI::ExcludesError*>(&error)) {
        const size_t at = what.find(" excludes ");
        if (at != std::string::npos)
            return what.substr(0, at) + ": option: cannot be combined with " + what.substr(at + 10);
    }
    if (dynamic_cast<const CLI::RequiresError*>(&error)) {
        const size_t at = what.find(" requires ");
        if (at != std::string::npos) return what.substr(0, at) + ": option: needs " + what.substr(at + 10);
    }
    return "command line: arguments: " + what;
}

int runCommandLine(CLI::App& app, int argc, char** argv, const std::function<int()>& afterParse) {
    // "preskin 0.1.0": the program's name and the version of the libpreskin it loaded.
    const std::string name = app.get_description().substr(0, app.get_description().find(':'));
    app.set_version_flag("--version", fmt::format("{} {}", name, preskin::version()));
    try {
        const std::string unknown = findUnknownOption(app, argc, argv);
        if (!unknown.empty()) {
            fmt::print(stderr, "preskin: error: {}\n", unknown);
            return 1;
        }
        app.parse(argc, argv);
        return afterParse ? afterParse() : 0;
    } catch (const CLI::Success& help) {
        return app.exit(help);  // usage text on stdout, exit 0
    } catch (const CLI::ParseError& e) {
        fmt::print(stderr, "preskin: error: {}\n", describeParseError(e, app));
    } catch (const Error& e) {
        fmt::print(stderr, "preskin: error: {}\n", oneLine(e.what()));
    } catch (const std::bad_alloc&) {
        fmt::print(stderr, "preskin: error: memory: not enough memory for this input\n");
    } catch (const std::exception& e) {
        fmt::print(stderr, "preskin: error: internal: {}\n", shown(e.what()));
    }
    return 1;
}

}  // namespace preskin::cli
