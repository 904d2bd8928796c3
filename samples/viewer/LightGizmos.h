// Outlines of the area lights (sphere, tube, rectangle, disc) drawn over the viewport with ImGui's
// background draw list, projected with the frame's view: where each light is, how big, which way
// a one-sided light faces (a short line along its normal).
#pragma once

#include <preskin/Scene.h>
#include <preskin/View.h>

#include <vector>

namespace preskin::viewer {

// `eye`: the mono eye the frame is drawn with; widthPx x heightPx: the viewport.
void drawAreaLightGizmos(const std::vector<Light>& lights, const Eye& eye, float widthPx, float heightPx);

}  // namespace preskin::viewer
