// Mesh files through assimp (Debian 12: libassimp-dev 5.2). assimp is asked to triangulate,
// join identical vertices, bake node transforms into the vertices, split meshes by primitive type
// and validate its own data structure; it is never asked to generate normals. Everything it
// returns is checked again (scene/assimp_mesh.cpp) before clpt uses it.
#include "scene/mesh_file.h"

#include <assimp/BaseImporter.h>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <memory>
#include <set>
#include <system_error>
#include <vector>

#include "scene/assimp_mesh.h"

namespace clpt {
namespace {

// Triangulation comes after clpt has set each mesh's primitive types from its faces
// (declare_primitive_types: assimp's own may claim polygons that are not there, and its
// triangulation then aborts). Joining identical vertices comes after clpt's finiteness check
// (parse_mesh_file): assimp's joining merges a NaN vertex into another one, and the NaN would go
// unseen.
constexpr unsigned kImportFlags = aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure;
constexpr unsigned kTriangulateFlags = aiProcess_Triangulate | aiProcess_SortByPType;
constexpr unsigned kJoinFlags = aiProcess_JoinIdenticalVertices;

// Where the PLY header's end_header line ends (a line starting with the word, followed by a
// space, a tab, the line's end or the end of the file), or npos. Not any whitespace: assimp ends
// the word only at those (and NUL or form feed), and "end_header" followed by a vertical tab made
// it loop as if there were no end_header at all (found by fuzz_mesh_file, 2026-12-04).
size_t ply_header_end(std::string_view bytes) {
  constexpr std::string_view kLine = "\nend_header";
  constexpr std::string_view kWordEnds = " \t\r\n";
  for (size_t at = bytes.find(kLine); at != std::string_view::npos; at = bytes.find(kLine, at + 1)) {
    const size_t after = at + kLine.size();
    if (after == bytes.size() || kWordEnds.find(bytes[after]) != std::string_view::npos) return after;
  }
  return std::string_view::npos;
}

// `bytes` with every OBJ `mtllib` statement turned into a comment (its first letter replaced by
// '#'; the length is unchanged). clpt takes materials from the scene and reads no .mtl file, and
// assimp 5.2's OBJ reader crashed (SEGV) on an `mtllib` line followed by a line starting with
// "map_K" (found by fuzz_mesh_file).
std::string without_obj_material_libraries(std::string_view bytes) {
  std::string out(bytes);
  constexpr std::string_view kStatement = "mtllib";
  for (size_t line = 0; line < out.size();) {
    size_t at = line;
    while (at < out.size() && (out[at] == ' ' || out[at] == '\t')) ++at;
    if (out.compare(at, kStatement.size(), kStatement) == 0) out[at] = '#';
    const size_t end = out.find('\n', line);
    line = end == std::string::npos ? out.size() : end + 1;
  }
  return out;
}

// `bytes` (a PLY file whose header refuse_what_assimp_cannot_handle has passed) with the vertex
// properties texture_s and texture_t renamed texture_u and texture_v (the same length: the body,
// binary or not, is unchanged). assimp 5.2 reads texture coordinates from vertex properties s/t,
// u/v, tx/ty and texture_u/texture_v but not texture_s/texture_t, which other PLY writers use. A
// vertex element that already has a property assimp reads for that coordinate keeps its names.
std::string with_ply_texture_st_as_uv(std::string_view bytes) {
  std::string out(bytes);
  const size_t header_end = ply_header_end(bytes);
  static const std::set<std::string_view> kReadAsU = {"u", "s", "tx", "texture_u"}, kReadAsV = {"v", "t", "ty", "texture_v"};
  // The lines of the header, split into words, with where each line's last word starts.
  struct Line {
    std::vector<std::string_view> words;
    size_t last_word_at = 0;
  };
  std::vector<Line> lines;
  for (size_t begin = 0; begin < header_end;) {
    size_t end = out.find('\n', begin);
    if (end == std::string::npos || end > header_end) end = header_end;
    Line line;
    for (size_t at = begin; at < end;) {
      while (at < end && std::isspace(static_cast<unsigned char>(bytes[at]))) ++at;
      size_t stop = at;
      while (stop < end && !std::isspace(static_cast<unsigned char>(bytes[stop]))) ++stop;
      if (stop > at) line.words.push_back(bytes.substr(at, stop - at)), line.last_word_at = at;
      at = stop;
    }
    lines.push_back(line);
    begin = end + 1;
  }
  for (size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].words.size() != 3 || lines[i].words[0] != "element" || lines[i].words[1] != "vertex") continue;
    size_t stop = i + 1;
    bool has_u = false, has_v = false;
    for (; stop < lines.size() && (lines[stop].words.empty() || lines[stop].words[0] != "element"); ++stop)
      if (lines[stop].words.size() == 3 && lines[stop].words[0] == "property") {
        has_u = has_u || kReadAsU.count(lines[stop].words[2]);
        has_v = has_v || kReadAsV.count(lines[stop].words[2]);
      }
    for (size_t k = i + 1; k < stop; ++k) {
      const Line& line = lines[k];
      if (line.words.size() != 3 || line.words[0] != "property") continue;
      if (!has_u && line.words[2] == "texture_s") out.replace(line.last_word_at, 9, "texture_u");
      if (!has_v && line.words[2] == "texture_t") out.replace(line.last_word_at, 9, "texture_v");
    }
  }
  return out;
}

