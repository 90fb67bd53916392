// Checks of mesh files before assimp reads them; see mesh_file_check.h.
#include "mesh_file_check.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace dss::mesh {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("cannot read mesh " + path + ": " + what);
}

std::string readAll(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

long lineOf(const std::string& text, std::size_t i) {
  return 1 + static_cast<long>(std::count(text.begin(), text.begin() + i, '\n'));
}

bool numberChar(char c) {
  return std::isdigit(static_cast<unsigned char>(c)) ||
         std::isspace(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.' ||
         c == 'e' || c == 'E';
}

// A stray character inside a number list stops assimp's index parser without advancing: it then
// appends the same value until memory runs out (three gigabytes for "0 1,2"). A count="N" that
// the file cannot hold makes it reserve N entries up front.
void checkCollada(const std::string& path) {
  const std::string text = readAll(path);
  static const char* const kLists[] = {"p", "vcount", "v", "h", "float_array", "int_array"};
  std::size_t pos = 0;
  while ((pos = text.find('<', pos)) != std::string::npos) {
    ++pos;
    std::size_t end = pos;
    while (end < text.size() &&
           (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_'))
      ++end;
    const std::string name = text.substr(pos, end - pos);
    const std::size_t open_end = text.find('>', end);
    if (open_end == std::string::npos) return;  // assimp's XML parser reports the file
    // Count attributes of any element.
    const std::string tag = text.substr(end, open_end - end);
    for (std::size_t c = tag.find("count"); c != std::string::npos; c = tag.find("count", c + 1)) {
      std::size_t k = c + 5;
      while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
      if (k >= tag.size() || tag[k] != '=') continue;
      ++k;
      while (k < tag.size() && std::isspace(static_cast<unsigned char>(tag[k]))) ++k;
      if (k >= tag.size() || (tag[k] != '"' && tag[k] != '\'')) continue;
      ++k;
      std::uint64_t n = 0;
      bool digits = false;
      while (k < tag.size() && std::isdigit(static_cast<unsigned char>(tag[k])) &&
             n <= text.size()) {
        n = 10 * n + static_cast<std::uint64_t>(tag[k] - '0');
        digits = true;
        ++k;
      }
      if (digits && n > text.size())
        fail(path, "line " + std::to_string(lineOf(text, end + c)) + ": <" + name +
                       "> declares a count larger than the file (" + std::to_string(text.size()) +
                       " bytes)");
    }
    if (std::find(std::begin(kLists), std::end(kLists), name) == std::end(kLists) ||
        text[open_end - 1] == '/') {  // not a number list, or an empty one (<p/>)
      pos = open_end;
      continue;
    }
    const std::size_t close = text.find('<', open_end + 1);
    const std::size_t stop = close == std::string::npos ? text.size() : close;
    for (std::size_t i = open_end + 1; i < stop; ++i) {
      const char c = text[i];
      if (numberChar(c)) continue;
      fail(path, "line " + std::to_string(lineOf(text, i)) + ": <" + name +
                     "> holds a character that is not part of a number" +
                     (std::isprint(static_cast<unsigned char>(c)) ? std::string(" ('") + c + "')"
                                                                  : std::string()));
    }
    pos = stop;
  }
}

}  // namespace

void checkMeshFile(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  if (ext == ".dae") return checkCollada(path);
  if (ext == ".stl" || ext == ".obj") return;  // assimp checks binary STL sizes itself
  fail(path,
       (ext.empty() ? std::string("a file without an extension") : "the format '" + ext + "'") +
           " is not read (meshes are STL, COLLADA .dae or OBJ; convert others, "
           "e.g. with meshlab or assimp export)");
}

}  // namespace dss::mesh
