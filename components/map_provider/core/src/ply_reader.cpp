#include "ply_reader.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "uampc/world/coordinate_bound.hpp"

namespace uampc::world {
namespace {

enum class Format { kAscii, kBinaryLittle, kBinaryBig };

struct Property {
  std::string name;
  int size = 0;     // bytes of the value (of each item for lists)
  char kind = 'f';  // 'i' signed, 'u' unsigned, 'f' floating
  bool is_list = false;
  int count_size = 0;  // lists: bytes of the item count
  char count_kind = 'u';
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
};

bool typeOf(const std::string& t, int& size, char& kind) {
  static const struct {
    const char* name;
    int size;
    char kind;
  } kTypes[] = {{"char", 1, 'i'},  {"int8", 1, 'i'},    {"uchar", 1, 'u'},  {"uint8", 1, 'u'},
                {"short", 2, 'i'}, {"int16", 2, 'i'},   {"ushort", 2, 'u'}, {"uint16", 2, 'u'},
                {"int", 4, 'i'},   {"int32", 4, 'i'},   {"uint", 4, 'u'},   {"uint32", 4, 'u'},
                {"float", 4, 'f'}, {"float32", 4, 'f'}, {"double", 8, 'f'}, {"float64", 8, 'f'}};
  for (const auto& k : kTypes) {
    if (t == k.name) {
      size = k.size;
      kind = k.kind;
      return true;
    }
  }
  return false;
}

// Reads values one at a time from the data part, never past its end.
class DataReader {
 public:
  DataReader(std::string data, Format format, const std::string& path, std::size_t header_lines)
      : data_(std::move(data)), format_(format), path_(path), header_lines_(header_lines) {
    if (format_ == Format::kAscii) ascii_.str(data_);
  }

  double read(int size, char kind) {
    if (format_ == Format::kAscii) {
      std::string token;
      if (!(ascii_ >> token)) fail("data ends early");
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end != token.c_str() + token.size()) fail("'" + token + "' is not a number");
      return v;
    }
    if (position_ + static_cast<std::size_t>(size) > data_.size()) fail("data ends early");
    unsigned char bytes[8];
    std::memcpy(bytes, data_.data() + position_, static_cast<std::size_t>(size));
    position_ += static_cast<std::size_t>(size);
    const bool little_host = [] {
      const std::uint16_t one = 1;
      unsigned char first;
      std::memcpy(&first, &one, 1);
      return first == 1;
    }();
    if ((format_ == Format::kBinaryLittle) != little_host) {
      for (int i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    }
    switch (kind) {
      case 'f':
        if (size == 4) {
          float f;
          std::memcpy(&f, bytes, 4);
          return f;
        } else {
          double d;
          std::memcpy(&d, bytes, 8);
          return d;
        }
      case 'i': {
        std::int64_t v = 0;
        if (size == 1) v = static_cast<std::int8_t>(bytes[0]);
        if (size == 2)
          v = [&] {
            std::int16_t x;
            std::memcpy(&x, bytes, 2);
            return x;
          }();
        if (size == 4)
          v = [&] {
            std::int32_t x;
            std::memcpy(&x, bytes, 4);
            return x;
          }();
        return static_cast<double>(v);
      }
      default: {
        std::uint64_t v = 0;
        if (size == 1) v = bytes[0];
        if (size == 2)
          v = [&] {
            std::uint16_t x;
            std::memcpy(&x, bytes, 2);
            return x;
          }();
        if (size == 4)
          v = [&] {
            std::uint32_t x;
            std::memcpy(&x, bytes, 4);
            return x;
          }();
        return static_cast<double>(v);
      }
    }
  }

  // Upper bound of the values still to read (to refuse absurd counts before allocating).
  std::size_t remainingValues() const {
    return format_ == Format::kAscii ? data_.size() / 2 + 1 : data_.size() - position_;
  }

  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error(path_ + ": corrupt PLY data: " + what);
  }

  // Where the value last read is, to name it in an error: "FILE:LINE: " in ASCII data (counted
  // only then), "FILE: " in binary data, where the caller names the element's index.
  std::string where() {
    if (format_ != Format::kAscii) return path_ + ": ";
    const std::streamoff pos = ascii_.tellg();  // -1 once the data's end was reached
    const auto end = pos < 0 ? data_.end() : data_.begin() + pos;
    const auto line = header_lines_ + 1 + static_cast<std::size_t>(std::count(data_.begin(), end, '\n'));
    return path_ + ":" + std::to_string(line) + ": ";
  }

