#include "shader_source.hpp"

#include <fmt/format.h>

#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>

namespace clothsim::gl {
namespace {

namespace fs = std::filesystem;

std::string trim_left(const std::string& s) {
  const auto start = s.find_first_not_of(" \t");
  return start == std::string::npos ? std::string() : s.substr(start);
}

// The directive name of a preprocessor line ("include" for `  # include "x"`), else "".
std::string directive_name(const std::string& line, std::string* rest) {
  std::string t = trim_left(line);
  if (t.empty() || t[0] != '#') return "";
  t = trim_left(t.substr(1));
  std::size_t end = 0;
  while (end < t.size() && (std::isalnum(static_cast<unsigned char>(t[end])) || t[end] == '_')) ++end;
  *rest = trim_left(t.substr(end));
  return t.substr(0, end);
}

class Assembler {
 public:
  ShaderSource out;

  // `where` is the `file:line` of the #include directive, empty for the top-level file.
  void add_file(const fs::path& path, const std::string& where) {
    const fs::path key = fs::weakly_canonical(path);
    const std::string shown = path.lexically_normal().string();
    for (std::size_t i = 0; i < open_.size(); ++i) {
      if (open_[i].key != key) continue;
      std::string chain;
      for (std::size_t j = i; j < open_.size(); ++j) chain += open_[j].shown + " -> ";
      throw ShaderError(fmt::format("{}: error: include cycle: {}{}", where, chain, shown));
    }
    std::ifstream file(path);
    if (!file) {
      throw ShaderError(where.empty() ? fmt::format("{}: cannot open shader file", shown)
                                      : fmt::format("{}: error: cannot open included file {}", where, shown));
    }

    const std::size_t k = out.files.size();
    out.files.push_back(shown);
    open_.push_back({key, shown});
    out.text += fmt::format("#line 1 {}\n", k);
    std::string line, rest;
    for (int n = 1; std::getline(file, line); ++n) {
      const std::string directive = directive_name(line, &rest);
      if (directive == "include") {
        add_include(path, shown, n, rest);
        out.text += fmt::format("#line {} {}\n", n + 1, k);
      } else if (directive == "version") {
        throw ShaderError(fmt::format("{}:{}: error: #version is set by the loader (#version 430 core); "
                                      "remove this line", shown, n));
      } else {
        out.text += line + "\n";
        // A #line inside a skipped #if group is ignored, so an include in one would leave the
        // numbering wrong after it: restate it wherever a group may become active again.
        if (directive == "else" || directive == "elif" || directive == "endif") {
          out.text += fmt::format("#line {} {}\n", n + 1, k);
        }
      }
    }
    open_.pop_back();
  }

 private:
  struct OpenFile {
    fs::path key;
    std::string shown;
  };
  std::vector<OpenFile> open_;  // the include chain being read, outermost first

  void add_include(const fs::path& path, const std::string& shown, int n, const std::string& rest) {
    if (!rest.empty() && rest[0] == '<') {
      // A C++ header of a file shared with the host; GLSL never sees it.
      out.text += "// (C++ only) #include " + rest + "\n";
      return;
    }
    const auto close = rest.find('"', 1);
    if (rest.empty() || rest[0] != '"' || close == std::string::npos) {
      throw ShaderError(fmt::format("{}:{}: error: expected #include \"relative/path\"", shown, n));
    }
    const fs::path child = path.parent_path() / rest.substr(1, close - 1);
    add_file(child, fmt::format("{}:{}", shown, n));
  }
};

}  // namespace

ShaderSource preprocess_shader(const std::filesystem::path& path, const Defines& defines) {
  Assembler assembler;
  assembler.out.files.push_back("<defines>");
  assembler.out.text = "#version 430 core\n";
  for (const auto& [name, value] : defines) assembler.out.text += fmt::format("#define {} {}\n", name, value);
  assembler.add_file(path, "");
  return std::move(assembler.out);
}

std::string map_info_log(const std::string& log, const std::vector<std::string>& files) {
  static const std::regex mesa(R"(^(\d+):(\d+)\((\d+)\): (.*)$)");
  static const std::regex nvidia(R"(^(\d+)\((\d+)\) : (.*)$)");
  static const std::regex glslang(R"(^(ERROR|WARNING): (\d+):(\d+): (.*)$)");
  auto file = [&](const std::string& k) {
    const std::size_t i = std::stoul(k);
    return i < files.size() ? files[i] : "<source string " + k + ">";
  };
  std::istringstream in(log);
  std::string out, line;
  std::smatch m;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (std::regex_match(line, m, mesa)) {
      out += fmt::format("{}:{}:{}: {}", file(m[1]), m[2].str(), m[3].str(), m[4].str());
    } else if (std::regex_match(line, m, nvidia)) {
      out += fmt::format("{}:{}: {}", file(m[1]), m[2].str(), m[3].str());
    } else if (std::regex_match(line, m, glslang)) {
      out += fmt::format("{}:{}: {}: {}", file(m[2]), m[3].str(), m[1] == "ERROR" ? "error" : "warning",
                         m[4].str());
    } else {
      out += line;
    }
    out += "\n";
  }
  return out;
}

}  // namespace clothsim::gl
