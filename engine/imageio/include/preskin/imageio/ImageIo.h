// preskin::imageio: the optional image component. It adds OpenImageIO's readers and writers to
// preskin's image codecs (<preskin/ImageCodec.h>): OpenEXR and TIFF in (EXR environments, EXR LUT
// folders, EXR or TIFF textures), OpenEXR out (linear renders, LUT folders). The core library
// decodes PNG, JPEG and Radiance .hdr and writes PNG by itself; link this component only where
// those other formats are needed (the preskin tools, the viewer and the reference do). It brings
// OpenImageIO's dependencies with it (OpenCV, FFmpeg, OpenVDB, ...: about 250 libraries on
// Debian 12), which is why the core does not.
#pragma once

#include <preskin/ImageCodec.h>

#include <memory>

#if defined(PRESKIN_BUILDING_IMAGEIO)
#define PRESKIN_IMAGEIO_API __attribute__((visibility("default")))
#else
#define PRESKIN_IMAGEIO_API
#endif

namespace preskin::imageio {

// OpenImageIO as a codec: decodes OpenEXR (single-part, scanline or tiled, any data window) and
// TIFF; writes OpenEXR (half or float, zip, the options' attributes as string metadata).
PRESKIN_IMAGEIO_API std::shared_ptr<const ImageCodec> openImageIoCodec();

// Registers openImageIoCodec() once per process (later calls do nothing).
PRESKIN_IMAGEIO_API void registerCodecs();

}  // namespace preskin::imageio