 private:
  std::string data_;
  Format format_;
  std::string path_;
  std::size_t header_lines_;
  std::istringstream ascii_;
  std::size_t position_ = 0;
};

struct PlyHeader {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t lines = 0;  // "ply" to end_header
};

using BadPly = std::function<std::runtime_error(const std::string&)>;

// A property line: "property TYPE NAME" or "property list COUNT_TYPE ITEM_TYPE NAME".
Property readProperty(std::istringstream& words, const std::string& line, const BadPly& bad) {
  Property p;
  std::string type;
  words >> type;
  if (type == "list") {
    std::string count_type, item_type;
    words >> count_type >> item_type >> p.name;
    p.is_list = true;
    if (!typeOf(count_type, p.count_size, p.count_kind) || p.count_kind == 'f' || !typeOf(item_type, p.size, p.kind)) {
      throw bad("bad list property '" + line + "'");
    }
  } else {
    words >> p.name;
    if (!typeOf(type, p.size, p.kind)) throw bad("unknown property type '" + type + "'");
  }
  if (p.name.empty()) throw bad("property without a name");
  return p;
}

// The header, from "ply" to end_header (at most 10,000 lines); `in` is left at the data.
PlyHeader readPlyHeader(std::istream& in, const BadPly& bad) {
  std::string line;
  if (!std::getline(in, line) || (line != "ply" && line != "ply\r")) throw bad("no 'ply' magic");
  PlyHeader header;
  bool have_format = false, ended = false;
  for (int n = 0; n < 10000 && std::getline(in, line); ++n) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "end_header") {
      ended = true;
      header.lines = static_cast<std::size_t>(n) + 2;  // with the "ply" line
      break;
    }
    if (key.empty() || key == "comment" || key == "obj_info") continue;
    if (key == "format") {
      std::string f;
      words >> f;
      if (f == "ascii")
        header.format = Format::kAscii;
      else if (f == "binary_little_endian")
        header.format = Format::kBinaryLittle;
      else if (f == "binary_big_endian")
        header.format = Format::kBinaryBig;
      else
        throw bad("unknown format '" + f + "'");
      have_format = true;
    } else if (key == "element") {
      Element e;
      long long count = -1;
      words >> e.name >> count;
      if (!words || count < 0) throw bad("bad element line '" + line + "'");
      e.count = static_cast<std::size_t>(count);
      header.elements.push_back(e);
    } else if (key == "property") {
      if (header.elements.empty()) throw bad("property before any element");
      header.elements.back().properties.push_back(readProperty(words, line, bad));
    } else {
      throw bad("unknown header line '" + line + "'");
    }
  }
  if (!have_format || !ended) throw bad("header without format or end_header");
  return header;
}

// Where an element's coordinates and face indices are among its properties (-1: none).
struct ElementColumns {
  int x = -1, y = -1, z = -1, face = -1;
};

ElementColumns columnsOf(const Element& e) {
  ElementColumns c;
  for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
    const Property& p = e.properties[static_cast<std::size_t>(k)];
    if (p.name == "x" && !p.is_list) c.x = k;
    if (p.name == "y" && !p.is_list) c.y = k;
    if (p.name == "z" && !p.is_list) c.z = k;
    if ((p.name == "vertex_indices" || p.name == "vertex_index") && p.is_list) c.face = k;
  }
  return c;
}

// A list property's items; kept (as vertex indices, out-of-range ones as the largest index) when
// `keep`, else read past.
std::vector<std::uint32_t> readList(DataReader& reader, const Element& e, const Property& p, bool keep) {
  const double n = reader.read(p.count_size, p.count_kind);
  if (!(n >= 0.0) || n > 1e6 || n != static_cast<double>(static_cast<std::int64_t>(n)) ||
      static_cast<std::size_t>(n) > reader.remainingValues()) {
    reader.fail("bad list length in element '" + e.name + "'");
  }
  std::vector<std::uint32_t> items;
  if (keep) items.reserve(static_cast<std::size_t>(n));
  for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
    const double value = reader.read(p.size, p.kind);
    if (keep) {
      const bool index = value >= 0.0 && value <= std::numeric_limits<std::uint32_t>::max();
      items.push_back(index ? static_cast<std::uint32_t>(value) : std::numeric_limits<std::uint32_t>::max());
    }
  }
  return items;
}

// A finite vertex beyond the coordinate bound is refused (coordinate_bound.hpp), checked as read,
// before float can turn it into infinity and the skip of non-finite vertices hides it.
void checkVertexBound(DataReader& reader, const Eigen::Vector3d& v, std::size_t index) {
  if (withinCoordinateBound(v)) return;
  throw std::runtime_error(reader.where() + "vertex " + std::to_string(index) + " (counted from 0) " +
                           beyondBoundText(v));
}

// One element's rows: vertices and faces go into contents, anything else is read past.
void readElement(DataReader& reader, const Element& e, const std::string& path, PlyContents& contents) {
  if (e.count > reader.remainingValues()) reader.fail("element '" + e.name + "' count too large");
  const bool is_vertex = e.name == "vertex";
  const bool is_face = e.name == "face";
  const ElementColumns c = columnsOf(e);
  if (is_vertex && (c.x < 0 || c.y < 0 || c.z < 0)) {
    throw std::runtime_error(path + ": PLY vertices have no x, y, z properties");
  }
  if (is_vertex) contents.vertices.reserve(e.count);
  if (is_face && c.face >= 0) contents.faces.reserve(e.count);
  for (std::size_t i = 0; i < e.count; ++i) {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int k = 0; k < static_cast<int>(e.properties.size()); ++k) {
      const Property& p = e.properties[static_cast<std::size_t>(k)];
      if (!p.is_list) {
        const double value = reader.read(p.size, p.kind);
        if (k == c.x) v.x() = value;
        if (k == c.y) v.y() = value;
        if (k == c.z) v.z() = value;
        continue;
      }
      const bool keep = is_face && k == c.face;
      std::vector<std::uint32_t> items = readList(reader, e, p, keep);
      if (keep) contents.faces.push_back(std::move(items));
    }
    if (is_vertex) {
      checkVertexBound(reader, v, i);
      contents.vertices.push_back(v.cast<float>());
    }
  }
}

}  // namespace

PlyContents readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open");
  const BadPly bad = [&](const std::string& what) { return std::runtime_error(path + ": not a valid PLY file: " + what); };
  const PlyHeader header = readPlyHeader(in, bad);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  DataReader reader(std::move(data), header.format, path, header.lines);
  PlyContents contents;
  for (const Element& e : header.elements) readElement(reader, e, path, contents);
  return contents;
}

}  // namespace uampc::world
