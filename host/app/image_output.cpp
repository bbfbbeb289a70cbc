#include "image_output.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "png.hpp"

extern char** environ;

namespace clothsim {
namespace fs = std::filesystem;
namespace {

// Whether `name` is an executable file in a directory of $PATH (as posix_spawnp searches it;
// glibc's default without PATH is /bin:/usr/bin). No shell is involved.
bool on_path(const std::string& name) {
  const char* env = std::getenv("PATH");
  const std::string path = env ? env : "/bin:/usr/bin";
  size_t begin = 0;
  while (begin <= path.size()) {
    size_t end = path.find(':', begin);
    if (end == std::string::npos) end = path.size();
    const std::string dir = end > begin ? path.substr(begin, end - begin) : ".";
    const std::string file = dir + "/" + name;
    struct stat st {};
    if (stat(file.c_str(), &st) == 0 && S_ISREG(st.st_mode) && access(file.c_str(), X_OK) == 0) return true;
    begin = end + 1;
  }
  return false;
}

// A file output's folder must exist and be writable: checked before the run.
void check_folder(const std::string& out) {
  std::error_code ec;
  const fs::path dir = fs::path(out).has_parent_path() ? fs::path(out).parent_path() : fs::path(".");
  if (fs::is_directory(out, ec)) throw ExitError(kExitBadInput, fmt::format("--out {}: is a directory", out));
  if (!fs::is_directory(dir, ec))
    throw ExitError(kExitBadInput, fmt::format("--out {}: the directory {} does not exist", out, dir.string()));
  if (access(dir.c_str(), W_OK) != 0)
    throw ExitError(kExitBadInput, fmt::format("--out {}: the directory {} is not writable", out, dir.string()));
}

std::string describe_status(int status) {
  if (WIFEXITED(status)) return fmt::format("exit status {}", WEXITSTATUS(status));
  if (WIFSIGNALED(status)) return fmt::format("killed by signal {} ({})", WTERMSIG(status), strsignal(WTERMSIG(status)));
  return fmt::format("wait status {}", status);
}

// Writes all of `data` to the pipe with SIGPIPE blocked in this thread, so an ffmpeg that has
// died makes write() fail with EPIPE instead of killing clothsim; a SIGPIPE left pending by
// that write is consumed before the mask is restored. Returns false (errno set) on failure.
bool write_to_pipe(int fd, const uint8_t* data, size_t n) {
  sigset_t pipe_only, old;
  sigemptyset(&pipe_only);
  sigaddset(&pipe_only, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_only, &old);
  const bool was_pending = [&] {
    sigset_t pending;
    sigpending(&pending);
    return sigismember(&pending, SIGPIPE) == 1;
  }();
  bool ok = true;
  int error = 0;
  for (size_t done = 0; done < n;) {
    const ssize_t k = ::write(fd, data + done, n - done);
    if (k < 0 && errno == EINTR) continue;
    if (k <= 0) {
      ok = false;
      error = errno;
      break;
    }
    done += size_t(k);
  }
  if (!ok && !was_pending) {
    const timespec zero{0, 0};
    while (sigtimedwait(&pipe_only, nullptr, &zero) == SIGPIPE) {
    }
  }
  pthread_sigmask(SIG_SETMASK, &old, nullptr);
  errno = error;
  return ok;
}

}  // namespace

void write_png(const std::string& path, int w, int h, const std::vector<uint8_t>& rgba) {
  try {
    write_replacing(path, [&](const std::string& temp) {
      try {
        write_png_file(temp, w, h, rgba);
      } catch (const std::runtime_error&) {
        throw std::runtime_error(fmt::format("{}: cannot write the PNG", path));
      }
    });
  } catch (const std::runtime_error& e) {
    throw ExitError(kExitBadInput, e.what());
  }
}

std::vector<std::string> ffmpeg_arguments(bool gif, int w, int h, double fps, const std::string& output) {
  std::vector<std::string> args = {"ffmpeg", "-y", "-loglevel", "error", "-f", "rawvideo", "-pix_fmt", "rgba",
                                   "-s", fmt::format("{}x{}", w, h), "-framerate", fmt::format("{}", fps), "-i", "-"};
  if (gif) {
    // One palette for the whole clip, made from every frame (stats_mode=diff favours what
    // moves), ordered dithering (error diffusion crawls from frame to frame) and only the
    // changed rectangle stored per frame: small files.
    args.insert(args.end(), {"-filter_complex",
                             "split[a][b];[a]palettegen=stats_mode=diff[p];"
                             "[b][p]paletteuse=dither=bayer:bayer_scale=3:diff_mode=rectangle",
                             "-loop", "0"});
  } else {
    args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-movflags", "+faststart"});
  }
  // The format is named, since the temporary's name does not end in .mp4 / .gif; `file:` makes
  // the rest of the element a file name, whatever it starts with or contains.
  args.insert(args.end(), {"-f", gif ? "gif" : "mp4", "file:" + output});
  return args;
}

// GIF frame delays are whole hundredths of a second, and browsers play delays under 2/100 s
// at 1/10 s instead: a faster GIF would play several times too slowly.
constexpr double kGifMaxFps = 50;

void FrameSink::check(const std::string& out, int w, int h, double fps) {
  const std::string ext = fs::path(out).extension().string();
  if (ext == ".png" || ext == ".mp4" || ext == ".gif") check_folder(out);
  if (ext != ".mp4" && ext != ".gif") return;
  if (!on_path("ffmpeg"))
    throw ExitError(kExitBadInput, fmt::format("--out {}: making an {} needs ffmpeg, which is not installed "
                                               "(apt-get install ffmpeg), or write PNGs with --out DIR",
                                               out, ext == ".mp4" ? "MP4" : "animated GIF"));
  if (ext == ".mp4" && (w % 2 || h % 2))
    throw ExitError(kExitBadInput, fmt::format("--size {}x{}: an MP4 (yuv420p) needs an even width and height", w, h));
  if (ext == ".gif" && fps > kGifMaxFps)
    throw ExitError(kExitBadInput, fmt::format("--out {}: {:g} frames/s is faster than a GIF can play (at most {:g}); "
                                               "keep every 2nd frame with --every 2, or set --fps",
                                               out, fps, kGifMaxFps));
}

FrameSink::FrameSink(const std::string& out, int w, int h, double fps)
    : out_(out), width_(w), height_(h), fps_(fps) {
  check(out, w, h, fps);
  const std::string ext = fs::path(out).extension().string();
  if (ext == ".mp4" || ext == ".gif") {
    kind_ = ext == ".mp4" ? Kind::Video : Kind::Gif;
    start_ffmpeg();
  } else if (ext == ".png") {
    kind_ = Kind::Still;
  } else {
    kind_ = Kind::Directory;
    std::error_code ec;
    fs::create_directories(out, ec);
    if (ec || !fs::is_directory(out))
      throw ExitError(kExitBadInput, fmt::format("--out {}: cannot create the directory ({})", out, ec.message()));
  }
}

void FrameSink::start_ffmpeg() {
  video_ = std::make_unique<PendingFile>(out_);
  const std::vector<std::string> args = ffmpeg_arguments(kind_ == Kind::Gif, width_, height_, fps_, video_->temp());
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);

