// The one translation unit that compiles tinygltf (Debian's libtinygltf-dev 2.7.0 is
// header-only), configured as scene/tinygltf_config.h says, with the system's nlohmann-json.
// Compiled without clpt's warnings (CMakeLists.txt): the library's own code is not clpt's to change.
#include <fstream>  // tinygltf's writer uses std::ofstream but includes <fstream> only with its default file system

#define TINYGLTF_IMPLEMENTATION
#include "scene/tinygltf_config.h"
