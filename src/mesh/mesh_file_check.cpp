// Checks of mesh files before assimp reads them; see mesh_file_check.h.
#include "mesh_file_check.h"

#include <tinyxml.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <stdexcept>
#include <vector>

#include "../common/nesting_scan.h"
#include "../common/utf8_scan.h"

namespace dss::mesh {
namespace {

// Deeper than any exporter writes (node hierarchies of robots are a few tens of levels).
constexpr std::size_t kMaxColladaDepth = 256;

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
// appends the same value until memory runs out (three gigabytes for "0 1,2").
void scanColladaText(const std::string& path, const std::string& text) {
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

bool digitsOnly(const char* s) {
  if (!s || !*s) return false;
  for (; *s; ++s)
    if (!std::isdigit(static_cast<unsigned char>(*s))) return false;
  return true;
}

std::uint64_t tokens(const char* s) {
  std::uint64_t n = 0;
  bool in = false;
  for (; s && *s; ++s) {
    const bool space = std::isspace(static_cast<unsigned char>(*s));
    n += !space && !in;
    in = !space;
  }
  return n;
}

// The structure assimp's Collada reader takes on trust: counts larger than the file, a missing
// count attribute (it then reads an unset count and crashed, found by fuzz_mesh), arrays whose
// count is not their number of values, accessors reaching past their array, primitives without
// a count.
void checkColladaStructure(const std::string& path, const std::string& text) {
  TiXmlDocument doc;
  doc.Parse(text.c_str());
  if (doc.Error())
    fail(path, "line " + std::to_string(doc.ErrorRow()) + ": malformed XML: " + doc.ErrorDesc());
  static const char* const kArrays[] = {"float_array", "int_array",    "bool_array", "Name_array",
                                        "IDREF_array", "SIDREF_array", "token_array"};
  static const char* const kPrimitives[] = {"triangles",  "polylist",  "polygons", "lines",
                                            "linestrips", "tristrips", "trifans"};
  auto is = [](const std::string& name, const auto& list) {
    return std::find_if(std::begin(list), std::end(list),
                        [&](const char* n) { return name == n; }) != std::end(list);
  };
  auto at = [&path](const TiXmlElement* e, const std::string& what) {
    fail(path, "line " + std::to_string(e->Row()) + ": <" + e->Value() + "> " + what);
  };
  std::map<std::string, std::uint64_t> array_counts;  // id -> count
  std::vector<const TiXmlElement*> accessors;
  std::vector<const TiXmlElement*> stack;
  if (doc.RootElement()) stack.push_back(doc.RootElement());
  while (!stack.empty()) {
    const TiXmlElement* e = stack.back();
    stack.pop_back();
    const std::string name = e->Value();
    // A count the file cannot hold (every counted item takes at least a byte): assimp reserves
    // what it declares before reading.
    const char* declared = e->Attribute("count");
    if (digitsOnly(declared) &&
        (std::string(declared).size() > 18 || std::stoull(declared) > text.size()))
      at(e, "declares a count larger than the file (" + std::to_string(text.size()) + " bytes)");
    if (is(name, kArrays)) {
      const char* count = e->Attribute("count");
      if (!digitsOnly(count) || std::string(count).size() > 18)
        at(e, "needs a count attribute of digits");
      const std::uint64_t n = std::stoull(count);
      if (tokens(e->GetText()) != n)
        at(e, "holds " + std::to_string(tokens(e->GetText())) + " values, not its count " +
                  std::to_string(n));
      if (const char* id = e->Attribute("id")) array_counts[id] = n;
    } else if (name == "accessor") {
      accessors.push_back(e);
    } else if (is(name, kPrimitives)) {
      if (!digitsOnly(e->Attribute("count"))) at(e, "needs a count attribute of digits");
    }
    for (const TiXmlElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement())
      stack.push_back(c);
  }
  for (const TiXmlElement* e : accessors) {
    const char* count = e->Attribute("count");
    const char* stride = e->Attribute("stride");
    const char* offset = e->Attribute("offset");
    const char* source = e->Attribute("source");
    if (!digitsOnly(count) || std::string(count).size() > 18)
      at(e, "needs a count attribute of digits");
    if ((stride && (!digitsOnly(stride) || std::string(stride).size() > 9)) ||
        (offset && (!digitsOnly(offset) || std::string(offset).size() > 18)))
      at(e, "has a stride or offset that is not digits");
    if (!source || source[0] != '#' || !array_counts.count(source + 1))
      at(e, "needs a source naming an array of the file");
    const std::uint64_t n = std::stoull(count), st = stride ? std::stoull(stride) : 1,
                        off = offset ? std::stoull(offset) : 0, size = array_counts[source + 1];
    if (st == 0 || off > size || n > (size - off) / st)
      at(e, "reads past its array '" + std::string(source + 1) + "' of " + std::to_string(size) +
                " values");
  }
}

void checkCollada(const std::string& path) {
  const std::string text = readAll(path);
  scanColladaText(path, text);
  // assimp's reader recurses into nodes, tinyxml into elements; tinyxml needs UTF-8.
  const input_scan::NestingExcess deep = input_scan::xmlNesting(text, kMaxColladaDepth);
  if (deep.exceeded)
    fail(path, "line " + std::to_string(deep.line) + ": XML nesting deeper than " +
                   std::to_string(kMaxColladaDepth) + " levels");
  const input_scan::Utf8Error bad = input_scan::firstInvalidUtf8(text);
  if (bad.found) throw std::runtime_error("cannot read mesh " + input_scan::utf8Message(path, bad));
  checkColladaStructure(path, text);
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
