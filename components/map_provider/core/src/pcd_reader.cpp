// PCD reading (pcd_reader.hpp; docs/decisions/pcd-own-reader.md). The file is read in three steps:
// its header and declared sizes are checked (as PCL 1.13 reads a header, so that a file we accept
// means the same to PCL-based tools), the fields x, y, z are chosen, and the data decoded.
#include "pcd_reader.hpp"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <locale>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "lzf.hpp"
#include "uampc/world/coordinate_bound.hpp"

namespace uampc::world {
namespace {

// The largest map read (1.2 GB as x, y, z floats; more than any map a scene needs).
constexpr std::size_t kMaxMapPoints = 100'000'000;
// LZF's best compression: 264 bytes from a 3-byte back reference (lzf.hpp).
constexpr std::size_t kMaxLzfRatio = 88;

// A field's TYPE and SIZE together, as PCL names its data types.
enum class PcdKind { kI1, kU1, kI2, kU2, kI4, kU4, kI8, kU8, kF4, kF8 };

struct PcdField {
  std::string name;
  PcdKind kind = PcdKind::kF4;
  std::size_t size = 4, count = 1;
  std::size_t offset = 0;  // bytes from the start of a point (binary data)
};

struct PcdLayout {
  std::vector<PcdField> fields;
  std::size_t point_step = 0;  // bytes per point
  std::size_t values = 0;      // values per point (sum of COUNT)
  std::size_t points = 0;
  std::string data;  // ascii, binary, binary_compressed
  std::size_t header_bytes = 0;
};

bool parseCount(const std::string& word, std::size_t& value) {
  if (word.empty() || word.size() > 12 || word.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  value = std::stoull(word);
  return true;
}

// PCL's header reader does not stop at DATA: it goes on reading lines (empty ones and comments
// skipped) for as long as their first word starts with a header keyword, and acts on them. Binary
// data whose first line reads "POINTS 357913941" made it allocate 4 GB. This finds the first such
// line after `pos`, as PCL 1.13 would read it; empty if PCL stops at once. PCL skips only lines
// that are empty; one of blanks ends its header.
std::string headerLineInData(const std::string& bytes, std::size_t pos) {
  static const char* const kKeywords[] = {"FIELDS", "COLUMNS", "SIZE",  "TYPE", "COUNT",
                                          "WIDTH",  "HEIGHT",  "VIEWPOINT", "POINTS", "DATA"};
  while (pos < bytes.size()) {
    std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos) eol = bytes.size();
    const std::string line = bytes.substr(pos, std::min<std::size_t>(eol - pos, 4096));
    pos = eol + 1;
    if (line.empty()) continue;
    std::istringstream in(line);
    std::string word;
    if (!(in >> word)) return {};
    if (word[0] == '#' || word.rfind("VERSION", 0) == 0) continue;
    for (const char* keyword : kKeywords) {
      if (word.rfind(keyword, 0) == 0) return keyword;
    }
    return {};
  }
  return {};
}

// The header's lines up to DATA, as written: what checkPcd checks next.
struct PcdHeader {
  std::vector<std::string> names, sizes, types, counts;
  std::size_t width = 0, height = 0;
  bool have_width = false, have_height = false, have_points = false;
};

using BadPcd = std::function<std::runtime_error(const std::string&)>;

// Reads the header's lines into header and layout (points, data, header_bytes).
void readPcdHeader(const std::string& bytes, const BadPcd& bad, PcdHeader& header, PcdLayout& layout) {
  std::size_t pos = 0, line_number = 0;
  while (layout.data.empty()) {
    const std::size_t eol = bytes.find('\n', pos);
    if (eol == std::string::npos || eol - pos > 4096) throw bad("header has no DATA line");
    std::string line = bytes.substr(pos, eol - pos);
    pos = eol + 1;
    ++line_number;
    // Read as PCL reads it, or PCL decodes another header than the one checked here: PCL skips
    // empty lines only, stops its header at a line of blanks (a fuzzed file then crashed it), and
    // splits words at spaces, tabs and carriage returns only.
    if (line.empty()) continue;
    if (line.find_first_of("\v\f") != std::string::npos) {
      throw bad("header line " + std::to_string(line_number) + " has a vertical tab or form feed");
    }
    if (line.find_first_not_of(" \t\r") == std::string::npos) {
      throw bad("header line " + std::to_string(line_number) + " is blank before DATA (PCL ends the header there)");
    }
    if (line.back() == '\r') line.pop_back();
    std::istringstream in(line);
    std::string key;
    in >> key;
    std::vector<std::string> w;
    for (std::string x; in >> x;) w.push_back(x);
    if (key[0] == '#') continue;
    if (key == "VERSION") continue;
    if (key == "FIELDS")
      header.names = w;
    else if (key == "SIZE")
      header.sizes = w;
    else if (key == "TYPE")
      header.types = w;
    else if (key == "COUNT")
      header.counts = w;
    else if (key == "WIDTH")
      header.have_width = w.size() == 1 && parseCount(w[0], header.width);
    else if (key == "HEIGHT")
      header.have_height = w.size() == 1 && parseCount(w[0], header.height);
    else if (key == "POINTS")
      header.have_points = w.size() == 1 && parseCount(w[0], layout.points);
    else if (key == "VIEWPOINT") {
      if (w.size() != 7) throw bad("VIEWPOINT needs 7 numbers");
    } else if (key == "DATA") {
      if (w.size() != 1 || (w[0] != "ascii" && w[0] != "binary" && w[0] != "binary_compressed")) {
        throw bad("unknown DATA kind");
      }
      layout.data = w[0];
    } else {
      throw bad("unknown header line '" + line.substr(0, 40) + "'");
    }
  }
  layout.header_bytes = pos;
}

// TYPE and SIZE as one kind (both already checked).
PcdKind kindOf(const std::string& type, std::size_t size) {
  const int log2_size = size == 1 ? 0 : size == 2 ? 1 : size == 4 ? 2 : 3;
  if (type == "F") return size == 4 ? PcdKind::kF4 : PcdKind::kF8;
  static constexpr PcdKind kSigned[] = {PcdKind::kI1, PcdKind::kI2, PcdKind::kI4, PcdKind::kI8};
  static constexpr PcdKind kUnsigned[] = {PcdKind::kU1, PcdKind::kU2, PcdKind::kU4, PcdKind::kU8};
  return type == "I" ? kSigned[log2_size] : kUnsigned[log2_size];
}

// FIELDS, SIZE, TYPE, COUNT and the point count agree; fills the layout's fields, point_step and
// values.
void checkPcdFields(const PcdHeader& header, const BadPcd& bad, PcdLayout& layout) {
  const std::size_t fields = header.names.size();
  if (fields == 0 || header.sizes.size() != fields || header.types.size() != fields ||
      (!header.counts.empty() && header.counts.size() != fields)) {
    throw bad("FIELDS, SIZE, TYPE and COUNT disagree");
  }
  if (!header.have_width || !header.have_height || !header.have_points || header.height == 0 ||
      header.width * header.height != layout.points) {
    throw bad("WIDTH, HEIGHT and POINTS missing or inconsistent");
  }
  for (std::size_t i = 0; i < fields; ++i) {
    std::size_t size = 0, count = 1;
    if (!parseCount(header.sizes[i], size) || (size != 1 && size != 2 && size != 4 && size != 8)) {
      throw bad("bad SIZE");
    }
    if (header.types[i] != "I" && header.types[i] != "U" && (header.types[i] != "F" || size < 4)) throw bad("bad TYPE");
    if (!header.counts.empty() && (!parseCount(header.counts[i], count) || count == 0 || count > 4096)) {
      throw bad("bad COUNT");
    }
    layout.fields.push_back({header.names[i], kindOf(header.types[i], size), size, count, layout.point_step});
    layout.point_step += size * count;
    layout.values += count;
  }
}

// The data after the header holds what the header declares, within the memory budget.
void checkPcdPayload(const std::string& bytes, const BadPcd& bad, const PcdLayout& layout) {
  // A memory budget checked before anything is allocated: the reader holds the file, the points
  // and, for binary_compressed, the data decompressed.
  if (layout.points > kMaxMapPoints) {
    throw bad(std::to_string(layout.points) + " points declared; maps of at most " + std::to_string(kMaxMapPoints) +
              " points are read");
  }
  const std::size_t payload = bytes.size() - layout.header_bytes;
  const std::size_t expected = layout.points * layout.point_step;
  if (layout.data == "binary" && payload < expected) throw bad("file shorter than its points");
  if (layout.data == "binary_compressed") {
    std::uint32_t sizes_word[2] = {0, 0};
    if (payload < 8) throw bad("compressed data missing");
    std::memcpy(sizes_word, bytes.data() + layout.header_bytes, 8);
    if (sizes_word[1] != expected || sizes_word[0] > payload - 8) {
      throw bad("compressed data sizes inconsistent");
    }
    // LZF encodes at most 264 bytes in a 3-byte back reference: a file claiming more than that
    // ratio lies about its size (a 171-byte file declaring 4.3 GB took 8.4 GB before it failed).
    if (expected > std::size_t{kMaxLzfRatio} * sizes_word[0]) {
      throw bad("declares " + std::to_string(expected) + " bytes of points in " + std::to_string(sizes_word[0]) +
                " compressed bytes, more than LZF can expand to");
    }
  }
}

PcdLayout checkPcd(const std::string& bytes, const BadPcd& bad) {
  PcdHeader header;
  PcdLayout layout;
  readPcdHeader(bytes, bad, header, layout);
  if (const std::string keyword = headerLineInData(bytes, layout.header_bytes); !keyword.empty()) {
    throw bad("the data after DATA starts with a line PCL reads as the header line '" + keyword + " ...'");
  }
  checkPcdFields(header, bad, layout);
  checkPcdPayload(bytes, bad, layout);
  return layout;
}

// ---- The fields x, y, z ----

// The field read for each of x, y, z. PCL 1.13 read the first field of the name that is F 4 of
// COUNT 1, and left the coordinate 0 when there was none; F 8 is read too now, and anything else
// refused rather than read as 0.
struct PcdXyz {
  std::size_t field[3] = {0, 0, 0};
};

std::optional<std::size_t> firstFieldOf(const PcdLayout& layout, const std::string& name, PcdKind kind) {
  for (std::size_t i = 0; i < layout.fields.size(); ++i) {
    const PcdField& f = layout.fields[i];
    if (f.name == name && f.kind == kind && f.count == 1) return i;
  }
  return std::nullopt;
}

PcdXyz chooseXyz(const PcdLayout& layout, const std::string& path) {
  static const char* const kAxes[] = {"x", "y", "z"};
  for (const char* axis : kAxes) {
    const bool named = std::any_of(layout.fields.begin(), layout.fields.end(), [&](const PcdField& f) { return f.name == axis; });
    if (!named) throw std::runtime_error(path + ": has no x, y, z fields");
  }
  PcdXyz xyz;
  for (int a = 0; a < 3; ++a) {
    std::optional<std::size_t> i = firstFieldOf(layout, kAxes[a], PcdKind::kF4);
    if (!i) i = firstFieldOf(layout, kAxes[a], PcdKind::kF8);
    if (!i) {
      throw std::runtime_error(path + ": field " + kAxes[a] +
                               " is not a float of COUNT 1 (x, y and z must be TYPE F, SIZE 4 or 8, COUNT 1)");
    }
    xyz.field[a] = *i;
  }
  return xyz;
}

// ---- Points as they are decoded ----

// Collects points in file order (the coordinates as read, in double), noting the first finite one
// beyond the coordinate bound: a coordinate of SIZE 8 beyond float's range is refused, not turned
// into infinity and skipped.
class PcdPoints {
 public:
  explicit PcdPoints(std::size_t n) { points_.reserve(n); }
  void add(const Eigen::Vector3d& p, std::size_t line = 0) {
    if (!beyond_ && !withinCoordinateBound(p)) {
      beyond_ = p;
      beyond_index_ = points_.size();
      beyond_line_ = line;
    }
    points_.push_back(p.cast<float>());
  }
  // Refuses the first point beyond the bound: by its line in an ASCII file, its index otherwise.
  std::vector<Eigen::Vector3f> take(const std::string& path, const PcdLayout& layout) {
    if (!beyond_) return std::move(points_);
    const std::string where = layout.data == "ascii"
                                  ? path + ":" + std::to_string(beyond_line_) + ": point "
                                  : path + ": point " + std::to_string(beyond_index_) + " (counted from 0) ";
    throw std::runtime_error(where + beyondBoundText(*beyond_));
  }

