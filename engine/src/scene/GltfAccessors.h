// Reading glTF accessors into plain arrays, with every range checked first (accessor inside its
// bufferView, bufferView inside its buffer, sparse indices and values inside theirs, sparse
// indices increasing and below count), so no read ever leaves the loaded data.
// Integer components are converted as glTF 2.0 specifies: normalized ones to [0, 1] or [-1, 1]
// (signed: max(c / (2^(n-1) - 1), -1)), others to their value. An accessor without bufferView
// reads as zeros (plus its sparse values). Of the matrix types only MAT4 is read (inverse bind
// matrices), as 16 column-major components.
#pragma once

#include "scene/GltfContext.h"

#include <cstdint>
#include <string>
#include <vector>

namespace preskin::gltf {

struct FloatAccessor {
    size_t count = 0;
    int components = 0;         // 1..4, or 16 (MAT4, column-major)
    std::vector<float> values;  // count * components
};

// Reads accessor `index` as floats. `componentsAllowed` lists the accepted element sizes (e.g.
// {3} for POSITION, {2} for TEXCOORD_0); `what` names the use in messages, such as
// "meshes[0].primitives[0].attributes.POSITION". Non-finite values are an error.
FloatAccessor readFloatAccessor(const LoadContext& ctx, int index, std::initializer_list<int> componentsAllowed,
                                const std::string& what);

// The element count of accessor `index` after the same checks as the readers, without reading
// it: callers check their totals against the limits before anything is allocated.
enum class AccessorUse { Attribute, Indices };
size_t accessorCount(const LoadContext& ctx, int index, const std::string& what,
                     AccessorUse use = AccessorUse::Attribute);

// Reads an index accessor (SCALAR, unsigned byte/short/int) and checks every index < vertexCount.
std::vector<uint32_t> readIndexAccessor(const LoadContext& ctx, int index, size_t vertexCount, const std::string& what);

}  // namespace preskin::gltf
