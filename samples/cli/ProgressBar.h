// A one-line progress bar on stderr for long CPU work (`preskin reference`, `preskin compare`):
// redrawn in place with a carriage return when the whole percentage changes, finished with a
// newline. stdout stays free for results.
#pragma once

#include <fmt/core.h>

#include <cstdio>
#include <string>

namespace preskin::cli {

class ProgressBar {
public:
    explicit ProgressBar(std::string label) : label_(std::move(label)) {}
    ~ProgressBar() {
        if (shown_ >= 0) fmt::print(stderr, "\n");
    }
    ProgressBar(const ProgressBar&) = delete;
    ProgressBar& operator=(const ProgressBar&) = delete;

    void operator()(double fraction) {
        const int percent = static_cast<int>(fraction * 100.0);
        if (percent <= shown_) return;
        shown_ = percent;
        const int filled = percent * kWidth / 100;
        fmt::print(stderr, "\rpreskin: {} [{}{}] {:3d}%", label_, std::string(size_t(filled), '#'),
                   std::string(size_t(kWidth - filled), '.'), percent);
        std::fflush(stderr);
    }

private:
    static constexpr int kWidth = 40;
    std::string label_;
    int shown_ = -1;
};

}  // namespace preskin::cli
