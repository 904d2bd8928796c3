// Range-checked accessor reads (see GltfAccessors.h).
#include "scene/GltfAccessors.h"

#include <preskin/Limits.h>

#include <algorithm>
#include <cmath>
#include <cstring>

namespace preskin::gltf {

namespace {

size_t componentSize(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
    }
}

std::string componentName(int componentType) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return std::to_string(componentType);
    }
}

int componentCount(int type) {
    switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT4: return 16;  // columns of 4 components: never padded (glTF 2.0, "Data Alignment")
    default: return 0;
    }
}

std::string typeName(int components) {
    return components == 1 ? "SCALAR" : components == 16 ? "MAT4" : "VEC" + std::to_string(components);
}

template <typename T>
T load(const uint8_t* p) {
    T v;
    std::memcpy(&v, p, sizeof(T));
    return v;
}

float convert(const uint8_t* p, int componentType, bool normalized) {
    switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
        const auto v = static_cast<float>(load<int8_t>(p));
        return normalized ? std::max(v / 127.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
        const auto v = static_cast<float>(load<uint8_t>(p));
        return normalized ? v / 255.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
        const auto v = static_cast<float>(load<int16_t>(p));
        return normalized ? std::max(v / 32767.0f, -1.0f) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        const auto v = static_cast<float>(load<uint16_t>(p));
        return normalized ? v / 65535.0f : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
        const auto v = static_cast<float>(load<uint32_t>(p));
        return normalized ? static_cast<float>(load<uint32_t>(p) / 4294967295.0) : v;
    }
    default: return load<float>(p);
    }
}

// The bytes of `count` elements of `elementSize` bytes, `stride` apart, starting `offset` bytes
// into bufferViews[viewIndex]; checks the view against its buffer and the elements against the view.
const uint8_t* viewBytes(const LoadContext& ctx, int viewIndex, uint64_t offset, uint64_t count, uint64_t elementSize,
                         uint64_t stride, const std::string& where) {
    const tinygltf::Model& model = *ctx.model;
    if (viewIndex < 0 || static_cast<size_t>(viewIndex) >= model.bufferViews.size()) {
        ctx.fail(where + ".bufferView",
                 std::to_string(viewIndex) + " is out of range: the file has " +
                     std::to_string(model.bufferViews.size()) + " bufferViews");
    }
    const tinygltf::BufferView& view = model.bufferViews[static_cast<size_t>(viewIndex)];
    const std::string viewName = indexed("bufferViews", static_cast<size_t>(viewIndex));
    if (view.buffer < 0 || static_cast<size_t>(view.buffer) >= model.buffers.size()) {
        ctx.fail(viewName + ".buffer", std::to_string(view.buffer) + " is out of range");
    }
    const tinygltf::Buffer& buffer = model.buffers[static_cast<size_t>(view.buffer)];
    const uint64_t bufferSize = buffer.data.size();
    if (view.byteOffset > bufferSize || view.byteLength > bufferSize - view.byteOffset) {
        ctx.fail(viewName,
                 "byteOffset " + std::to_string(view.byteOffset) + " + byteLength " + std::to_string(view.byteLength) +
                     " exceeds buffers[" + std::to_string(view.buffer) + "] (" + std::to_string(bufferSize) +
                     " bytes)");
    }
    // count <= limits::kMaxSceneIndices and stride <= 2^8 (or elementSize <= 64), so no overflow.
    const uint64_t span = count == 0 ? 0 : (count - 1) * stride + elementSize;
    if (offset > view.byteLength || span > view.byteLength - offset) {
        ctx.fail(where,
                 "byteOffset " + std::to_string(offset) + " + " + std::to_string(count) + " elements of " +
                     std::to_string(elementSize) + " bytes (stride " + std::to_string(stride) +
                     ") = " + std::to_string(offset + span) + " bytes exceeds " + viewName + " (" +
                     std::to_string(view.byteLength) + " bytes)");
    }
    return buffer.data.data() + view.byteOffset + offset;
}

struct CheckedAccessor {
    const tinygltf::Accessor* accessor = nullptr;
    std::string name;  // "accessors[i]"
    int components = 0;
    size_t componentBytes = 0;
};

