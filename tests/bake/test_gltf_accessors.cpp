// glTF accessor reading (bake/gltf_accessors.h, glTF 2.0 §3.6.2): component types, the
// normalized integer decoding, byte strides, sparse substitution, and the error codes and
// messages of out-of-range or malformed accessors. Models are built in memory, so each test
// controls every byte.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "bake/gltf_accessors.h"

namespace stipple::bake::gltf {
namespace {

// A model with one buffer; views and accessors are added by the tests.
struct ModelBuilder {
    tinygltf::Model model;

    ModelBuilder() { model.buffers.emplace_back(); }

    template <typename T>
    size_t append(const std::vector<T>& values) {
        std::vector<unsigned char>& data = model.buffers[0].data;
        while (data.size() % 4 != 0) data.push_back(0);  // §3.6.2.4 alignment
        const size_t offset = data.size();
        data.resize(offset + values.size() * sizeof(T));
        std::memcpy(data.data() + offset, values.data(), values.size() * sizeof(T));
        return offset;
    }
    template <typename T>
    int view(const std::vector<T>& values, size_t stride = 0) {
        tinygltf::BufferView v;
        v.buffer = 0;
        v.byteOffset = append(values);
        v.byteLength = values.size() * sizeof(T);
        v.byteStride = stride;
        model.bufferViews.push_back(v);
        return int(model.bufferViews.size() - 1);
    }
    int accessor(int view, int component_type, int type, size_t count, bool normalized = false,
                 size_t byte_offset = 0) {
        tinygltf::Accessor a;
        a.bufferView = view;
        a.byteOffset = byte_offset;
        a.componentType = component_type;
        a.type = type;
        a.count = count;
        a.normalized = normalized;
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    }
};

TEST(GltfAccessors, ReadsTightlyPackedFloats) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1.5f, -2.0f, 3.25f, 4, 5, 6});
    const int acc = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 2);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC3, kF32, &out);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(out, (std::vector<float>{1.5f, -2.0f, 3.25f, 4, 5, 6}));
}

TEST(GltfAccessors, ReadsPlainIntegersAsTheirValues) {
    ModelBuilder b;
    const int u16 = b.view(std::vector<uint16_t>{0, 65535, 7});
    const int i8 = b.view(std::vector<int8_t>{-5, 100, -128, 0});
    const int a16 =
        b.accessor(u16, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_SCALAR, 3);
    const int a8 = b.accessor(i8, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, 1);
    std::vector<uint32_t> indices;
    ASSERT_TRUE(read_accessor(b.model, a16, TINYGLTF_TYPE_SCALAR, kU16, &indices).ok());
    EXPECT_EQ(indices, (std::vector<uint32_t>{0, 65535, 7}));
    std::vector<float> values;
    ASSERT_TRUE(read_accessor(b.model, a8, TINYGLTF_TYPE_VEC4, kI8, &values).ok());
    EXPECT_EQ(values, (std::vector<float>{-5, 100, -128, 0}));
}

// §3.6.2.2: signed c / (2^(n-1) - 1) clamped to -1, unsigned c / (2^n - 1).
TEST(GltfAccessors, DecodesNormalizedIntegers) {
    ModelBuilder b;
    const int i8 = b.view(std::vector<int8_t>{-128, -127, 0, 127});
    const int u8 = b.view(std::vector<uint8_t>{0, 51, 255, 255});
    const int i16 = b.view(std::vector<int16_t>{-32768, 32767, -16384, 0});
    const int u16 = b.view(std::vector<uint16_t>{0, 65535, 13107, 0});
    struct Case {
        int view, type;
        unsigned format;
        std::vector<float> expected;
    };
    const Case cases[] = {
        {i8, TINYGLTF_COMPONENT_TYPE_BYTE, kI8N, {-1.0f, -1.0f, 0.0f, 1.0f}},
        {u8, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, kU8N, {0.0f, 0.2f, 1.0f, 1.0f}},
        {i16, TINYGLTF_COMPONENT_TYPE_SHORT, kI16N, {-1.0f, 1.0f, float(-16384 / 32767.0), 0.0f}},
        {u16, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, kU16N, {0.0f, 1.0f, 0.2f, 0.0f}},
    };
    for (const Case& c : cases) {
        const int acc = b.accessor(c.view, c.type, TINYGLTF_TYPE_VEC4, 1, true);
        std::vector<float> out;
        const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC4, c.format, &out);
        ASSERT_TRUE(e.ok()) << e.message;
        ASSERT_EQ(out.size(), 4u);
        for (size_t i = 0; i < 4; ++i) EXPECT_FLOAT_EQ(out[i], c.expected[i]) << c.type << " " << i;
    }
}

