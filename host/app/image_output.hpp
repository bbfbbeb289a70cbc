// Where rendered frames go: PNG files (one per frame, or the last frame only) or an MP4
// made by piping raw frames into ffmpeg.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace clothsim {

void write_png(const std::string& path, int width, int height, const std::vector<uint8_t>& rgba);

class FrameSink {
 public:
  // `out`: DIR (frame_0000.png ...), FILE.png (last frame only) or FILE.mp4.
  // Throws ExitError (2) for an unusable destination or a missing ffmpeg.
  FrameSink(const std::string& out, int width, int height, double fps);
  ~FrameSink();
  void add(const std::vector<uint8_t>& rgba);
  std::string finish();  // flushes; returns a sentence saying what was written

 private:
  enum class Kind { Directory, Still, Video } kind_;
  std::string out_;
  int width_, height_, frames_ = 0;
  std::vector<uint8_t> last_;
  std::FILE* ffmpeg_ = nullptr;
};

}  // namespace clothsim