CheckedAccessor checkAccessor(const LoadContext& ctx, int index, const std::string& what) {
    const tinygltf::Model& model = *ctx.model;
    if (index < 0 || static_cast<size_t>(index) >= model.accessors.size()) {
        ctx.fail(what,
                 "accessor " + std::to_string(index) + " is out of range: the file has " +
                     std::to_string(model.accessors.size()) + " accessors");
    }
    CheckedAccessor c;
    c.accessor = &model.accessors[static_cast<size_t>(index)];
    c.name = indexed("accessors", static_cast<size_t>(index));
    const tinygltf::Accessor& a = *c.accessor;
    c.components = componentCount(a.type);
    if (c.components == 0) ctx.fail(c.name + ".type", "MAT2 or MAT3, " + what + " needs a vector, scalar or MAT4");
    c.componentBytes = componentSize(a.componentType);
    if (c.componentBytes == 0) {
        ctx.fail(c.name + ".componentType", componentName(a.componentType) + " is not allowed for accessors");
    }
    if (a.count == 0) ctx.fail(c.name + ".count", "0 (must be at least 1)");
    if (a.count > limits::kMaxSceneIndices) {
        ctx.fail(c.name + ".count",
                 std::to_string(a.count) + " exceeds the limit of " + std::to_string(limits::kMaxSceneIndices) +
                     " elements");
    }
    return c;
}

CheckedAccessor checkIndexAccessor(const LoadContext& ctx, int index, const std::string& what) {
    const CheckedAccessor c = checkAccessor(ctx, index, what);
    const int type = c.accessor->componentType;
    if (c.components != 1) ctx.fail(c.name + ".type", typeName(c.components) + ", but " + what + " needs SCALAR");
    if (type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        type != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
        ctx.fail(c.name + ".componentType", componentName(type) + ", but " + what + " needs an unsigned integer type");
    }
    if (c.accessor->normalized) ctx.fail(c.name + ".normalized", "true, but " + what + " must not be normalized");
    return c;
}

uint32_t loadUnsigned(const uint8_t* p, size_t bytes) {
    return bytes == 1 ? load<uint8_t>(p) : bytes == 2 ? load<uint16_t>(p) : load<uint32_t>(p);
}

// Calls store(element, component, bytes) for every component of a checked accessor: first the
// bufferView's data (none when it has no bufferView: the caller's zeros stay), then the sparse
// substitutions.
struct ViewRange {
    const uint8_t* base = nullptr;  // nullptr: no bufferView
    uint64_t stride = 0;
};

// The checked range of an accessor's bufferView data (element size and stride against the view).
ViewRange viewRange(const LoadContext& ctx, const CheckedAccessor& c) {
    const tinygltf::Accessor& a = *c.accessor;
    if (a.bufferView < 0) return {};
    const uint64_t elementSize = c.componentBytes * static_cast<size_t>(c.components);
    const tinygltf::BufferView& view = ctx.model->bufferViews.at(static_cast<size_t>(a.bufferView));
    const uint64_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
    if (stride < elementSize) {
        ctx.fail(indexed("bufferViews", static_cast<size_t>(a.bufferView)) + ".byteStride",
                 std::to_string(stride) + " is smaller than the element size " + std::to_string(elementSize) + " of " +
                     c.name);
    }
    return {viewBytes(ctx, a.bufferView, a.byteOffset, a.count, elementSize, stride, c.name), stride};
}

