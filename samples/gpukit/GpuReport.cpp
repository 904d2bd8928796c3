// The GPU kit's report (see GpuReport.h).
#include "GpuReport.h"

#include <fmt/core.h>

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace preskin::gpukit {

namespace {

using json = nlohmann::json;
using ojson = nlohmann::ordered_json;

// bench[a][b]...: throws naming the path when the bench did not write it.
const json& at(const json& root, std::initializer_list<const char*> path) {
    const json* node = &root;
    std::string where;
    for (const char* key : path) {
        where += where.empty() ? key : std::string(".") + key;
        if (!node->is_object() || !node->contains(key)) throw std::runtime_error("the bench report has no " + where);
        node = &(*node)[key];
    }
    return *node;
}

double number(const json& root, std::initializer_list<const char*> path) {
    const json& v = at(root, path);
    if (!v.is_number()) throw std::runtime_error("the bench report's figure is not a number");
    return v.get<double>();
}

// A configuration's frames: GPU time per frame and per pass (medians of the frames).
ojson frame(const json& measurement) {
    ojson out;
    out["gpu_ms"] = number(measurement, {"gpu_ms"});
    out["frames"] = number(measurement, {"frames"});
    out["passes_gpu_ms"] = at(measurement, {"gpu_pass_ms"});
    out["wall_ms"] = number(measurement, {"wall_ms"});
    return out;
}

ojson goal(const std::string& name, double measured, double target, bool atMost, const std::string& note = {}) {
    ojson g;
    g["goal"] = name;
    g["target"] = target;
    g["measured"] = measured;
    g["holds"] = std::isfinite(measured) && (atMost ? measured <= target : measured >= target);
    if (!note.empty()) g["note"] = note;
    return g;
}

const json* lightRow(const json& bench, double lights) {
    for (const json& row : at(bench, {"light_loop"}))
        if (row.value("lights", -1.0) == lights) return &row;
    return nullptr;
}

std::string ms(const ojson& v) { return v.is_number() ? fmt::format("{:.3f}", v.get<double>()) : "-"; }
std::string ratio(const ojson& v) { return v.is_number() ? fmt::format("{:.3f}", v.get<double>()) : "-"; }

std::string passes(const ojson& f) {
    std::string out;
    for (auto it = f["passes_gpu_ms"].begin(); it != f["passes_gpu_ms"].end(); ++it)
        if (it.value().is_number())
            out += fmt::format("{}{} {:.3f}", out.empty() ? "" : ", ", it.key(), it.value().get<double>());
    return out;
}

}  // namespace

ojson makeReport(const json& bench, const ReportInfo& info) {
    ojson r;
    r["tool"] = "preskin GPU kit";
    r["mode"] = info.mode;
    r["date"] = info.date;
    r["command"] = info.command;
    r["source"] = info.source;
    r["elapsed_s"] = info.elapsedS;
    r["device"] = at(bench, {"device"});
    r["driver"] = at(bench, {"driver"});
    r["software_device"] = at(bench, {"software_device"});
    r["timing"] =
        "GPU timestamps around each pass; every figure the median of its frames after warm-up, the configurations "
        "compared with each other measured in interleaved rounds (preskin bench)";
    std::vector<ojson> goals;

    // The head: standard against skin, each technique's cost, the baselines, IBL and background.
    ojson head;
    head["width"] = at(bench, {"width"});
    head["height"] = at(bench, {"height"});
    const json& skinRow = at(bench, {"skin_vs_standard"}).at(0);
    head["lights"] = at(skinRow, {"lights"});
    head["standard"] = frame(at(skinRow, {"standard_material"}));
    head["skin"] = frame(at(skinRow, {"skin"}));
    head["skin_techniques_off"] = frame(at(skinRow, {"skin_features_off"}));
    head["skin_over_standard"] = number(skinRow, {"skin_over_standard_gpu"});
    ojson techniques;
    const json& costs = at(bench, {"skin_techniques", "cost_ms"});
    for (auto it = costs.begin(); it != costs.end(); ++it) techniques[it.key()] = number(it.value(), {"forward_gpu"});
    head["technique_cost_forward_gpu_ms"] = techniques;
    // The quality tiers (high is the skin frame): their frames and ratios to the standard frame
    // measured in the techniques' rounds.
    ojson tiers;
    tiers["high"] = number(at(bench, {"skin_techniques"}), {"skin_over_standard_gpu"});
    const json& tierRows = at(bench, {"skin_techniques", "tiers"});
    for (const char* tier : {"medium", "low"}) tiers[tier] = number(at(tierRows, {tier}), {"over_standard_gpu"});
    head["tier_over_standard"] = tiers;
    const json& mono = at(bench, {"diffusion_methods", "mono"});
    head["preintegrated"] = frame(at(mono, {"preintegrated"}));
    head["screen_space"] = frame(at(mono, {"screen"}));
    head["texture_space"] = frame(at(mono, {"texture"}));
    head["preintegrated_over_screen_space"] = number(mono, {"preintegrated_over_screen_gpu"});
    head["preintegrated_over_texture_space"] =
        number(mono, {"preintegrated", "gpu_ms"}) / number(mono, {"texture", "gpu_ms"});
    const json& env = at(bench, {"environment"});
    head["ibl_and_background"] = frame(at(env, {"ibl_and_background"}));
    head["neither"] = frame(at(env, {"neither"}));
    const double envFull = number(env, {"ibl_and_background", "gpu_ms"});
    head["ibl_and_background_share"] = (envFull - number(env, {"neither", "gpu_ms"})) / envFull;
    r["head"] = head;
    goals.push_back(goal("skin frame / standard frame <= 1.10 (GPU time, the head, " +
                             fmt::format("{}x{}, {} lights)", head["width"].get<int>(), head["height"].get<int>(),
                                         head["lights"].get<int>()),
                         head["skin_over_standard"], 1.10, true));
    goals.push_back(goal("specular IBL and environment background / frame <= 0.05 (GPU time)",
                         head["ibl_and_background_share"], 0.05, true));
    goals.push_back(goal("preskin frame / screen-space blur frame <= 0.5 (GPU time, mono)",
                         head["preintegrated_over_screen_space"], 0.5, true));

    // VR: the stereo frame against its eyes' two mono frames, and against 90 Hz.
    const json& vr = at(bench, {"vr"});
    ojson v;
    v["eye_width"] = at(vr, {"eye_width"});
    v["eye_height"] = at(vr, {"eye_height"});
    v["msaa_samples"] = at(vr, {"msaa_samples"});
    v["lights"] = at(vr, {"lights"});
    v["stereo"] = frame(at(vr, {"stereo"}));
    v["left_mono"] = frame(at(vr, {"left_mono"}));
    v["right_mono"] = frame(at(vr, {"right_mono"}));
    v["stereo_over_two_mono"] = number(vr, {"stereo_over_two_mono_gpu"});
    const double stereoMs = number(vr, {"stereo", "gpu_ms"});
    v["frame_budget_ms"] = 1000.0 / 90.0;
    v["budget_left_ms"] = 1000.0 / 90.0 - stereoMs;
    r["vr"] = v;
    const std::string vrSize =
        fmt::format("2 x {}x{}, MSAA {}x, {} lights, skin", v["eye_width"].get<int>(), v["eye_height"].get<int>(),
                    v["msaa_samples"].get<int>(), v["lights"].get<int>());
    goals.push_back(goal("stereo frame / two mono frames <= 0.85 (GPU time, " + vrSize + ")", v["stereo_over_two_mono"],
                         0.85, true));
    goals.push_back(goal("VR frame within 11.1 ms (90 Hz; GPU time, " + vrSize + ")", stereoMs, 1000.0 / 90.0, true,
                         fmt::format("{:.2f} ms left of the 11.11 ms frame", 1000.0 / 90.0 - stereoMs)));

    // Lights at constant density, the grid's share; area lights against points.
    ojson lights;
    lights["density"] = at(bench, {"light_density"});
    ojson rows = ojson::array();
    for (const json& row : at(bench, {"light_loop"})) {
        ojson o;
        o["lights"] = at(row, {"lights"});
        o["frame"] = frame(at(row, {"clustered"}));
        o["grid_build"] = at(row, {"clustered", "cluster_build"});
        const json& passesMs = at(row, {"clustered", "gpu_pass_ms"});
        const double clustersMs = passesMs.contains("clusters") && passesMs["clusters"].is_number()
            ? passesMs["clusters"].get<double>()
            : 0.0;
        o["grid_pass_share_of_frame_gpu"] = clustersMs / number(row, {"clustered", "gpu_ms"});
        rows.push_back(o);
    }
    lights["counts"] = rows;
    const json* at4096 = lightRow(bench, 4096);
    const json* at65536 = lightRow(bench, 65536);
    if (!at4096 || !at65536)
        throw std::runtime_error("the bench report has no light_loop rows at 4096 and 65536 lights");
    lights["frame_65536_over_4096"] =
        number(*at65536, {"clustered", "gpu_ms"}) / number(*at4096, {"clustered", "gpu_ms"});
    const json& area = at(bench, {"area_lights"});
    ojson areaOut;
    for (const char* shape : {"point", "sphere", "tube", "rectangle", "disc"}) {
        ojson s;
        s["forward_ms_per_light"] = number(area, {shape, "forward_ms_per_light"});
        s["per_light_over_point"] = number(area, {shape, "per_light_over_point"});
        areaOut[shape] = s;
    }
    lights["area_64_lights"] = areaOut;
    r["lights"] = lights;
    goals.push_back(goal(
        fmt::format("65,536 lights / 4,096 lights at density {} <= 1.5 (GPU time)", lights["density"].get<double>()),
        lights["frame_65536_over_4096"], 1.5, true));

    // The animated head.
    const json& anim = at(bench, {"animation"});
    ojson a;
    a["scene"] = at(anim, {"scene"});
    a["frame"] = frame(at(anim, {"frame"}));
    a["deform_gpu_ms"] = number(anim, {"deform_gpu_ms"});
    a["curvature_gpu_ms"] = number(anim, {"curvature_gpu_ms"});
    a["deform_and_curvature_share"] = number(anim, {"deform_and_curvature_share_gpu"});
    r["animation"] = a;

    r["goals"] = goals;
    r["bench_goals"] = at(bench, {"goals"});
    r["bench"] = bench;
    return r;
}

std::string reportMarkdown(const ojson& r) {
    std::ostringstream md;
    md << "# preskin GPU report\n\n";
    md << fmt::format(
        "- device: {}\n- driver: {}\n- date: {}\n- mode: {}\n- command: `{}`\n- kit made from: {}\n- elapsed: {:.0f} s\n\n",
        r["device"].get<std::string>(), r["driver"].get<std::string>(), r["date"].get<std::string>(),
        r["mode"].get<std::string>(), r["command"].get<std::string>(), r.value("source", std::string("-")),
        r["elapsed_s"].get<double>());
    md << r["timing"].get<std::string>()
       << ".\n\n## Goals\n\n| goal | target | measured | holds |\n| --- | --- | --- | --- |\n";
    for (const auto& g : r["goals"])
        md << fmt::format("| {} | {} | {} | {} |\n", g["goal"].get<std::string>(), ratio(g["target"]),
                          ratio(g["measured"]) + (g.contains("note") ? " (" + g["note"].get<std::string>() + ")" : ""),
                          g["holds"].get<bool>() ? "yes" : "**no**");
    const ojson& h = r["head"];
    md << fmt::format("\n## The head, {}x{}, {} lights (GPU ms)\n\n| frame | GPU ms | passes |\n| --- | --- | --- |\n",
                      h["width"].get<int>(), h["height"].get<int>(), h["lights"].get<int>());
    for (const char* key : {"standard", "skin", "skin_techniques_off", "preintegrated", "screen_space", "texture_space",
                            "ibl_and_background", "neither"})
        md << fmt::format("| {} | {} | {} |\n", key, ms(h[key]["gpu_ms"]), passes(h[key]));
    md << fmt::format(
        "\nskin / standard {}; preskin / screen-space {}, / texture-space {}; IBL and background share {}\n",
        ratio(h["skin_over_standard"]), ratio(h["preintegrated_over_screen_space"]),
        ratio(h["preintegrated_over_texture_space"]), ratio(h["ibl_and_background_share"]));
    md << "\n| technique | forward-pass cost, GPU ms (skin frame minus the frame without it) |\n| --- | --- |\n";
    for (auto it = h["technique_cost_forward_gpu_ms"].begin(); it != h["technique_cost_forward_gpu_ms"].end(); ++it)
        md << fmt::format("| {} | {} |\n", it.key(), ms(it.value()));
    md << "\n| quality tier | skin frame / standard frame (GPU time, in the techniques' rounds) |\n| --- | --- |\n";
    for (auto it = h["tier_over_standard"].begin(); it != h["tier_over_standard"].end(); ++it)
        md << fmt::format("| {} | {} |\n", it.key(), ratio(it.value()));
    const ojson& v = r["vr"];
    md << fmt::format("\n## VR: 2 x {}x{}, MSAA {}x, {} lights\n\n| frame | GPU ms | passes |\n| --- | --- | --- |\n",
                      v["eye_width"].get<int>(), v["eye_height"].get<int>(), v["msaa_samples"].get<int>(),
                      v["lights"].get<int>());
    for (const char* key : {"stereo", "left_mono", "right_mono"})
        md << fmt::format("| {} | {} | {} |\n", key, ms(v[key]["gpu_ms"]), passes(v[key]));
    md << fmt::format("\nstereo / two monos {}; {} ms of the 11.11 ms frame left\n", ratio(v["stereo_over_two_mono"]),
                      ms(v["budget_left_ms"]));
    const ojson& l = r["lights"];
    md << fmt::format(
        "\n## Lights at density {}\n\n| lights | GPU ms | grid build | grid pass share | passes |\n"
        "| --- | --- | --- | --- | --- |\n",
        l["density"].get<double>());
    for (const auto& row : l["counts"])
        md << fmt::format("| {} | {} | {} | {} | {} |\n", row["lights"].get<int>(), ms(row["frame"]["gpu_ms"]),
                          row["grid_build"].get<std::string>(), ratio(row["grid_pass_share_of_frame_gpu"]),
                          passes(row["frame"]));
    md << fmt::format(
        "\n65,536 / 4,096 lights: {}\n\n| 64 lights of shape | forward ms per light | over a point's |\n"
        "| --- | --- | --- |\n",
        ratio(l["frame_65536_over_4096"]));
    for (auto it = l["area_64_lights"].begin(); it != l["area_64_lights"].end(); ++it)
        md << fmt::format("| {} | {} | {} |\n", it.key(), ms(it.value()["forward_ms_per_light"]),
                          ratio(it.value()["per_light_over_point"]));
    const ojson& a = r["animation"];
    md << fmt::format(
        "\n## The animated head\n\nframe {} GPU ms ({}); deformation {} ms and curvature {} ms: {} of the "
        "frame\n",
        ms(a["frame"]["gpu_ms"]), passes(a["frame"]), ms(a["deform_gpu_ms"]), ms(a["curvature_gpu_ms"]),
        ratio(a["deform_and_curvature_share"]));
    md << "\n## The bench's own goals (wall time on software devices)\n\n| goal | target | measured | holds |\n"
          "| --- | --- | --- | --- |\n";
    for (const auto& g : r["bench_goals"])
        md << fmt::format("| {} | {} | {} | {} |\n", g["goal"].get<std::string>(), ratio(g["target"]),
                          ratio(g["measured"]), g["holds"].get<bool>() ? "yes" : "**no**");
    return md.str();
}

}  // namespace preskin::gpukit
