// A one-line progress bar on stderr for long CPU work (`preskin bake`, `reference`, `compare`):
// redrawn in place with a carriage return when the whole percentage changes, finished with a
// newline; only when stderr is a terminal (a log gets no carriage-return lines). stdout stays
// free for results.
#pragma once

#include <fmt/core.h>
#include <unistd.h>

#include <cstdio>
#include <string>
#include <utility>

namespace preskin::cli {

class ProgressBar {
public:
    explicit ProgressBar(std::string label) : label_(std::move(label)), enabled_(isatty(fileno(stderr)) != 0) {}
    ~ProgressBar() {
        if (shown_ >= 0) fmt::print(stderr, "\n");
    }
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    void operator()(double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (!enabled_ || percent <= shown_) return;
        shown_ = percent;
        const int filled = percent * kWidth / 100;
        fmt::print(stderr, "\rpreskin: {} [{}{}] {:3d}%", label_, std::string(size_t(filled), '#'),
                   std::string(size_t(kWidth - filled), '.'), percent);
        std::fflush(stderr);
    }

private:
    static constexpr int kWidth = 40;
    std::string label_;
    bool enabled_;
    int shown_ = -1;
};

}  // namespace preskin::cli
