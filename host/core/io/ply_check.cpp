#include "io/ply_check.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <sstream>
#include <vector>

#include <fmt/format.h>

namespace clothsim {
namespace {

struct Property {
  int size = 0;        // bytes of a scalar, or of a list's items
  int count_size = 0;  // > 0: a list, with its length stored in this many bytes
};
struct Element {
  std::string name;
  uint64_t count = 0;
  std::vector<Property> props;
};

int type_size(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32") return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

using File = std::unique_ptr<std::FILE, int (*)(std::FILE*)>;

// One line of the file without its \n or \r\n; false at the end.
bool next_line(std::FILE* f, std::string& line) {
  line.clear();
  int c;
  while ((c = getc_unlocked(f)) != EOF && c != '\n') line += char(c);
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return c != EOF || !line.empty();
}

// Walks a binary body: scalars are skipped, list lengths read. Fails when the data ends first.
std::optional<std::string> check_binary(std::FILE* f, const std::vector<Element>& elements, bool big_endian,
                                        uint64_t size) {
  for (const Element& e : elements) {
    bool lists = false;
    uint64_t fixed = 0;
    for (const Property& p : e.props) lists |= p.count_size > 0, fixed += uint64_t(p.size);
    if (!lists) {  // bounded above: count x fixed <= size
      if (std::fseek(f, long(fixed * e.count), SEEK_CUR) != 0) return "cannot seek in the file";
      continue;
    }
    for (uint64_t i = 0; i < e.count; ++i)
      for (const Property& p : e.props) {
        if (p.count_size == 0) {
          if (std::fseek(f, p.size, SEEK_CUR) != 0) return "cannot seek in the file";
          continue;
        }
        uint8_t b[4] = {};
        if (std::fread(b, 1, size_t(p.count_size), f) != size_t(p.count_size))
          return fmt::format("truncated: the data ends in {} {} of {} (the header promises {})", e.name, i, e.count,
                             e.count);
        uint64_t n = 0;
        for (int k = 0; k < p.count_size; ++k) {
          const int at = big_endian ? k : p.count_size - 1 - k;
          n = (n << 8) | b[at];
        }
        if (p.count_size == 4 && n > 0x7fffffffu) n = 0;  // a negative int count: Assimp refuses it
        if (std::fseek(f, long(n * uint64_t(p.size)), SEEK_CUR) != 0) return "cannot seek in the file";
      }
  }
  const long end = std::ftell(f);
  if (end < 0 || uint64_t(end) > size)
    return fmt::format("truncated: the header's elements need {} bytes, the file has {}", end, size);
  return std::nullopt;
}

// Each element on its own line with exactly its values (a list: its length, then the items).
std::optional<std::string> check_ascii(std::FILE* f, const std::vector<Element>& elements, uint64_t header_lines) {
  std::string line;
  uint64_t line_no = header_lines;
  for (const Element& e : elements)
    for (uint64_t i = 0; i < e.count; ++i) {
      do {
        if (!next_line(f, line))
          return fmt::format("truncated: the header promises {} {} elements, the file ends at {} {}", e.count, e.name,
                             e.name, i);
        ++line_no;
      } while (line.find_first_not_of(" \t") == std::string::npos);  // blank lines are nothing
      std::istringstream words(line);
      std::string w;
      std::vector<std::string> values;
      while (words >> w) values.push_back(w);
      size_t need = 0;
      for (const Property& p : e.props) {
        if (p.count_size == 0) {
          ++need;
          continue;
        }
        if (need >= values.size())
          return fmt::format("line {}: {} {} has {} values, too few for the header's properties (a truncated or "
                             "corrupt file)",
                             line_no, e.name, i, values.size());
        char* end = nullptr;
        const unsigned long long n = std::strtoull(values[need].c_str(), &end, 10);
        if (*end || values[need][0] == '-' || n > values.size())
          return fmt::format("line {}: {} {}: a list length of \"{}\" (expected a count of the values that follow)",
                             line_no, e.name, i, values[need]);
        need += 1 + size_t(n);
      }
      if (values.size() != need)
        return fmt::format("line {}: {} {} has {} values, the header's properties need {} (a truncated or corrupt "
                           "file)",
                           line_no, e.name, i, values.size(), need);
    }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> ply_problem(const std::filesystem::path& file, uint64_t size) {
  File f(std::fopen(file.c_str(), "rb"), &std::fclose);
  if (!f) return std::nullopt;  // the caller's open reports it
  std::string line;
  if (!next_line(f.get(), line) || line != "ply") return std::nullopt;
  std::string format;
  std::vector<Element> elements;
  uint64_t lines = 1;
  for (bool done = false; !done;) {
    if (std::ftell(f.get()) > (1 << 20)) return "a PLY header longer than 1 MiB";
    if (!next_line(f.get(), line)) return "a PLY header without end_header";
    ++lines;
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "end_header") {
      done = true;
    } else if (key == "format") {
      words >> format;
    } else if (key == "element") {
      Element e;
      std::string count;
      words >> e.name >> count;
      char* end = nullptr;
      e.count = std::strtoull(count.c_str(), &end, 10);
      if (count.empty() || *end || count[0] == '-')
        return fmt::format("header line {}: element {} has a count of \"{}\" (expected an integer >= 0)", lines,
                           e.name, count);
      elements.push_back(e);
    } else if (key == "property") {
      if (elements.empty()) return fmt::format("header line {}: a property before any element", lines);
      std::string type;
      words >> type;
      Property p;
      if (type == "list") {
        std::string count_type, item_type;
        words >> count_type >> item_type;
        p.count_size = type_size(count_type);
        p.size = type_size(item_type);
        if (p.count_size == 0 || p.count_size == 8 || p.size == 0)
          return fmt::format("header line {}: a list of {} {} (unknown types)", lines, count_type, item_type);
      } else if ((p.size = type_size(type)) == 0) {
        return fmt::format("header line {}: a property of unknown type \"{}\"", lines, type);
      }
      elements.back().props.push_back(p);
    }
  }
  const bool ascii = format == "ascii";
  if (!ascii && format != "binary_little_endian" && format != "binary_big_endian")
    return fmt::format("a PLY of format \"{}\" (expected ascii, binary_little_endian or binary_big_endian)", format);
  // Every element takes at least this many bytes: in ASCII a digit and a separator per value,
  // in binary its scalars and list lengths. More than the file holds is a lie of the header.
  const uint64_t body = size - uint64_t(std::ftell(f.get()));
  uint64_t least = 0;
  for (const Element& e : elements) {
    uint64_t per = 0;
    for (const Property& p : e.props) per += ascii ? 2 : uint64_t(p.count_size ? p.count_size : p.size);
    per = std::max<uint64_t>(per, 1);
    if (e.count > body / per)
      return fmt::format("the header claims {} {} elements, more than the file's {} bytes of data can hold (at "
                         "least {} bytes each): a corrupt or truncated file",
                         e.count, e.name, body, per);
    least += e.count * per;
    if (least > body)
      return fmt::format("the header's elements need at least {} bytes, the file has {} bytes of data: a corrupt or "
                         "truncated file",
                         least, body);
  }
  return ascii ? check_ascii(f.get(), elements, lines) : check_binary(f.get(), elements, format == "binary_big_endian", size);
}

}  // namespace clothsim
