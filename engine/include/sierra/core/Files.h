#pragma once
// Whole-file reads and all-or-nothing writes: every file Sierra writes (images,
// heightfields, meshes, benchmark reports) goes through writeFileAtomic, so a
// failed or interrupted run never leaves half a file.

#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace sierra {

// The size in bytes of the regular file at `path` (symlinks followed). Throws
// sierra::Error "cannot open PATH: ..." when it is missing, or "PATH is a
// FIFO/character device/directory/...; expected a regular file": a FIFO would
// block a reader forever and /dev/zero never ends.
uint64_t regularFileSize(const std::string& path);

// The bytes of the regular file `path`, at most `maxBytes` of them. Refuses
// anything but a regular file (see regularFileSize) without blocking, and a file
// larger than maxBytes before reading it ("PATH has N bytes, more than the M
// bytes allowed; <limitReason>"). Throws sierra::Error "cannot open PATH:
// <reason>" (the system's reason, e.g. "No such file or directory") or "cannot
// read PATH: ...".
std::vector<uint8_t> readFileBytes(const std::string& path,
                                   uint64_t maxBytes = std::numeric_limits<uint64_t>::max(),
                                   std::string_view limitReason = {});

// Calls write() on "PATH.tmp-XXXXXXXX" in the same directory, flushes it to disk
// (fsync), renames it to `path` and syncs the directory, so readers see either
// the old file or the complete new one, also after a power loss. A `path` that
// exists and is not a regular file (a symlink, FIFO, device or directory) is
// refused before anything is written: renaming over it would replace the link
// or the device node instead of writing through it. On any failure (a write
// error, or write() throwing) the temporary file is removed and sierra::Error
// names the path; an exception from write() is rethrown as is.
void writeFileAtomic(const std::string& path, const std::function<void(std::FILE*)>& write);
void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes);
void writeFileAtomic(const std::string& path, std::string_view text);

// Makes sure writeFileAtomic(path, ...) can succeed later: creates the parent
// directory (and its parents) if missing, checks that it is a writable directory
// and that `path`, if it exists, is a regular file. Apps call it for every
// output before long work, so a bad --out fails in milliseconds, not after the
// run. Throws sierra::Error "cannot write PATH: ..." naming what is wrong.
void ensureWritableLocation(const std::string& path);

// The extension of `path`'s file name with its dot, in lower case (".png" for
// "out/Frame.PNG"; "" when the name has none).
std::string lowerExtension(const std::string& path);

}  // namespace sierra
