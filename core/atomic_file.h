#pragma once
// Whole-file reads and crash-safe whole-file writes.
//
// writeFileAtomically follows the usual POSIX recipe: write the new contents to a
// uniquely named temporary file in the target's directory (same file system, so the
// rename below cannot degrade into a copy), fsync it, then rename(2) it over the
// target. rename replaces the directory entry atomically: a concurrent reader opens
// either the complete old file or the complete new one, never a half-written file,
// and if anything fails before the rename the old file is untouched. Finally the
// directory is fsynced so the rename itself survives a power loss.

#include <filesystem>
#include <string>
#include <string_view>

namespace la {

/// Replaces (or creates) `path` with exactly `contents`, atomically as described
/// above. The new file gets mode 0666 minus the umask, like any newly created file.
/// Throws std::runtime_error naming the path, the failed step and the OS error; the
/// temporary file is removed on failure and an existing file at `path` is left as it
/// was.
void writeFileAtomically(const std::filesystem::path& path, std::string_view contents);

/// The whole contents of a file, byte for byte. Throws std::runtime_error
/// "cannot open <path>: <reason>" (or "cannot read ..." when reading fails after the
/// open, e.g. for a directory).
std::string readFile(const std::filesystem::path& path);

}  // namespace la
