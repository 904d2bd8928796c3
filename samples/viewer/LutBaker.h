// Live LUT re-baking: LutSet::bake (all four skin tables, about 0.15-0.4 s at the default size
// on two cores) runs on a worker thread while the viewer keeps drawing; the finished set is
// handed to the main thread, which uploads it with Renderer::setLuts. Requests made while a bake
// runs are coalesced: only the newest one is baked next (the finished, older set is still shown
// meanwhile).
// Limits: one bake at a time; a bake cannot be cancelled midway.
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/LutSet.h>

#include <atomic>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <string>

namespace preskin::viewer {

struct LutBakeResult {
    std::optional<LutSet> luts;  // empty when the bake failed
    std::string error;
    double bakeMs = 0.0;
};

class LutBaker {
public:
    LutBaker() = default;
    ~LutBaker();
    LutBaker(const LutBaker&) = delete;
    LutBaker& operator=(const LutBaker&) = delete;

    // Bakes `profile` (now, or after the running bake when one is busy).
    void request(const DiffusionProfile& profile, const LutBakeSettings& settings);
    bool busy() const { return job_.valid() || next_.has_value(); }
    // Progress of the running bake in [0, 1].
    double progress() const { return progress_->load(); }
    // Call once per frame: returns a finished bake.
    std::optional<LutBakeResult> poll();

private:
    struct Request {
        DiffusionProfile profile;
        LutBakeSettings settings;
    };
    void start(Request request);

    std::future<LutBakeResult> job_;
    std::optional<Request> next_;
    std::shared_ptr<std::atomic<double>> progress_ = std::make_shared<std::atomic<double>>(0.0);
};

}  // namespace preskin::viewer
