// The input-number rule (io/NumberRule.h) applied where a host hands numbers to the Renderer:
// its settings and its lights. Throws preskin::Error "RenderSettings: <field>: <problem>" or
// "lights[i].<field>: <problem>".
#pragma once

#include <preskin/Renderer.h>
#include <preskin/Scene.h>

#include <vector>

namespace preskin {

void checkRenderSettings(const RenderSettings& settings);
void checkLights(const std::vector<Light>& lights);

}  // namespace preskin
