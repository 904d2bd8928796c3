// Live LUT re-baking: LutSet::bake (all four skin tables, about 0.15-0.4 s at the default size
// on two cores) runs on a worker thread while the viewer keeps drawing; the finished set is
// handed to the main thread, which uploads that profile's layer alone with
// Renderer::setProfileLayer. Requests made while a bake runs are coalesced per layer: only the
// newest one of each layer is baked next (the finished, older set is still shown meanwhile).
// Limits: one bake at a time; a bake cannot be cancelled midway.
#pragma once

#include <preskin/DiffusionProfile.h>
#include <preskin/LutSet.h>

#include <atomic>
#include <chrono>
#include <future>
#include <map>
#include <memory>
#include <optional>
#include <string>

namespace preskin::viewer {

struct LutBakeResult {
    size_t layer = 0;            // the LUT layer it is for (Renderer::setProfileLayer)
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

    // Bakes `profile` for LUT layer `layer` (now, or after the running bake when one is busy).
    void request(size_t layer, const DiffusionProfile& profile, const LutBakeSettings& settings);
    bool busy() const { return job_.valid() || !next_.empty(); }
    // Progress of the running bake in [0, 1].
    double progress() const { return progress_->load(); }
    // Call once per frame: returns a finished bake.
    std::optional<LutBakeResult> poll();

private:
    struct Request {
        size_t layer;
        DiffusionProfile profile;
        LutBakeSettings settings;
    };
    void start(Request request);

    std::future<LutBakeResult> job_;
    std::map<size_t, Request> next_;  // per layer, the newest request
    std::shared_ptr<std::atomic<double>> progress_ = std::make_shared<std::atomic<double>>(0.0);
};

}  // namespace preskin::viewer
