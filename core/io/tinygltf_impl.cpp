// The one translation unit that compiles tinygltf. We build it ourselves instead of linking a shared
// library so that the same code serves the native and the emscripten builds. Images are never decoded:
// the field designer needs geometry only. These macros must match the ones in gltf_loader.cpp, because
// they change the layout and inline members of tinygltf::TinyGLTF.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wsign-compare"
#endif
#include <tiny_gltf.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
