// PNG writing (stb_image_write from Debian's libstb).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace clothsim {

// Top row first, RGBA8. Throws std::runtime_error naming the file when it cannot be written.
void write_png_file(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

}  // namespace clothsim