// Throws MeshFileError naming the line (1-based) unless `header` (the bytes up to end_header)
// is a PLY header by the format's grammar: "ply", one "format ascii|binary_little_endian|
// binary_big_endian 1.0", then comment, obj_info, "element NAME COUNT", "property TYPE NAME" and
// "property list TYPE TYPE NAME" lines (properties after an element), and "end_header". assimp
// 5.2's PLY reader wrote past its buffers on headers with mangled lines (a line
// "propertyformat binary_big_endian 1.0blue", elements declared twice; found by fuzz_mesh_file).
// It also refuses a header whose elements cannot fit in the `body_bytes` after it, counting each
// value's least size (ASCII: a digit and a separator; binary: its type's size; a list: its count),
// because assimp allocates what the header declares before it reads a byte of the body (a 2 kB
// PLY declaring 33,333,324 vertices ran the fuzzer out of memory). An element with a count but no
// properties is refused for the same reason: it would need no bytes at all.
void check_ply_header(std::string_view header, size_t body_bytes) {
  static const std::map<std::string_view, unsigned> kTypeBytes = {
      {"char", 1},  {"uchar", 1},   {"short", 2},   {"ushort", 2},  {"int", 4},     {"uint", 4},
      {"float", 4}, {"double", 8},  {"int8", 1},    {"uint8", 1},   {"int16", 2},   {"uint16", 2},
      {"int32", 4}, {"uint32", 4},  {"float32", 4}, {"float64", 8}};
  static const std::set<std::string_view> kFormats = {"ascii", "binary_little_endian", "binary_big_endian"};
  auto is_count = [](std::string_view w) {
    return !w.empty() && w.size() <= 10 && std::all_of(w.begin(), w.end(), [](char c) { return c >= '0' && c <= '9'; });
  };
  bool ascii = true;
  bool in_element = false;
  size_t line_number = 0;
  // The element being declared: its header line, its name, its count and the fewest bytes one takes.
  size_t element_line = 0;
  std::string element_name;
  double element_count = 0, element_bytes = 0;
  double body_bytes_needed = 0;  // double: counts of up to 10 digits times many properties
  auto close_element = [&] {
    if (element_line == 0) return;
    if (element_count > 0 && element_bytes == 0)
      throw MeshFileError("line " + std::to_string(element_line) + " of the PLY header declares element '" +
                          element_name + "' without properties");
    body_bytes_needed += element_count * element_bytes;
    if (body_bytes_needed > static_cast<double>(body_bytes))
      throw MeshFileError("line " + std::to_string(element_line) + " of the PLY header declares " +
                          std::to_string(static_cast<unsigned long long>(element_count)) + " '" + element_name +
                          "' elements, more than the " + std::to_string(body_bytes) +
                          " bytes after end_header can hold (the elements up to it need at least " +
                          std::to_string(static_cast<unsigned long long>(body_bytes_needed)) + ")");
  };
  auto value_bytes = [&](std::string_view type) { return ascii ? 2.0 : double(kTypeBytes.at(type)); };
  for (size_t begin = 0; begin < header.size();) {
    size_t end = header.find('\n', begin);
    if (end == std::string_view::npos) end = header.size();
    const std::string_view line = header.substr(begin, end - begin);
    begin = end + 1;
    ++line_number;
    std::vector<std::string_view> words;
    for (size_t at = 0; at < line.size();) {
      while (at < line.size() && std::isspace(static_cast<unsigned char>(line[at]))) ++at;
      size_t stop = at;
      while (stop < line.size() && !std::isspace(static_cast<unsigned char>(line[stop]))) ++stop;
      if (stop > at) words.push_back(line.substr(at, stop - at));
      at = stop;
    }
    bool ok;
    if (line_number == 1) ok = words.size() == 1 && words[0] == "ply";
    else if (line_number == 2) {
      ok = words.size() == 3 && words[0] == "format" && kFormats.count(words[1]) && words[2] == "1.0";
      ascii = ok && words[1] == "ascii";
    } else if (words.empty()) ok = true;
    else if (words[0] == "comment" || words[0] == "obj_info") ok = true;
    else if (words[0] == "element") {
      ok = in_element = words.size() == 3 && is_count(words[2]);
      if (ok) {
        close_element();
        element_line = line_number;
        element_name = std::string(words[1].substr(0, 40));
        element_count = std::stod(std::string(words[2]));
        element_bytes = 0;
      }
    } else if (words[0] == "property" && words.size() == 3) {
      ok = in_element && kTypeBytes.count(words[1]);
      if (ok) element_bytes += value_bytes(words[1]);
    } else if (words[0] == "property" && words.size() == 5) {
      ok = in_element && words[1] == "list" && kTypeBytes.count(words[2]) && kTypeBytes.count(words[3]);
      if (ok) element_bytes += value_bytes(words[2]);  // the list's count; the list may be empty
    } else {
      ok = words.size() == 1 && words[0] == "end_header";
      if (ok) close_element();
    }
    if (!ok) {
      std::string shown(line.substr(0, 80));
      std::replace_if(shown.begin(), shown.end(), [](char c) { return c == '\r' || c == '\t'; }, ' ');
      throw MeshFileError("line " + std::to_string(line_number) + " of the PLY header is not a PLY header line: '" +
                          shown + "'");
    }
  }
}

