// tinygltf as clpt configures it: every file that includes tiny_gltf.h includes it through here,
// because the header's class declarations change with these macros (a TinyGLTF built with its
// image writer in one file and without it in another does not link). No stb_image: images are
// not decoded (textures are a later issue); no default file system: gltf_document.cpp serves the
// buffers it has checked and nothing else; no external images are opened.
#pragma once

#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>
