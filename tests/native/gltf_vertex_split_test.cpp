// SPDX-License-Identifier: GPL-2.0-or-later
// Splitting a kept glTF primitive's vertices for a per-corner attribute (io/gltf_vertex_split.h): accessors
// read whole however they are stored (interleaved with a stride, sparse, without a bufferView), a vertex per
// (source vertex, value) pair in source order, and bad accessors refused by name.
#include "io/gltf_vertex_split.h"

#include <gtest/gtest.h>

#include <cstring>

#include "common/input_error.h"

namespace {

using nlohmann::json;

// Three VEC2 floats interleaved with a 4-byte pad (stride 12) in buffer 0, a sparse substitute for element 2,
// and one accessor with no bufferView (zeros, one sparse value).
tvf::GltfSource strideAndSparseSource() {
  tvf::GltfSource s;
  std::vector<uint8_t> bytes(3 * 12 + 4 + 8, 0);
  const float values[3][2] = {{1, 2}, {3, 4}, {5, 6}};
  for (int i = 0; i < 3; ++i) std::memcpy(&bytes[12 * i], values[i], 8);
  const uint32_t sparseIndex = 2;
  std::memcpy(&bytes[36], &sparseIndex, 4);
  const float substitute[2] = {7, 8};
  std::memcpy(&bytes[40], substitute, 8);
  s.buffers.push_back(bytes);
  const json sparse = {{"count", 1},
                       {"indices", {{"bufferView", 1}, {"componentType", 5125}}},
                       {"values", {{"bufferView", 2}}}};
  s.document = {
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 36}, {"byteStride", 12}},
        {{"buffer", 0}, {"byteOffset", 36}, {"byteLength", 4}},
        {{"buffer", 0}, {"byteOffset", 40}, {"byteLength", 8}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}},
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}, {"sparse", sparse}},
        {{"componentType", 5126}, {"count", 3}, {"type", "VEC2"}, {"sparse", sparse}},
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "MAT2"}},
        {{"bufferView", 9}, {"componentType", 5126}, {"count", 3}, {"type", "VEC2"}}}}};
  return s;
}

std::vector<float> floats(const tvf::AccessorElements& e) {
  std::vector<float> out(e.bytes.size() / 4);
  std::memcpy(out.data(), e.bytes.data(), e.bytes.size());
  return out;
}

TEST(GltfVertexSplit, ReadsStridedSparseAndViewlessAccessors) {
  const tvf::GltfSource s = strideAndSparseSource();
  EXPECT_EQ(floats(tvf::readAccessorElements(s, 0, 3)), (std::vector<float>{1, 2, 3, 4, 5, 6}));
  EXPECT_EQ(floats(tvf::readAccessorElements(s, 1, 3)), (std::vector<float>{1, 2, 3, 4, 7, 8}));
  EXPECT_EQ(floats(tvf::readAccessorElements(s, 2, 3)), (std::vector<float>{0, 0, 0, 0, 7, 8}));
  const auto [min, max] = tvf::elementBounds(tvf::readAccessorElements(s, 1, 3));
  EXPECT_EQ(min, json({1.0, 2.0}));
  EXPECT_EQ(max, json({7.0, 8.0}));
}

TEST(GltfVertexSplit, RefusesBadAccessorsByName) {
  const tvf::GltfSource s = strideAndSparseSource();
  const auto message = [&](int accessor) {
    try {
      tvf::readAccessorElements(s, accessor, 3);
    } catch (const tvf::InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message(3).find("accessor 3 has 4 elements where its primitive has 3"), std::string::npos);
  EXPECT_NE(message(4).find("accessor 4 is not a vertex attribute's type (MAT2)"), std::string::npos);
  EXPECT_NE(message(5).find("bufferView that does not exist"), std::string::npos);
  EXPECT_NE(message(6).find("accessor 6 does not exist"), std::string::npos);
}

// Two triangles sharing the edge 1-2 of a quad 0-1-2-3: vertex 1 carries one value in both, vertex 2 two
// (a jump of one period across the shared edge), vertex 4 is used by no triangle and keeps one vertex.
TEST(GltfVertexSplit, AVertexPerSourceVertexAndValueInSourceOrder) {
  const std::vector<uint32_t> corners = {0, 1, 2, 2, 1, 3};
  const float values[12] = {0, 0, 1, 0, 1, 1, 2, 1, 1, 0, 2, 0};
  const tvf::VertexSplit split = tvf::splitVertices(5, corners, values);
  EXPECT_EQ(split.sourceVertex, (std::vector<uint32_t>{0, 1, 2, 2, 3, 4}));
  ASSERT_EQ(split.indices.size(), 6u);
  for (size_t c = 0; c < 6; ++c) {
    EXPECT_EQ(split.sourceVertex[split.indices[c]], corners[c]);
    EXPECT_EQ(split.values[2 * split.indices[c]], values[2 * c]);
    EXPECT_EQ(split.values[2 * split.indices[c] + 1], values[2 * c + 1]);
  }
  tvf::AccessorElements e;
  e.componentType = 5121, e.type = "SCALAR", e.components = 1, e.elementSize = 1, e.count = 5;
  e.bytes = {10, 11, 12, 13, 14};
  EXPECT_EQ(tvf::gatherElements(e, split.sourceVertex).bytes, (std::vector<uint8_t>{10, 11, 12, 12, 13, 14}));
}

}  // namespace
