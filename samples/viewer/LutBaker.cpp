// Background LUT baking (see LutBaker.h).
#include "LutBaker.h"

#include <exception>
#include <utility>

namespace preskin::viewer {

LutBaker::~LutBaker() {
    if (job_.valid()) job_.wait();
}

void LutBaker::request(const DiffusionProfile& profile, const LutBakeSettings& settings) {
    Request request{profile, settings};
    if (job_.valid()) {
        next_ = std::move(request);
        return;
    }
    start(std::move(request));
}

void LutBaker::start(Request request) {
    progress_->store(0.0);
    auto progress = progress_;
    job_ = std::async(std::launch::async, [request = std::move(request), progress] {
        LutBakeResult result;
        const auto begin = std::chrono::steady_clock::now();
        try {
            result.luts = LutSet::bake(request.profile, request.settings,
                                       [progress](double fraction) { progress->store(fraction); });
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        result.bakeMs =
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
        return result;
    });
}

std::optional<LutBakeResult> LutBaker::poll() {
    if (!job_.valid() || job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    LutBakeResult result = job_.get();
    // A newer request waiting starts now; this result is still shown meanwhile, so a slider
    // dragged for a while keeps updating the image.
    if (next_) start(std::move(*std::exchange(next_, std::nullopt)));
    return result;
}

}  // namespace preskin::viewer
