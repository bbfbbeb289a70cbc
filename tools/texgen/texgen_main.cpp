// texgen: writes the project's procedural textures and sky cube map as PNGs.
// Exit codes as for clothsim: 0 success, 1 a file could not be written, 2 bad usage.
#include <cstdio>
#include <filesystem>
#include <functional>
#include <system_error>

#include <CLI/CLI.hpp>

#include "texgen.hpp"

int main(int argc, char** argv) {
  using namespace clothsim::texgen;
  CLI::App app{"texgen: writes clothsim's procedural textures and sky cube map (deterministic PNGs)", "texgen"};
  std::filesystem::path out = "textures";
  int size = 512, face_size = 0;
  app.add_option("--out", out, "directory to write the PNGs into (created if missing)")->capture_default_str();
  app.add_option("--size", size, "width and height of the 2D textures in pixels")
      ->capture_default_str()->check(CLI::Range(16, 4096));
  app.add_option("--face-size", face_size, "width and height of each cube map face [default: --size / 2]")
      ->check(CLI::Range(8, 4096));
  app.failure_message(CLI::FailureMessage::help);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  }
  if (face_size == 0) face_size = size / 2;

  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) {
    std::fprintf(stderr, "error: %s: cannot create the directory (%s)\n", out.string().c_str(), ec.message().c_str());
    return 1;
  }
  auto write = [&](const char* name, const std::function<Image()>& make) {
    write_png(make(), out / name);
    std::printf("wrote %s\n", (out / name).string().c_str());
  };
  try {
    write("fabric.png", [&] { return make_fabric(size); });
    write("checker.png", [&] { return make_checker(size); });
    write("height_weave.png", [&] { return make_height_weave(size); });
    write("height_bumps.png", [&] { return make_height_bumps(size); });
    for (CubeFace face : kCubeFaces) {
      const std::string name = "sky_" + face_name(face) + ".png";
      write(name.c_str(), [&] { return make_sky_face(face, face_size); });
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
