#include "ply_check.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cstdint>
#include <vector>

namespace sutura::engine::detail {

namespace {

struct Property {
  bool list = false;
  int length_size = 0;  // binary bytes of a list's length field
  bool length_signed = false;
  int size = 0;  // binary bytes of the value, or of each list item
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

enum class Encoding { Ascii, LittleEndian, BigEndian };

// Binary size of a PLY scalar type; 0 for an unknown name.
int type_size(std::string_view type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" ||
      type == "float32") {
    return 4;
  }
  if (type == "double" || type == "float64") return 8;
  return 0;
}

bool is_integer_type(std::string_view type) {
  return type_size(type) != 0 && type != "float" && type != "float32" && type != "double" &&
         type != "float64";
}

bool is_signed_type(std::string_view type) {
  return type == "char" || type == "int8" || type == "short" || type == "int16" || type == "int" ||
         type == "int32";
}

void split(std::string_view line, std::vector<std::string_view>& words) {
  words.clear();
  std::size_t at = 0;
  while (true) {
    at = line.find_first_not_of(" \t", at);
    if (at == std::string_view::npos) return;
    const std::size_t end = std::min(line.find_first_of(" \t", at), line.size());
    words.push_back(line.substr(at, end - at));
    at = end;
  }
}

std::optional<std::uint64_t> parse_count(std::string_view word) {
  std::uint64_t value = 0;
  const auto [end, error] = std::from_chars(word.data(), word.data() + word.size(), value);
  if (error != std::errc() || end != word.data() + word.size() || value > UINT32_MAX) {
    return std::nullopt;
  }
  return value;
}

class Reader {
 public:
  explicit Reader(std::string_view bytes) : bytes_(bytes) {}

  // The next line without its '\n' and an optional '\r' before it.
  std::optional<std::string_view> next_line() {
    if (pos_ >= bytes_.size()) return std::nullopt;
    const std::size_t eol = std::min(bytes_.find('\n', pos_), bytes_.size());
    std::string_view line = bytes_.substr(pos_, eol - pos_);
    pos_ = eol + 1;
    crlf_ = !line.empty() && line.back() == '\r';
    if (crlf_) line.remove_suffix(1);
    return line;
  }
  [[nodiscard]] bool last_line_had_crlf() const { return crlf_; }

  // Skips `n` bytes; false if fewer remain.
  bool skip(std::uint64_t n) {
    if (n > bytes_.size() - std::min(pos_, bytes_.size())) return false;
    pos_ += n;
    return true;
  }

  std::uint64_t remaining() const { return bytes_.size() - std::min(pos_, bytes_.size()); }

  // Reads a binary integer of `size` bytes; nullopt if the data ends or it is negative.
  std::optional<std::uint64_t> read_length(int size, bool is_signed, Encoding encoding) {
    if (remaining() < static_cast<std::uint64_t>(size)) return std::nullopt;
    std::uint64_t value = 0;
    for (int k = 0; k < size; ++k) {
      const int byte = encoding == Encoding::LittleEndian ? size - 1 - k : k;
      value = (value << 8) | static_cast<unsigned char>(bytes_[pos_ + byte]);
    }
    pos_ += size;
    if (is_signed && (value >> (8 * size - 1)) != 0) return std::nullopt;
    return value;
  }

