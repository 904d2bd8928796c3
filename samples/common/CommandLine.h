// The command line of the sample programs under the one-line error promise: every failure ends
// with one line "preskin: error: <file or option>: <field>: <problem>" on stderr and exit status
// 1. Here: validators for numbers and names whose refusals already have that form (NaN and
// values out of range included), the translation of CLI11's own parse errors into it (unknown
// options, missing values, conflicts), and the top-level handler that prints errors of any kind.
// Help (--help, --help-all) still prints CLI11's usage text on stdout and exits 0.
#pragma once

#include <CLI/CLI.hpp>

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>

namespace preskin::cli {

// A finite number in [min, max] (NaN, infinities and text are refused).
CLI::Validator numberIn(double min, double max);
// A whole number in [min, max].
CLI::Validator wholeNumberIn(int64_t min, int64_t max);
// 0 (an option's "chosen automatically") or a whole number in [min, max].
CLI::Validator zeroOrWholeNumberIn(int64_t min, int64_t max);
// One of the given words.
CLI::Validator oneOf(std::initializer_list<std::string> words);

// "<option>: <field>: <problem>" for a CLI11 parse error of `app`.
std::string describeParseError(const CLI::ParseError& error, const CLI::App& app);

// Parses and runs `app` (its callbacks run the commands); returns the exit status. Prints help
// for help requests and one "preskin: error: ..." line for every failure.
int runCommandLine(CLI::App& app, int argc, char** argv, const std::function<int()>& afterParse = {});

}  // namespace preskin::cli
