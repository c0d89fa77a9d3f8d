#include "io/png_writer.h"

#include <cstdlib>
#include <memory>
#include <string>

#include "mesh/surface_mesh.h"

// Private to this translation unit (tinygltf is built without its copy of the writer).
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#define STBI_WRITE_NO_STDIO
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace tvf {
namespace {

struct StbFree {
  void operator()(unsigned char* p) const { std::free(p); }
};

std::vector<uint8_t> writeRgba8(const std::vector<uint8_t>& bytes, int width, int height) {
  int length = 0;
  const std::unique_ptr<unsigned char, StbFree> png(
      stbi_write_png_to_mem(bytes.data(), width * 4, width, height, 4, &length));
  if (!png) throw InputError("PNG encoding failed (out of memory)");
  return std::vector<uint8_t>(png.get(), png.get() + length);
}

void put32(uint8_t* p, uint32_t value) {
  for (int k = 0; k < 4; ++k) p[k] = static_cast<uint8_t>(value >> (24 - 8 * k));
}

// stb writes 8-bit samples only. A 16-bit RGBA row of width w is byte for byte an 8-bit RGBA row of width
// 2w (samples big-endian, as PNG stores them), and PNG's "Up" filter does not depend on the pixel size, so
// stb encodes the rows and the zlib stream; only the header's width and bit depth change (and its CRC).
std::vector<uint8_t> writeRgba16(const std::vector<uint16_t>& samples, int width, int height) {
  std::vector<uint8_t> bigEndian(samples.size() * 2);
  for (std::size_t i = 0; i < samples.size(); ++i) {
    bigEndian[2 * i] = static_cast<uint8_t>(samples[i] >> 8);
    bigEndian[2 * i + 1] = static_cast<uint8_t>(samples[i] & 0xFF);
  }
  const int savedFilter = stbi_write_force_png_filter;
  stbi_write_force_png_filter = 2;  // Up (stb writes the first row unfiltered, which Up means there)
  std::vector<uint8_t> png = writeRgba8(bigEndian, 2 * width, height);
  stbi_write_force_png_filter = savedFilter;
  // Signature (8), IHDR length (4), "IHDR" (4), width (4), height (4), bit depth (1), ..., CRC at 29.
  put32(&png[16], static_cast<uint32_t>(width));
  png[24] = 16;
  put32(&png[29], stbiw__crc32(&png[12], 17));
  return png;
}

}  // namespace

std::vector<uint8_t> encodePngRgba(const std::vector<uint16_t>& samples, int width, int height, int bits) {
  if (bits != 8 && bits != 16) throw InputError("PNG bit depth must be 8 or 16, got " + std::to_string(bits));
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192) {
    throw InputError("PNG size must be 1..8192 pixels per side, got " + std::to_string(width) + " x " +
                     std::to_string(height));
  }
  if (samples.size() != static_cast<std::size_t>(width) * height * 4) {
    throw InputError("PNG data has " + std::to_string(samples.size()) + " samples, expected " +
                     std::to_string(static_cast<std::size_t>(width) * height * 4));
  }
  if (bits == 16) return writeRgba16(samples, width, height);
  std::vector<uint8_t> bytes(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i] > 255) throw InputError("8-bit PNG sample out of range");
    bytes[i] = static_cast<uint8_t>(samples[i]);
  }
  return writeRgba8(bytes, width, height);
}

}  // namespace tvf
