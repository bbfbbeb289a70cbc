#include "export/output_plan.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "io/input_file.hpp"
#include "scene/scene.hpp"

namespace clothsim {
namespace fs = std::filesystem;
namespace {

// The same file whatever the spelling: the folder resolved (symlinks, "..") and the name as
// written; and, for a file that exists, the device and inode it leads to (hard links, a
// symlink to it).
struct Identity {
  std::string key;
  std::optional<std::pair<dev_t, ino_t>> inode;
  bool same(const Identity& o) const { return key == o.key || (inode && o.inode && *inode == *o.inode); }
};

Identity identify(const std::string& path) {
  Identity id;
  std::error_code ec;
  const fs::path p = fs::absolute(strip_slashes(path), ec).lexically_normal();
  fs::path parent = fs::weakly_canonical(p.parent_path(), ec);
  if (ec) parent = p.parent_path();
  id.key = (parent / p.filename()).string();
  struct stat st {};
  if (stat(path.c_str(), &st) == 0) id.inode = std::make_pair(st.st_dev, st.st_ino);
  return id;
}

// The folder a file goes in: exists, is a folder, can be written.
std::optional<std::string> folder_problem(const fs::path& file) {
  const fs::path dir = file.has_parent_path() ? file.parent_path() : fs::path(".");
  struct stat st {};
  if (stat(dir.c_str(), &st) != 0)
    return errno == ENOENT ? fmt::format("the directory {} does not exist", dir.string())
                           : fmt::format("the directory {}: {}", dir.string(), errno_words(errno));
  if (!S_ISDIR(st.st_mode)) return fmt::format("{} is not a directory", dir.string());
  if (access(dir.c_str(), W_OK) != 0) return fmt::format("the directory {} is not writable", dir.string());
  return std::nullopt;
}

// Whether following the symlinks at `path` passes through /proc or /dev: their links stand for
// open files and devices (/proc/self/fd/1 is whatever stdout is now), never for a file to replace.
bool links_to_special(const std::string& path) {
  fs::path at(path);
  for (int hop = 0; hop < 40; ++hop) {
    std::error_code ec;
    if (!fs::is_symlink(fs::symlink_status(at, ec))) return false;
    const fs::path target = fs::read_symlink(at, ec);
    if (ec) return false;
    at = target.is_absolute() ? target : at.parent_path() / target;
    const std::string s = fs::absolute(at, ec).lexically_normal().string();
    if (s.rfind("/proc/", 0) == 0 || s.rfind("/dev/", 0) == 0) return true;
  }
  return false;
}

// A file that will be replaced: absent, or a regular file (or a symlink to one, which the
// rename replaces, never following it).
std::optional<std::string> file_problem(const std::string& path) {
  if (path.empty()) return "expected a file name, got an empty one";
  struct stat st {};
  if (lstat(path.c_str(), &st) != 0) {
    if (errno != ENOENT) return errno_words(errno);
    return folder_problem(path);
  }
  if (S_ISLNK(st.st_mode) && stat(path.c_str(), &st) != 0)
    return errno == ENOENT ? std::string("is a symlink to nothing (it is not replaced)")
                           : fmt::format("is a symlink: {}", errno_words(errno));
  if (links_to_special(path)) return "is a symlink into /proc or /dev (an open file or a device), so it is left alone";
  if (S_ISDIR(st.st_mode)) return "is a directory; expected a file";
  if (!S_ISREG(st.st_mode))
    return fmt::format("is {}; clothsim replaces only regular files, so it is left alone", file_kind(st.st_mode));
  return folder_problem(path);
}

}  // namespace

void OutputPlan::input(const std::string& what, const std::string& path) {
  if (!path.empty() && path[0] != '<') inputs_.push_back({what, path});
}

void OutputPlan::inputs_of(const Scene& scene) {
  input("the scene", scene.source);
  for (const ClothParams* c : scene.cloths())
    if (c->is_mesh()) input("the cloth's mesh", c->mesh_path.string());
  for (size_t k = 0; k < scene.meshes.size(); ++k)
    input(fmt::format("the mesh of mesh[{}]", k), scene.meshes[k].file_path.string());
}

void OutputPlan::inputs_in(const std::string& what, const std::string& folder) {
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec)) input(what, it->path().string());
}

void OutputPlan::file(const std::string& flag, const std::string& path) { outputs_.push_back({flag, path, "", ""}); }

