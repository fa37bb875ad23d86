// The one translation unit that compiles tinygltf (Debian ships it as a header; the stb_image and
// stb_image_write implementations it calls come from Debian's libstb, linked through PkgConfig::STB).
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