// Inputs on which assimp 5.2 does not come back, refused before it sees them (found by
// tests/fuzz/fuzz_mesh_file; README "Known library crashes and leaks").
void refuse_what_assimp_cannot_handle(std::string_view bytes, const std::string& extension) {
  // A PLY header without its end_header line: assimp's PLY reader loops for minutes (or for
  // ever) looking for it, even on a 200-byte file. "end_header" elsewhere (in a comment) is not
  // enough: it must start a line and end at whitespace or the end of the file.
  // OBJ is text; one with NUL bytes in it made assimp's OBJ reader crash (SEGV).
  if (extension == "obj") {
    const size_t nul = bytes.find('\0');
    if (nul != std::string_view::npos)
      throw MeshFileError("an OBJ file is text, but byte " + std::to_string(nul) + " is NUL");
  }
  if (extension != "ply") return;
  const size_t header_end = ply_header_end(bytes);
  if (header_end == std::string_view::npos) throw MeshFileError("the PLY header has no 'end_header' line");
  // The PLY header is ASCII text by the format's definition. A header with other bytes in its
  // property lines made assimp's triangulation fail an internal assertion and abort the process.
  for (size_t i = 0; i < header_end; ++i) {
    const unsigned char c = static_cast<unsigned char>(bytes[i]);
    if (c >= 0x80 || (c < 0x20 && c != '\n' && c != '\r' && c != '\t'))
      throw MeshFileError("the PLY header has a byte that is not ASCII text at offset " + std::to_string(i));
  }
  check_ply_header(bytes.substr(0, header_end), bytes.size() - header_end);
}