template <typename Store>
void readComponents(const LoadContext& ctx, const CheckedAccessor& c, Store&& store) {
    const tinygltf::Accessor& a = *c.accessor;
    const auto components = static_cast<size_t>(c.components);
    const uint64_t elementSize = c.componentBytes * components;
    if (const ViewRange range = viewRange(ctx, c); range.base) {
        const uint8_t* base = range.base;
        const uint64_t stride = range.stride;
        for (size_t i = 0; i < a.count; ++i) {
            const uint8_t* element = base + i * stride;
            for (size_t k = 0; k < components; ++k) store(i, k, element + k * c.componentBytes);
        }
    }
    if (a.sparse.isSparse) {
        const std::string where = c.name + ".sparse";
        const int count = a.sparse.count;
        if (count < 1 || static_cast<size_t>(count) > a.count) {
            ctx.fail(where + ".count", std::to_string(count) + " (must be in 1.." + std::to_string(a.count) + ")");
        }
        const int indexType = a.sparse.indices.componentType;
        const size_t indexBytes = componentSize(indexType);
        if (indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE && indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
            indexType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT) {
            // The validator warns only: the substitution cannot be read, the dense values stay.
            ctx.warn(where + ".indices.componentType",
                     componentName(indexType) + " is not an unsigned integer type; the sparse substitution is ignored");
            return;
        }
        if (a.sparse.indices.byteOffset < 0) ctx.fail(where + ".indices.byteOffset", "negative");
        if (a.sparse.values.byteOffset < 0) ctx.fail(where + ".values.byteOffset", "negative");
        const auto n = static_cast<uint64_t>(count);
        const uint8_t* indexBase =
            viewBytes(ctx, a.sparse.indices.bufferView, static_cast<uint64_t>(a.sparse.indices.byteOffset), n,
                      indexBytes, indexBytes, where + ".indices");
        const uint8_t* valueBase =
            viewBytes(ctx, a.sparse.values.bufferView, static_cast<uint64_t>(a.sparse.values.byteOffset), n,
                      elementSize, elementSize, where + ".values");
        uint64_t previous = 0;
        for (uint64_t s = 0; s < n; ++s) {
            const uint8_t* p = indexBase + s * indexBytes;
            const uint64_t target = loadUnsigned(p, indexBytes);
            if (target >= a.count) {
                ctx.fail(where + ".indices",
                         "element " + std::to_string(s) + " = " + std::to_string(target) + " >= the accessor's count " +
                             std::to_string(a.count));
            }
            if (s > 0 && target <= previous) {
                ctx.fail(where + ".indices",
                         "element " + std::to_string(s) + " = " + std::to_string(target) +
                             " is not greater than the one before");
            }
            previous = target;
            for (size_t k = 0; k < components; ++k) {
                store(static_cast<size_t>(target), k, valueBase + s * elementSize + k * c.componentBytes);
            }
        }
    }
}

}  // namespace

size_t accessorCount(const LoadContext& ctx, int index, const std::string& what, AccessorUse use) {
    const CheckedAccessor c =
        use == AccessorUse::Indices ? checkIndexAccessor(ctx, index, what) : checkAccessor(ctx, index, what);
    viewRange(ctx, c);
    return c.accessor->count;
}

FloatAccessor readFloatAccessor(const LoadContext& ctx, int index, std::initializer_list<int> componentsAllowed,
                                const std::string& what) {
    const CheckedAccessor c = checkAccessor(ctx, index, what);
    if (std::find(componentsAllowed.begin(), componentsAllowed.end(), c.components) == componentsAllowed.end()) {
        std::string allowed;
        for (int n : componentsAllowed) allowed += (allowed.empty() ? "" : " or ") + typeName(n);
        ctx.fail(c.name + ".type", typeName(c.components) + ", but " + what + " needs " + allowed);
    }
    FloatAccessor out;
    out.count = c.accessor->count;
    out.components = c.components;
    out.values.assign(out.count * static_cast<size_t>(c.components), 0.0f);
    const int type = c.accessor->componentType;
    const bool normalized = c.accessor->normalized;
    const auto components = static_cast<size_t>(c.components);
    readComponents(ctx, c, [&](size_t element, size_t component, const uint8_t* p) {
        out.values[element * components + component] = convert(p, type, normalized);
    });
    for (size_t i = 0; i < out.values.size(); ++i) {
        if (auto problem = io::numberProblem(out.values[i])) {
            const size_t element = i / static_cast<size_t>(c.components);
            ctx.fail(c.name,
                     "element " + std::to_string(element) + " (component " +
                         std::to_string(i % static_cast<size_t>(c.components)) + ") of " + what + ": " + *problem);
        }
    }
    return out;
}

std::vector<uint32_t> readIndexAccessor(const LoadContext& ctx, int index, size_t vertexCount,
                                        const std::string& what) {
    const CheckedAccessor c = checkIndexAccessor(ctx, index, what);
    std::vector<uint32_t> indices(c.accessor->count, 0);
    readComponents(ctx, c, [&](size_t element, size_t, const uint8_t* p) {
        indices[element] = loadUnsigned(p, c.componentBytes);
    });
    for (size_t i = 0; i < indices.size(); ++i) {
        if (indices[i] >= vertexCount) {
            ctx.fail(c.name,
                     "index " + std::to_string(indices[i]) + " at element " + std::to_string(i) + " of " + what +
                         " >= vertex count " + std::to_string(vertexCount));
        }
    }
    return indices;
}

}  // namespace preskin::gltf
