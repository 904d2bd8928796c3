// Background LUT baking (see LutBaker.h).
#include "LutBaker.h"

#include <exception>
#include <utility>

namespace preskin::viewer {

LutBaker::~LutBaker() {
    if (job_.valid()) job_.wait();
}

void LutBaker::request(size_t layer, const DiffusionProfile& profile, const LutBakeSettings& settings) {
    Request request{layer, profile, settings};
    if (job_.valid()) {
        next_.insert_or_assign(layer, std::move(request));
        return;
    }
    start(std::move(request));
}

void LutBaker::start(Request request) {
    progress_->store(0.0);
    auto progress = progress_;
    job_ = std::async(std::launch::async, [request = std::move(request), progress] {
        LutBakeResult result;
        result.layer = request.layer;
        const auto begin = std::chrono::steady_clock::now();
        try {
            result.luts = LutSet::bake(request.profile, request.settings,
                                       [progress](double fraction) { progress->store(fraction); });
        } catch (const std::exception& e) {
            result.error = e.what();
        }
        result.bakeMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - begin).count();
        return result;
    });
}

std::optional<LutBakeResult> LutBaker::poll() {
    if (!job_.valid() || job_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return std::nullopt;
    LutBakeResult result = job_.get();
    // A newer request waiting starts now; this result is still shown meanwhile, so a slider
    // dragged for a while keeps updating the image.
    if (!next_.empty()) {
        Request request = std::move(next_.begin()->second);
        next_.erase(next_.begin());
        start(std::move(request));
    }
    return result;
}

}  // namespace preskin::viewer
