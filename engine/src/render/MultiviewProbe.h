// Whether a device's multiview draws triangles that need clipping in every view. Mesa lavapipe
// 22.3 (Debian 12) loses them in the second view when the first view clipped them too, so a
// stereo frame would miss large triangles (floors, walls) in the right eye. The probe draws one
// triangle larger than the viewport into a 2-view, 4x4 multiview pass and reads both layers
// back. Runs once per device (cached in vk::Device); the renderer uses multiview where it
// passes and instanced layered drawing elsewhere (EyeDrawing in <preskin/Renderer.h>).
#pragma once

#include "vk/Device.h"

namespace preskin {

bool multiviewClipsEveryView(const vk::Device& device);

}  // namespace preskin