// Leaves `importer` only the readers that claim `extension`. assimp picks a reader by the file's
// extension, but when that reader declines the contents it tries every other reader on them: a
// PLY file named .glb went to the PLY reader past clpt's PLY checks (they follow the extension)
// and corrupted the heap (found by fuzz_mesh_file). A file is now read as what its extension says
// or refused. Unregistered readers are no longer the importer's to delete, so they are deleted here.
void keep_only_readers_of(Assimp::Importer& importer, const std::string& extension) {
  for (size_t i = importer.GetImporterCount(); i-- > 0;) {
    Assimp::BaseImporter* reader = importer.GetImporter(i);
    std::set<std::string> claimed;
    reader->GetExtensionList(claimed);
    if (claimed.count(extension)) continue;
    if (importer.UnregisterLoader(reader) == aiReturn_SUCCESS) delete reader;
  }
}

}  // namespace

const std::vector<std::string>& mesh_file_extensions() {
  static const std::vector<std::string> extensions = {"obj", "ply", "glb", "gltf", "stl"};
  return extensions;
}

std::string mesh_file_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  const auto& known = mesh_file_extensions();
  if (std::find(known.begin(), known.end(), ext) != known.end()) return ext;
  std::string list;
  for (size_t i = 0; i < known.size(); ++i) list += (i ? ", ." : ".") + known[i];
  throw MeshFileError("unsupported mesh file type '" + (ext.empty() ? std::string("(no extension)") : "." + ext) +
                      "' (expected " + list + ")");
}

std::string resolve_mesh_path(const std::string& scene_file, const std::string& mesh_file) {
  const std::filesystem::path mesh(mesh_file);
  if (mesh.is_absolute()) return mesh_file;
  return (std::filesystem::path(scene_file).parent_path() / mesh).string();
}

std::string read_mesh_file(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(status))
    throw MeshFileError("cannot open mesh file: " + (ec ? ec.message() : std::string("No such file or directory")));
  if (!std::filesystem::is_regular_file(status)) throw MeshFileError("cannot open mesh file: not a regular file");
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) throw MeshFileError("cannot open mesh file: " + ec.message());
  if (size > kMaxMeshFileBytes)
    throw MeshFileError("mesh file is " + std::to_string(size) + " bytes, over the limit of " +
                        std::to_string(kMaxMeshFileBytes));
  errno = 0;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!file) throw MeshFileError(std::string("cannot open mesh file: ") + std::strerror(errno));
  std::string bytes(size, '\0');
  if (size > 0 && std::fread(bytes.data(), 1, size, file.get()) != size)
    throw MeshFileError("cannot read mesh file: it changed size while being read");
  return bytes;
}

MeshFileContents parse_mesh_file(std::string_view bytes, const std::string& extension) {
  if (bytes.empty()) throw MeshFileError("the mesh file is empty");
  refuse_what_assimp_cannot_handle(bytes, extension);
  const std::string text = extension == "obj"   ? without_obj_material_libraries(bytes)
                           : extension == "ply" ? with_ply_texture_st_as_uv(bytes)
                                                : std::string();
  if (extension == "obj" || extension == "ply") bytes = text;
  Assimp::Importer importer;
  keep_only_readers_of(importer, extension);
  const aiScene* scene = importer.ReadFileFromMemory(bytes.data(), bytes.size(), kImportFlags, extension.c_str());
  if (!scene) throw MeshFileError(std::string("assimp cannot read it: ") + importer.GetErrorString());
  // The importer owns the scene and its post-processing steps change it in place; the const of
  // ReadFileFromMemory's result is only a view.
  declare_primitive_types(const_cast<aiScene&>(*scene));
  scene = importer.ApplyPostProcessing(kTriangulateFlags);
  if (!scene) throw MeshFileError(std::string("assimp cannot triangulate it: ") + importer.GetErrorString());
  check_assimp_vertices(*scene);
  scene = importer.ApplyPostProcessing(kJoinFlags);
  if (!scene) throw MeshFileError(std::string("assimp cannot join its vertices: ") + importer.GetErrorString());
  return mesh_from_assimp(*scene);
}

}  // namespace clpt