void OutputPlan::companion(const std::string& flag, const std::string& path, const std::string& why) {
  outputs_.push_back({flag, path, why, ""});
}

void OutputPlan::folder(const std::string& flag, const std::string& path, const std::vector<std::string>& names) {
  folders_.push_back(path);
  folder_flags_.push_back(flag);
  for (const std::string& name : names)
    outputs_.push_back({flag, (fs::path(strip_slashes(path)) / name).string(), fmt::format("a frame of {} {}", flag, path), path});
}

void OutputPlan::check() const {
  auto said = [](const Output& o) {
    if (o.why.empty()) return fmt::format("{} {}", o.flag, o.path);
    return fmt::format("{} ({})", o.path, o.why);
  };
  for (size_t k = 0; k < folders_.size(); ++k) {
    const std::string& dir = folders_[k];
    if (strip_slashes(dir).empty()) throw OutputError(fmt::format("{}: expected a folder name, got an empty one", folder_flags_[k]));
    struct stat st {};
    if (stat(dir.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode))
        throw OutputError(fmt::format("{} {}: is {}; expected a folder", folder_flags_[k], dir,
                                      file_kind(st.st_mode)));
      if (access(dir.c_str(), W_OK) != 0)
        throw OutputError(fmt::format("{} {}: the folder is not writable", folder_flags_[k], dir));
    } else if (errno != ENOENT) {
      throw OutputError(fmt::format("{} {}: {}", folder_flags_[k], dir, errno_words(errno)));
    } else {
      // Created by the run, with its missing parents: the nearest folder that exists must be writable.
      fs::path up = fs::absolute(strip_slashes(dir)).parent_path();
      std::error_code ec;
      while (!up.empty() && !fs::exists(up, ec) && up != up.parent_path()) up = up.parent_path();
      if (!fs::is_directory(up, ec) || access(up.c_str(), W_OK) != 0)
        throw OutputError(fmt::format("{} {}: cannot create it: {} is not a writable folder", folder_flags_[k], dir,
                                      up.string()));
    }
  }
  // Each path is identified once (a sequence of thousands of frames is thousands of outputs),
  // and clashes are found through maps, not by comparing every pair.
  std::vector<std::string> folder_keys;
  std::map<std::string, bool> folder_exists;
  for (const std::string& dir : folders_) {
    folder_keys.push_back(identify(dir).key);
    folder_exists[dir] = fs::is_directory(dir);
  }
  std::vector<Identity> ids;
  for (const Output& o : outputs_) {
    // A frame of a folder that does not exist yet has nothing to check but the folder, above.
    if (o.folder.empty() || folder_exists[o.folder])
      if (const auto problem = file_problem(o.path)) throw OutputError(fmt::format("{}: {}", said(o), *problem));
    ids.push_back(identify(o.path));
  }
  std::map<std::string, size_t> by_key;
  std::map<std::pair<dev_t, ino_t>, size_t> by_inode;
  for (size_t a = 0; a < outputs_.size(); ++a) {
    auto b = by_key.find(ids[a].key);
    if (b == by_key.end() && ids[a].inode) {
      const auto same_inode = by_inode.find(*ids[a].inode);
      if (same_inode != by_inode.end()) b = by_key.find(ids[same_inode->second].key);
    }
    if (b != by_key.end())
      throw OutputError(fmt::format("{} and {} name the same file: one would overwrite the other; name "
                                    "different files",
                                    said(outputs_[b->second]), said(outputs_[a])));
    by_key.emplace(ids[a].key, a);
    if (ids[a].inode) by_inode.emplace(*ids[a].inode, a);
    // A sequence folder holds its frames only: another output inside it could be one of them
    // now, or be taken for one (a later run's --export-every).
    if (outputs_[a].folder.empty())
      for (size_t k = 0; k < folders_.size(); ++k)
        if (fs::path(ids[a].key).parent_path().string() == folder_keys[k])
          throw OutputError(fmt::format("{}: is inside {} {}, the folder of a sequence of frames, which holds "
                                        "only its frames; put it elsewhere",
                                        said(outputs_[a]), folder_flags_[k], folders_[k]));
  }
  for (const Input& in : inputs_) {
    const Identity input = identify(in.path);
    for (size_t a = 0; a < outputs_.size(); ++a)
      if (ids[a].same(input))
        throw OutputError(fmt::format("{}: is {} this run reads ({}); an output never replaces an input of "
                                      "its run: name another file",
                                      said(outputs_[a]), in.what, in.path));
  }
}

}  // namespace clothsim