 private:
  std::vector<Eigen::Vector3f> points_;
  std::optional<Eigen::Vector3d> beyond_;
  std::size_t beyond_index_ = 0, beyond_line_ = 0;
};

double rawValue(const char* at, PcdKind kind) {
  if (kind == PcdKind::kF4) {
    float f;
    std::memcpy(&f, at, 4);
    return f;
  }
  double d;
  std::memcpy(&d, at, 8);
  return d;
}

// ---- binary and binary_compressed ----

// Points stored one after the other (x86 byte order, as PCL writes them).
void decodeBinary(const char* data, const PcdLayout& layout, const PcdXyz& xyz, PcdPoints& points) {
  const PcdField* f[3];
  for (int a = 0; a < 3; ++a) f[a] = &layout.fields[xyz.field[a]];
  for (std::size_t i = 0; i < layout.points; ++i) {
    const char* p = data + i * layout.point_step;
    points.add({rawValue(p + f[0]->offset, f[0]->kind), rawValue(p + f[1]->offset, f[1]->kind),
                rawValue(p + f[2]->offset, f[2]->kind)});
  }
}

// LZF-compressed fields one after the other: all points' first field, then their second, ...
void decodeCompressed(const std::string& bytes, const BadPcd& bad, const PcdLayout& layout, const PcdXyz& xyz,
                      PcdPoints& points) {
  // PCL 1.13 leaves fields named "_" (padding) out of this layout but not out of the declared
  // size, and then places the points at a stride without them: such files mean nothing certain.
  if (std::any_of(layout.fields.begin(), layout.fields.end(), [](const PcdField& f) { return f.name == "_"; })) {
    throw bad("binary_compressed data with a padding field '_' (PCL 1.13 misplaces its points) is not read");
  }
  std::uint32_t compressed_size = 0;
  std::memcpy(&compressed_size, bytes.data() + layout.header_bytes, 4);
  std::string plain(layout.points * layout.point_step, '\0');  // bounded by checkPcdPayload
  try {
    lzfDecompress(std::string_view(bytes).substr(layout.header_bytes + 8, compressed_size), plain.data(), plain.size());
  } catch (const LzfError& e) {
    throw bad(e.what());
  }
  const char* block[3];
  for (int a = 0; a < 3; ++a) block[a] = plain.data() + layout.fields[xyz.field[a]].offset * layout.points;
  const std::size_t size[3] = {layout.fields[xyz.field[0]].size, layout.fields[xyz.field[1]].size,
                               layout.fields[xyz.field[2]].size};
  const PcdKind kind[3] = {layout.fields[xyz.field[0]].kind, layout.fields[xyz.field[1]].kind,
                           layout.fields[xyz.field[2]].kind};
  for (std::size_t i = 0; i < layout.points; ++i) {
    points.add({rawValue(block[0] + i * size[0], kind[0]), rawValue(block[1] + i * size[1], kind[1]),
                rawValue(block[2] + i * size[2], kind[2])});
  }
}

// ---- ascii ----

// How PCL 1.13 turns an ASCII value into a number, kept so that points equal PCL's: "nan" (any
// case) is NaN, except in fields of SIZE 1; other values go through one std::istringstream that PCL
// never clears, with atof where the stream fails. Once a value has ended the stream (reached the
// end of its text or failed; in practice the file's first value) every later value is atof's
// double, rounded to float for SIZE 4. So the first value is rounded once (strtof), the others
// twice, which differs in the last bit for a decimal close to halfway between two floats.
class PclAsciiNumbers {
 public:
  PclAsciiNumbers() { stream_.imbue(std::locale::classic()); }

