// The test program is a preskin tool: it registers the image component (EXR and TIFF) before any
// test runs, as the CLI and the viewer do. Tests of the core as a host sees it without the
// component replace the registered codecs for their duration (image::ScopedCodecs).
#include <preskin/imageio/ImageIo.h>

namespace {

[[maybe_unused]] const bool kRegistered = [] {
    preskin::imageio::registerCodecs();
    return true;
}();

}  // namespace