  int fds[2];
  if (pipe2(fds, O_CLOEXEC) != 0)
    throw ExitError(kExitBadInput, fmt::format("--out {}: cannot make a pipe to ffmpeg ({})", out_, std::strerror(errno)));
  // The read end becomes ffmpeg's stdin (dup2 clears close-on-exec there); the write end is
  // close-on-exec, so ffmpeg sees end of input when clothsim closes it.
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, fds[0], STDIN_FILENO);
  // ffmpeg starts with SIGPIPE at its default whatever clothsim's is.
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t defaults;
  sigemptyset(&defaults);
  sigaddset(&defaults, SIGPIPE);
  posix_spawnattr_setsigdefault(&attr, &defaults);
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF);
  const int rc = posix_spawnp(&ffmpeg_, "ffmpeg", &actions, &attr, argv.data(), environ);
  posix_spawnattr_destroy(&attr);
  posix_spawn_file_actions_destroy(&actions);
  close(fds[0]);
  if (rc != 0) {
    close(fds[1]);
    ffmpeg_ = -1;
    throw ExitError(kExitBadInput, fmt::format("--out {}: cannot start ffmpeg ({})", out_, std::strerror(rc)));
  }
  ffmpeg_input_ = fds[1];
  register_writer(ffmpeg_);  // a SIGINT/SIGTERM stops it before removing its temporary
}

std::string FrameSink::stop_ffmpeg() {
  if (ffmpeg_input_ >= 0) close(ffmpeg_input_);
  ffmpeg_input_ = -1;
  if (ffmpeg_ < 0) return "not running";
  int status = 0;
  pid_t r;
  while ((r = waitpid(ffmpeg_, &status, 0)) < 0 && errno == EINTR) {
  }
  forget_writer(ffmpeg_);
  ffmpeg_ = -1;
  if (r < 0) return fmt::format("cannot wait for it ({})", std::strerror(errno));
  return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? "" : describe_status(status);
}

FrameSink::~FrameSink() {
  // Not finished (an error elsewhere): ffmpeg is stopped, and video_ removes its temporary.
  if (ffmpeg_ >= 0) {
    kill(ffmpeg_, SIGTERM);
    stop_ffmpeg();
  }
}

void FrameSink::add(const std::vector<uint8_t>& rgba) {
  switch (kind_) {
    case Kind::Video:
    case Kind::Gif:
      if (!write_to_pipe(ffmpeg_input_, rgba.data(), rgba.size())) {
        const std::string why = std::strerror(errno);
        const std::string how = stop_ffmpeg();
        video_->discard();
        throw ExitError(kExitCheckFailed,
                        fmt::format("{}: ffmpeg stopped accepting frames after {} frame{} ({}; ffmpeg: {}); {} is {}", out_,
                                    frames_, frames_ == 1 ? "" : "s", why, how.empty() ? "exit status 0" : how, out_,
                                    fs::exists(out_) ? "unchanged" : "not written"));
      }
      break;
    case Kind::Still: last_ = rgba; break;
    case Kind::Directory:
      write_png((fs::path(out_) / fmt::format("frame_{:04d}.png", frames_)).string(), width_, height_, rgba);
      break;
  }
  ++frames_;
}

std::string FrameSink::finish() {
  switch (kind_) {
    case Kind::Video:
    case Kind::Gif: {
      const std::string how = stop_ffmpeg();
      if (!how.empty()) {
        video_->discard();
        throw ExitError(kExitCheckFailed, fmt::format("{}: ffmpeg failed ({}); {} is {}", out_, how, out_,
                                                      fs::exists(out_) ? "unchanged" : "not written"));
      }
      try {
        video_->commit();
      } catch (const std::runtime_error& e) {
        throw ExitError(kExitBadInput, e.what());
      }
      return fmt::format("wrote {} ({} frames, {}, {:g} frames/s)", out_, frames_,
                         kind_ == Kind::Video ? "H.264" : "GIF", fps_);
    }
    case Kind::Still:
      if (!last_.empty()) write_png(out_, width_, height_, last_);
      return fmt::format("wrote {} (frame {})", out_, frames_);
    case Kind::Directory: break;
  }
  return fmt::format("wrote {} frames to {}/frame_0000.png ...", frames_, out_);
}

}  // namespace clothsim