  // The value of `token` in a field of `kind`; `atof` is strtod's value of it.
  double value(const std::string& token, double atof, PcdKind kind) {
    const bool one_byte = kind == PcdKind::kI1 || kind == PcdKind::kU1;
    if (!one_byte && isNan(token)) return std::numeric_limits<double>::quiet_NaN();
    if (live_) {
      double streamed = 0.0;
      const bool read = extract(token, kind, streamed);
      live_ = stream_.rdstate() == std::ios::goodbit;
      if (read) return streamed;
    }
    return kind == PcdKind::kF4 ? static_cast<double>(static_cast<float>(atof)) : atof;
  }

 private:
  static bool isNan(const std::string& token) {
    return token.size() == 3 && std::tolower(static_cast<unsigned char>(token[0])) == 'n' &&
           std::tolower(static_cast<unsigned char>(token[1])) == 'a' &&
           std::tolower(static_cast<unsigned char>(token[2])) == 'n';
  }

  template <typename T>
  bool extractAs(const std::string& token, double& value) {
    T t{};
    stream_.str(token);
    const bool read = static_cast<bool>(stream_ >> t);
    value = static_cast<double>(t);
    return read;
  }

  // Integer values matter only for what they do to the stream (they are never coordinates).
  bool extract(const std::string& token, PcdKind kind, double& value) {
    switch (kind) {
      case PcdKind::kI1:
      case PcdKind::kU1:
        return extractAs<int>(token, value);
      case PcdKind::kI2:
        return extractAs<std::int16_t>(token, value);
      case PcdKind::kU2:
        return extractAs<std::uint16_t>(token, value);
      case PcdKind::kI4:
        return extractAs<std::int32_t>(token, value);
      case PcdKind::kU4:
        return extractAs<std::uint32_t>(token, value);
      case PcdKind::kI8:
        return extractAs<std::int64_t>(token, value);
      case PcdKind::kU8:
        return extractAs<std::uint64_t>(token, value);
      case PcdKind::kF4:
        return extractAs<float>(token, value);
      case PcdKind::kF8:
        return extractAs<double>(token, value);
    }
    return false;
  }

