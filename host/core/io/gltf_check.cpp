// A glTF's JSON read before Assimp reads the file (gltf_check.hpp).
#include "io/gltf_check.hpp"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace clothsim {

std::optional<std::string> gltf_problem(const std::filesystem::path& file, uint64_t size) {
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  if (ext != ".gltf" && ext != ".glb") return std::nullopt;
  if (size > (uint64_t(1) << 30)) return std::nullopt;  // larger than Assimp reads anyway: its message
  std::ifstream in(file, std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (ext == ".glb") {
    // 12-byte header, then the first chunk: its length, its type ("JSON"), its bytes.
    uint32_t length = 0;
    if (text.size() < 20 || text.compare(0, 4, "glTF") != 0 || text.compare(16, 4, "JSON") != 0) return std::nullopt;
    std::memcpy(&length, text.data() + 12, 4);
    if (length > text.size() - 20) return std::nullopt;
    text = text.substr(20, length);
  }
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (j.is_discarded() || !j.is_object() || !j.contains("skins") || !j["skins"].is_array()) return std::nullopt;
  for (size_t k = 0; k < j["skins"].size(); ++k)
    if (!j["skins"][k].is_object() || !j["skins"][k].contains("inverseBindMatrices"))
      return fmt::format("skin {} has no inverseBindMatrices, which Assimp 5.2 cannot read (it crashes); write "
                         "them out (the identity where they are the default)",
                         k);
  return std::nullopt;
}

}  // namespace clothsim
