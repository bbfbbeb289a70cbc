#include "png.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <stb/stb_image_write.h>

namespace clothsim {

void write_png_file(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba) {
  if (!stbi_write_png(path.c_str(), w, h, 4, rgba.data(), w * 4))
    throw std::runtime_error(fmt::format("{}: cannot write the PNG", path));
}

}  // namespace clothsim