  std::istringstream stream_;
  bool live_ = true;
};

// Splits a data line at the blanks std::istream skips (space, \t, \n, \v, \f, \r).
void splitAtBlanks(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  static constexpr std::string_view kBlanks = " \t\n\v\f\r";
  std::size_t pos = line.find_first_not_of(kBlanks);
  while (pos != std::string_view::npos) {
    const std::size_t end = std::min(line.find_first_of(kBlanks, pos), line.size());
    tokens.push_back(line.substr(pos, end - pos));
    pos = line.find_first_not_of(kBlanks, end);
  }
}

// The values of one data row: each a number as strtod reads it whole, as many as a point has.
void parseAsciiRow(const std::vector<std::string_view>& tokens, std::size_t row, const BadPcd& bad,
                   std::size_t values, std::vector<std::string>& texts, std::vector<double>& numbers) {
  texts.resize(tokens.size());
  numbers.resize(tokens.size());
  for (std::size_t t = 0; t < tokens.size(); ++t) {
    texts[t].assign(tokens[t]);
    char* end = nullptr;
    numbers[t] = std::strtod(texts[t].c_str(), &end);
    if (end != texts[t].c_str() + texts[t].size()) {
      throw bad("data row " + std::to_string(row) + ": '" + texts[t] + "' is not a number");
    }
  }
  if (tokens.size() != values) {
    throw bad("data row " + std::to_string(row) + " has " + std::to_string(tokens.size()) + " values, expected " +
              std::to_string(values));
  }
}

// One row's point: every value converted in field order as PCL converts it (fields named "_",
// padding, skipped as PCL skips them), x, y, z kept.
Eigen::Vector3d asciiPoint(const PcdLayout& layout, const PcdXyz& xyz, const std::vector<std::string>& texts,
                           const std::vector<double>& numbers, PclAsciiNumbers& pcl) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  std::size_t t = 0;
  for (std::size_t i = 0; i < layout.fields.size(); ++i) {
    const PcdField& f = layout.fields[i];
    if (f.name == "_") {
      t += f.count;
      continue;
    }
    for (std::size_t c = 0; c < f.count; ++c, ++t) {
      const double v = pcl.value(texts[t], numbers[t], f.kind);
      for (int a = 0; a < 3; ++a) {
        if (xyz.field[a] == i) p[a] = v;
      }
    }
  }
  return p;
}

// ASCII data: a row of numbers per point, as many as a point has values, and as many rows as
// POINTS; lines without a value are skipped (PCL 1.13 skipped only empty ones, and took a line of
// blanks for a point at the origin).
void decodeAscii(const std::string& bytes, const BadPcd& bad, const PcdLayout& layout, const PcdXyz& xyz,
                 PcdPoints& points) {
  std::size_t line = static_cast<std::size_t>(std::count(bytes.begin(), bytes.begin() + layout.header_bytes, '\n'));
  std::size_t pos = layout.header_bytes, rows = 0;
  std::vector<std::string_view> tokens;
  std::vector<std::string> texts;
  std::vector<double> numbers;
  PclAsciiNumbers pcl;
  while (rows < layout.points && pos < bytes.size()) {
    const std::size_t eol = std::min(bytes.find('\n', pos), bytes.size());
    splitAtBlanks(std::string_view(bytes).substr(pos, eol - pos), tokens);
    pos = eol + 1;
    ++line;
    if (tokens.empty()) continue;
    parseAsciiRow(tokens, rows + 1, bad, layout.values, texts, numbers);
    points.add(asciiPoint(layout, xyz, texts, numbers, pcl), line);
    ++rows;
  }
  if (rows < layout.points) throw bad("fewer data rows than POINTS");
}

}  // namespace

std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path, const std::string& bytes) {
  const BadPcd bad = [&](const std::string& what) { return std::runtime_error(path + ": not a valid PCD file: " + what); };
  const PcdLayout layout = checkPcd(bytes, bad);
  const PcdXyz xyz = chooseXyz(layout, path);
  if (layout.points == 0) return {};
  // An ASCII row takes at least two bytes: a short file declaring many points reserves no more.
  const std::size_t payload = bytes.size() - layout.header_bytes;
  PcdPoints points(layout.data == "ascii" ? std::min(layout.points, payload / 2) : layout.points);
  if (layout.data == "ascii") {
    decodeAscii(bytes, bad, layout, xyz, points);
  } else if (layout.data == "binary") {
    decodeBinary(bytes.data() + layout.header_bytes, layout, xyz, points);
  } else {
    decodeCompressed(bytes, bad, layout, xyz, points);
  }
  return points.take(path, layout);
}

}  // namespace uampc::world
