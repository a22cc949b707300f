#pragma once
// Whole-file reads and all-or-nothing writes: every file Sierra writes (images,
// heightfields, meshes, benchmark reports) goes through writeFileAtomic, so a
// failed or interrupted run never leaves half a file.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sierra {

// The bytes of `path`. Throws sierra::Error "cannot open PATH: <reason>" (the
// system's reason, e.g. "No such file or directory") or "cannot read PATH: ...".
std::vector<uint8_t> readFileBytes(const std::string& path);

// Calls write() on "PATH.tmp-XXXXXXXX" in the same directory, then renames it to
// `path`, so readers see either the old file or the complete new one. On any
// failure (a write error, or write() throwing) the temporary file is removed and
// sierra::Error names the path; an exception from write() is rethrown as is.
void writeFileAtomic(const std::string& path, const std::function<void(std::FILE*)>& write);
void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes);
void writeFileAtomic(const std::string& path, std::string_view text);

}  // namespace sierra
