// The one translation unit that compiles tinygltf (Debian ships it as a header; stb_image/stb_image_write,
// which it calls, come from Debian's libstb through PkgConfig::STB).
//
// Why our own copy even though Debian also ships libtinygltf.so: libassimp loads libdraco.so.7, which
// exports its own, ABI-incompatible build of tinygltf (117 tinygltf:: symbols). Left to the dynamic
// linker, tinygltf::TinyGLTF::LoadBinaryFromFile binds to draco's copy and crashes. Definitions compiled
// into the program take precedence over every shared library, so this file must stay.
#define TINYGLTF_IMPLEMENTATION
#include <tiny_gltf.h>
