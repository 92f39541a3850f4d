#include "strictmin/report/report_manifest.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>

#include "strictmin/io/atomic_file.h"

namespace strictmin {
namespace fs = std::filesystem;

namespace {

void add_once(std::vector<std::string>& files, std::set<std::string>& seen, const std::string& file) {
  if (!file.empty() && seen.insert(file).second) files.push_back(file);
}

// True when PATH, with its symbolic links resolved, lies inside the folder ROOT (canonical).
bool lies_inside(const fs::path& root, const fs::path& path) {
  std::error_code ec;
  const fs::path folder = fs::weakly_canonical(path.parent_path(), ec);
  if (ec) return false;
  const auto [end, unused] = std::mismatch(root.begin(), root.end(), folder.begin(), folder.end());
  return end == root.end();
}

// Removes DIR/FILE when it is a file (or link) inside DIR, and then its sub-folders of DIR
// left empty. False when it is there and could not be removed.
bool remove_stale(const fs::path& root, const std::string& file) {
  const fs::path path = root / file;
  std::error_code ec;
  const fs::file_status status = fs::symlink_status(path, ec);
  if (!fs::exists(status)) return true;  // already gone
  if (fs::is_directory(status) || !lies_inside(root, path)) return true;  // not ours to remove
  if (!fs::remove(path, ec)) return false;
  for (fs::path folder = path.parent_path(); folder != root && lies_inside(root, folder); folder = folder.parent_path())
    if (!fs::is_empty(folder, ec) || ec || !fs::remove(folder, ec)) break;
  return true;
}

}  // namespace

std::vector<std::string> report_files(const HtmlReport& report, const std::string& index_name) {
  std::vector<std::string> files;
  std::set<std::string> seen;
  for (const ReportSection& s : report.sections) {
    add_once(files, seen, s.input_picture);
    add_once(files, seen, s.histogram);
    for (const MethodEntry& m : s.methods) {
      add_once(files, seen, m.picture);
      add_once(files, seen, m.histogram);
      for (const auto& [caption, path] : m.extra_pictures) add_once(files, seen, path);
      for (const auto& [text, path] : m.links) add_once(files, seen, path);
    }
  }
  add_once(files, seen, index_name);
  return files;
}

bool is_manifest_entry(const std::string& entry) {
  if (entry.empty() || entry.find_first_of("\\\n\r") != std::string::npos) return false;
  const fs::path path(entry);
  if (path.is_absolute() || path.has_root_path()) return false;
  for (const fs::path& part : path) {
    const std::string name = part.string();
    if (name.empty() || name == "." || name == "..") return false;
  }
  return entry.back() != '/';
}

std::vector<std::string> read_report_manifest(const std::string& dir) {
  std::vector<std::string> entries;
  std::ifstream in(fs::path(dir) / kReportManifestName);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (is_manifest_entry(line)) entries.push_back(line);
  }
  return entries;
}

std::vector<std::string> update_report_manifest(const std::string& dir, const std::vector<std::string>& files) {
  std::error_code ec;
  const fs::path root = fs::canonical(dir, ec);
  if (ec) return {};  // no folder: nothing to clean or record
  const std::set<std::string> kept(files.begin(), files.end());
  std::vector<std::string> listed, removed;
  for (const std::string& f : files)
    if (is_manifest_entry(f)) listed.push_back(f);
  for (const std::string& old : read_report_manifest(dir)) {
    if (kept.count(old)) continue;
    if (remove_stale(root, old)) removed.push_back(old);
    else listed.push_back(old);  // not removable now: still ours
  }
  write_file_atomically((root / kReportManifestName).string(), [&](std::ostream& os) {
    for (const std::string& f : listed) os << f << '\n';
  });
  return removed;
}

}  // namespace strictmin
