#pragma once
// The manifest of a report folder: DIR/.strictmin-report lists the files the last report
// wrote into DIR (paths relative to DIR, one per line). A new report into the same folder
// removes the files of the old manifest it does not write again (pictures of runs no longer
// in the report), and never any other file: a user's own files stay.
#include <string>
#include <vector>

#include "strictmin/report/html_report.h"

namespace strictmin {

inline constexpr const char* kReportManifestName = ".strictmin-report";

// The files a report refers to, relative to its folder: every picture, histogram and link of
// REPORT, and INDEX_NAME (its index.html). Each once, in the order of the page.
std::vector<std::string> report_files(const HtmlReport& report, const std::string& index_name);

// True for a manifest entry that names a file inside the folder: a relative path whose
// components are plain names (no "..", ".", empty component, backslash or line break).
bool is_manifest_entry(const std::string& entry);

// The entries of DIR's manifest that is_manifest_entry accepts (others are ignored); none
// when DIR has no manifest.
std::vector<std::string> read_report_manifest(const std::string& dir);

// Removes the files of DIR's old manifest that FILES does not list (and sub-folders of DIR
// left empty by that), then writes DIR's manifest: FILES, and the stale files that could not
// be removed (tried again next time). A file is only removed when it lies inside DIR, also
// through symbolic links. Returns the removed files, relative to DIR.
std::vector<std::string> update_report_manifest(const std::string& dir, const std::vector<std::string>& files);

}  // namespace strictmin
