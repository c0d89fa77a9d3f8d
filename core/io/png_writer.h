#pragma once
// PNG encoding through stb_image_write (Debian's libstb-dev): the same code, and so the same bytes, in the
// native and the WebAssembly builds.
#include <cstdint>
#include <vector>

namespace tvf {

// RGBA, 4 samples per pixel, row-major from the image's first row; bits is 8 or 16 (samples must fit).
// Throws InputError for a bad size or bit depth.
std::vector<uint8_t> encodePngRgba(const std::vector<uint16_t>& samples, int width, int height, int bits);

}  // namespace tvf