 private:
  std::string_view bytes_;
  std::size_t pos_ = 0;
  bool crlf_ = false;
};

// assimp's line reader treats a lone '\r' as a line end and swallows a blank line, so lines it
// would split differently from the '\n' lines checked here are refused.
std::optional<std::string> line_problem(std::string_view line, const std::string& where) {
  if (line.empty()) return "blank line in the " + where;
  if (line.find_first_of(std::string_view("\r\0", 2)) != std::string_view::npos) {
    return "stray control character in the " + where;
  }
  return std::nullopt;
}

std::string entry_name(const Element& e, std::uint64_t i) {
  return e.name + " entry " + std::to_string(i) + " of " + std::to_string(e.count);
}

// The property whose lists are polygons, counted as the k - 2 triangles assimp makes of k
// corners: the first list of a `face` element; nullptr for other elements.
const Property* polygon_list(const Element& e) {
  if (e.name != "face") return nullptr;
  const auto it = std::find_if(e.properties.begin(), e.properties.end(),
                               [](const Property& q) { return q.list; });
  return it == e.properties.end() ? nullptr : &*it;
}

std::uint64_t polygon_triangles(std::uint64_t corners) { return corners >= 3 ? corners - 2 : 0; }

std::optional<std::string> check_ascii(Reader& reader, const std::vector<Element>& elements,
                                       std::uint64_t& triangles) {
  std::vector<std::string_view> words;
  for (const Element& e : elements) {
    const Property* polygons = polygon_list(e);
    for (std::uint64_t i = 0; i < e.count; ++i) {
      const std::optional<std::string_view> line = reader.next_line();
      if (!line) return "the data ends before " + entry_name(e, i);
      if (auto problem = line_problem(*line, "data of " + entry_name(e, i))) return problem;
      split(*line, words);
      std::size_t w = 0;
      for (const Property& p : e.properties) {
        if (w >= words.size()) return entry_name(e, i) + " has too few values";
        if (!p.list) {
          ++w;
          continue;
        }
        const std::optional<std::uint64_t> length = parse_count(words[w++]);
        if (!length) return entry_name(e, i) + " has an invalid list length";
        if (*length > words.size() - w) {
          return entry_name(e, i) + " announces a list of " + std::to_string(*length) +
                 " values but holds fewer";
        }
        if (&p == polygons) triangles += polygon_triangles(*length);
        w += *length;
      }
    }
  }
  return std::nullopt;
}

std::optional<std::string> check_binary(Reader& reader, const std::vector<Element>& elements,
                                        Encoding encoding, std::uint64_t& triangles) {
  for (const Element& e : elements) {
    if (e.properties.empty()) continue;
    const Property* polygons = polygon_list(e);
    for (std::uint64_t i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        std::uint64_t values = 1;
        if (p.list) {
          const std::optional<std::uint64_t> length =
              reader.read_length(p.length_size, p.length_signed, encoding);
          if (!length) return "the data ends in or has a bad list length in " + entry_name(e, i);
          values = *length;
          if (&p == polygons) triangles += polygon_triangles(values);
        }
        if (values > reader.remaining() / p.size || !reader.skip(values * p.size)) {
          return "the data ends in " + entry_name(e, i);
        }
      }
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> ply_structure_problem(std::string_view bytes, std::uint64_t* triangles) {
  std::uint64_t counted = 0;
  Reader reader(bytes);
  std::vector<std::string_view> words;
  const std::optional<std::string_view> magic = reader.next_line();
  if (magic) split(*magic, words);
  if (!magic || words.size() != 1 || words[0] != "ply") return "not a PLY file (no \"ply\" line)";

  std::optional<Encoding> encoding;
  std::vector<Element> elements;
  bool complete = false;
  while (!complete) {
    const std::optional<std::string_view> line = reader.next_line();
    if (!line) return "incomplete PLY header: no end_header line";
    if (auto problem = line_problem(*line, "PLY header")) return problem;
    split(*line, words);
    const std::string bad_line = "corrupt PLY header line \"" + std::string(*line) + "\"";
    if (words.empty()) return "blank line in the PLY header";
    if (words[0] == "format") {
      if (words.size() < 2) return bad_line;
      if (words[1] == "ascii")
        encoding = Encoding::Ascii;
      else if (words[1] == "binary_little_endian")
        encoding = Encoding::LittleEndian;
      else if (words[1] == "binary_big_endian")
        encoding = Encoding::BigEndian;
      else
        return bad_line;
    } else if (words[0] == "element") {
      // assimp reads the count from the name when the name starts with a digit.
      const std::optional<std::uint64_t> count =
          words.size() == 3 ? parse_count(words[2]) : std::nullopt;
      if (!count ||
          !(std::isalpha(static_cast<unsigned char>(words[1][0])) || words[1][0] == '_')) {
        return bad_line;
      }
      // Every entry takes at least one byte; this also bounds entries without properties.
      if (*count > bytes.size()) {
        return "incomplete PLY file: the header announces " + std::to_string(*count) + " " +
               std::string(words[1]) + " entries, more than the file can hold";
      }
      elements.push_back({std::string(words[1]), *count, {}});
    } else if (words[0] == "property") {
      if (elements.empty()) return bad_line;
      Property p;
      if (words.size() == 5 && words[1] == "list" && is_integer_type(words[2]) &&
          type_size(words[3]) != 0) {
        p = {true, type_size(words[2]), is_signed_type(words[2]), type_size(words[3])};
      } else if (words.size() == 3 && type_size(words[1]) != 0) {
        p.size = type_size(words[1]);
      } else {
        return bad_line;
      }
      elements.back().properties.push_back(p);
    } else if (words[0] == "end_header") {
      complete = true;
      // Binary data must start right after the '\n'; assimp would start at it after a '\r'.
      if (reader.last_line_had_crlf() && encoding && *encoding != Encoding::Ascii) return bad_line;
    }
    // comment, obj_info and unknown lines are ignored, as assimp does.
  }
  if (!encoding) return "corrupt PLY header: no format line";
  auto problem = *encoding == Encoding::Ascii ? check_ascii(reader, elements, counted)
                                              : check_binary(reader, elements, *encoding, counted);
  if (triangles != nullptr) *triangles = counted;
  return problem;
}

}  // namespace sutura::engine::detail
