#pragma once
// A square, power-of-two, toroidal RGB image: the exemplar of texture synthesis and every level of its Gaussian
// stack. Colours are floats in [0, 1] (sRGB values as stored in the file; the analysis treats them as plain numbers).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace tvf {

struct ExemplarImage {
  int size = 0;             // width = height, a power of two
  std::vector<float> rgb;   // 3 per pixel, row-major, row y = pixels [y*size, (y+1)*size)

  int pixels() const { return size * size; }
  // Toroidal access: any integer x, y wraps onto the image.
  int wrap(int v) const { return v & (size - 1); }
  int index(int x, int y) const { return wrap(y) * size + wrap(x); }
  const float* at(int x, int y) const { return &rgb[3 * static_cast<std::size_t>(index(x, y))]; }
  float* at(int x, int y) { return &rgb[3 * static_cast<std::size_t>(index(x, y))]; }
};

bool isPowerOfTwo(int n);

// From 8-bit RGBA (4 bytes per pixel, alpha ignored). Throws InputError unless width == height is a power of two
// in [4, 1024] and the byte count matches.
ExemplarImage exemplarFromRGBA8(const uint8_t* rgba, int width, int height);
// Back to 8-bit RGBA (alpha 255), rounding and clamping.
std::vector<uint8_t> exemplarToRGBA8(const ExemplarImage& image);
// The image moved by (dx, dy) pixels on the torus: out(x + dx, y + dy) = in(x, y).
ExemplarImage shiftedExemplar(const ExemplarImage& image, int dx, int dy);

}  // namespace tvf
