#include "texture/exemplar_image.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "mesh/surface_mesh.h"

namespace tvf {

bool isPowerOfTwo(int n) { return n > 0 && (n & (n - 1)) == 0; }

ExemplarImage exemplarFromRGBA8(const uint8_t* rgba, int width, int height) {
  if (width != height || !isPowerOfTwo(width) || width < 4 || width > 1024)
    throw InputError("exemplar must be square with a power-of-two side in [4, 1024] (got " + std::to_string(width) +
                     "x" + std::to_string(height) + ")");
  if (!rgba) throw InputError("exemplar: no pixel data");
  ExemplarImage image;
  image.size = width;
  image.rgb.resize(3 * static_cast<size_t>(width) * height);
  for (size_t p = 0; p < static_cast<size_t>(width) * height; ++p)
    for (int c = 0; c < 3; ++c) image.rgb[3 * p + c] = rgba[4 * p + c] / 255.0f;
  return image;
}

std::vector<uint8_t> exemplarToRGBA8(const ExemplarImage& image) {
  std::vector<uint8_t> out(4 * static_cast<size_t>(image.pixels()));
  for (size_t p = 0; p < static_cast<size_t>(image.pixels()); ++p) {
    for (int c = 0; c < 3; ++c) {
      const float v = std::clamp(image.rgb[3 * p + c], 0.0f, 1.0f);
      out[4 * p + c] = static_cast<uint8_t>(std::lround(v * 255.0f));
    }
    out[4 * p + 3] = 255;
  }
  return out;
}

ExemplarImage shiftedExemplar(const ExemplarImage& image, int dx, int dy) {
  ExemplarImage out = image;
  for (int y = 0; y < image.size; ++y)
    for (int x = 0; x < image.size; ++x) std::copy_n(image.at(x, y), 3, out.at(x + dx, y + dy));
  return out;
}

}  // namespace tvf