TEST(GltfAccessors, NormalizedFlagSelectsTheFormat) {
    ModelBuilder b;
    const int view = b.view(std::vector<uint8_t>{255, 0, 0, 0});
    const int plain =
        b.accessor(view, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, 1);
    std::vector<float> out;
    // Plain UNSIGNED_BYTE is not accepted where only normalized bytes are.
    const BakeError e = read_accessor(b.model, plain, TINYGLTF_TYPE_VEC4, kU8N | kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: component type UNSIGNED_BYTE is not allowed here");
    // Normalized FLOAT exists in no format (§3.6.2.2).
    const int fview = b.view(std::vector<float>{1});
    const int nfloat =
        b.accessor(fview, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 1, true);
    const BakeError f = read_accessor(b.model, nfloat, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(f.code, BakeErrorCode::malformed_input);
    EXPECT_NE(f.message.find("FLOAT (normalized) is not allowed here"), std::string::npos)
        << f.message;
}

TEST(GltfAccessors, HonoursByteStrideAndOffset) {
    ModelBuilder b;
    // VEC2 floats every 16 bytes (2 floats of padding), starting 4 bytes into the view.
    const int view = b.view(std::vector<float>{-1, 1, 2, -1, -1, 3, 4, -1, -1, 5, 6}, 16);
    const int acc =
        b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 3, false, 4);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC2, kF32, &out);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(out, (std::vector<float>{1, 2, 3, 4, 5, 6}));
}

TEST(GltfAccessors, RejectsAStrideSmallerThanTheElement) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1, 2, 3, 4, 5, 6}, 8);
    const int acc = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 2);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC3, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message,
              "accessor 0: bufferView 0: byteStride 8 is smaller than the element (12 bytes)");
}

TEST(GltfAccessors, RejectsElementsPastTheEndOfTheView) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1, 2, 3, 4, 5});
    const int acc = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, 2);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC3, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message,
              "accessor 0: 2 elements of 12 bytes at byteOffset 0 (stride 12) exceed bufferView 0 "
              "(byteLength 20)");
}

TEST(GltfAccessors, RejectsAViewPastTheEndOfTheBuffer) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1, 2, 3});
    b.model.bufferViews[size_t(view)].byteLength = 16;
    const int acc = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 1);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_NE(e.message.find("exceeds buffer 0 (12 bytes)"), std::string::npos) << e.message;
}

