// The GPU kit's report: the figures the kit exists for, read from one `preskin bench` run (its
// JSON), with GPU timestamps per pass (medians), and every performance goal met or not.
// gpu-report.json holds the summary, the goals and the whole bench report; gpu-report.md the
// same as tables.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace preskin::gpukit {

struct ReportInfo {
    std::string command;  // how the kit was run
    std::string mode;     // "full" or "quick"
    std::string date;     // ISO 8601, UTC
    double elapsedS = 0.0;
    std::string source;  // what the kit was made from (scripts/gpu-kit.sh: the commit), or "a build folder"
};

// The report from the bench's JSON. Throws std::runtime_error naming a figure the bench did not
// give (a section that did not run).
nlohmann::ordered_json makeReport(const nlohmann::json& bench, const ReportInfo& info);
// The report as Markdown.
std::string reportMarkdown(const nlohmann::ordered_json& report);

}  // namespace preskin::gpukit
