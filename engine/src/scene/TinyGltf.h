// The one include of tinygltf's header. The implementation comes from Debian's shared
// libtinygltf (2.7), so TINYGLTF_IMPLEMENTATION is never defined here; no option macro that
// changes the library's types is set either. Third-party warnings are silenced for this header.
#pragma once

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wold-style-cast"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#pragma GCC diagnostic ignored "-Wnull-dereference"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop

namespace tinygltf {
// Part of the library's implementation section, exported by libtinygltf but declared only there.
std::string base64_decode(std::string const& s);
}  // namespace tinygltf