TEST(GltfAccessors, RejectsOutOfRangeIndices) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1});
    b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 1);
    std::vector<float> out;
    BakeError e = read_accessor(b.model, 7, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 7 out of range (accessor count 1)");
    e = read_accessor(b.model, -1, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);

    b.accessor(3, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 1);  // no view 3
    e = read_accessor(b.model, 1, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 1: bufferView 3 out of range (bufferView count 1)");

    b.model.bufferViews[0].buffer = 2;  // no buffer 2
    e = read_accessor(b.model, 0, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: bufferView 0: buffer 2 out of range (buffer count 1)");
}

TEST(GltfAccessors, RejectsTheWrongTypeAndAnEmptyAccessor) {
    ModelBuilder b;
    const int view = b.view(std::vector<float>{1, 2});
    const int vec2 = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 1);
    const int empty = b.accessor(view, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 0);
    std::vector<float> out;
    BakeError e = read_accessor(b.model, vec2, TINYGLTF_TYPE_VEC3, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: type VEC2, expected VEC3");
    e = read_accessor(b.model, empty, TINYGLTF_TYPE_VEC2, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 1: count is 0");
}

// §3.6.2.3: no bufferView means zeros; sparse values replace the elements at their indices.
TEST(GltfAccessors, AppliesSparseValuesOverZeros) {
    ModelBuilder b;
    const int indices = b.view(std::vector<uint16_t>{1, 3});
    const int values = b.view(std::vector<float>{10, 11, 30, 31});
    const int acc = b.accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, 4);
    auto& sparse = b.model.accessors[size_t(acc)].sparse;
    sparse.isSparse = true;
    sparse.count = 2;
    sparse.indices.bufferView = indices;
    sparse.indices.byteOffset = 0;
    sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
    sparse.values.bufferView = values;
    sparse.values.byteOffset = 0;
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_VEC2, kF32, &out);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(out, (std::vector<float>{0, 0, 10, 11, 0, 0, 30, 31}));
}

TEST(GltfAccessors, AppliesSparseValuesOverDenseData) {
    ModelBuilder b;
    const int dense = b.view(std::vector<uint8_t>{1, 2, 3, 4, 5});
    const int indices = b.view(std::vector<uint32_t>{4});
    const int values = b.view(std::vector<uint8_t>{200});
    const int acc =
        b.accessor(dense, TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_SCALAR, 5);
    auto& sparse = b.model.accessors[size_t(acc)].sparse;
    sparse.isSparse = true;
    sparse.count = 1;
    sparse.indices.bufferView = indices;
    sparse.indices.byteOffset = 0;
    sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    sparse.values.bufferView = values;
    sparse.values.byteOffset = 0;
    std::vector<uint32_t> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kU8, &out);
    ASSERT_TRUE(e.ok()) << e.message;
    EXPECT_EQ(out, (std::vector<uint32_t>{1, 2, 3, 4, 200}));
}

TEST(GltfAccessors, RejectsMalformedSparseData) {
    ModelBuilder b;
    const int indices = b.view(std::vector<uint8_t>{2, 1});  // not increasing
    const int values = b.view(std::vector<float>{7, 8});
    const int acc = b.accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 3);
    auto& sparse = b.model.accessors[size_t(acc)].sparse;
    sparse.isSparse = true;
    sparse.count = 2;
    sparse.indices.bufferView = indices;
    sparse.indices.byteOffset = 0;
    sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    sparse.values.bufferView = values;
    sparse.values.byteOffset = 0;
    std::vector<float> out;
    BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: sparse index 1 is out of range or not increasing");

    sparse.count = 4;  // more than the accessor's 3 elements
    e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: sparse count 4 out of range (accessor count 3)");

    // tinygltf keeps a JSON count of 2^31 as INT_MIN; the message shows 2^31, not a negative.
    sparse.count = int(uint32_t(1) << 31);
    e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.message, "accessor 0: sparse count 2147483648 out of range (accessor count 3)");

    sparse.count = 2;
    sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
    e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: sparse indices have component type FLOAT");

    sparse.indices.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
    sparse.values.bufferView = 9;
    e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::malformed_input);
    EXPECT_EQ(e.message, "accessor 0: sparse: bufferView 9 out of range (bufferView count 2)");
}

// Zero-filled accessors are not bounded by the file size; past the cap they are refused as
// unsupported (the file may be valid), not as malformed.
TEST(GltfAccessors, RefusesHugeZeroFilledAccessorsAsUnsupported) {
    ModelBuilder b;
    const int acc = b.accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR,
                               kMaxZeroFilledElements + 1);
    std::vector<float> out;
    const BakeError e = read_accessor(b.model, acc, TINYGLTF_TYPE_SCALAR, kF32, &out);
    EXPECT_EQ(e.code, BakeErrorCode::unsupported);
    EXPECT_NE(e.message.find("elements without a bufferView"), std::string::npos) << e.message;
    const int fits = b.accessor(-1, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_SCALAR, 3);
    ASSERT_TRUE(read_accessor(b.model, fits, TINYGLTF_TYPE_SCALAR, kF32, &out).ok());
    EXPECT_EQ(out, (std::vector<float>{0, 0, 0}));
}

}  // namespace
}  // namespace stipple::bake::gltf
