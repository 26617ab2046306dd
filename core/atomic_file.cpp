#include "core/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <system_error>

namespace la {
namespace {

// How many unique temporary names to try before giving up. A clash needs another
// writer with the same process id, counter and 64 random bits: one retry is already
// paranoia; the limit only guarantees termination.
constexpr int kMaxTemporaryNameAttempts = 16;

// The text of an OS error number, as strerror gives it (but thread-safe).
std::string osError(int error_number) {
  return std::system_category().message(error_number);
}

[[noreturn]] void failWrite(const std::filesystem::path& path, const std::string& step,
                            int error_number) {
  throw std::runtime_error("cannot write " + path.string() + ": " + step + ": " +
                           osError(error_number));
}

// A name no other writer uses: ".<target name>.tmp-<pid>-<counter>-<random hex>".
// The leading dot hides it from directory listings and globs such as *.json.
std::filesystem::path temporaryName(const std::filesystem::path& path) {
  static std::atomic<unsigned long long> counter{0};
  thread_local std::mt19937_64 random_bits{std::random_device{}()};
  char suffix[80];
  std::snprintf(suffix, sizeof suffix, ".tmp-%ld-%llu-%016llx", static_cast<long>(::getpid()),
                counter.fetch_add(1), static_cast<unsigned long long>(random_bits()));
  std::filesystem::path directory = path.parent_path();
  if (directory.empty()) directory = ".";
  std::string name = ".";  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on "." + s
  name += path.filename().string();
  name += suffix;
  return directory / name;
}

// Closes fd on every path out of writeFileAtomically, and removes the temporary
// file unless the rename succeeded.
class TemporaryFile {
 public:
  TemporaryFile(int fd, std::filesystem::path name) : m_fd(fd), m_name(std::move(name)) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  ~TemporaryFile() {
    if (m_fd >= 0) ::close(m_fd);
    if (!m_renamed) ::unlink(m_name.c_str());  // best effort: we are already failing
  }
  int fd() const { return m_fd; }
  const std::filesystem::path& name() const { return m_name; }
  /// Returns the error number of close(2), 0 on success.
  int close() {
    const int result = ::close(m_fd);
    m_fd = -1;
    return result == 0 ? 0 : errno;
  }
  void markRenamed() { m_renamed = true; }

 private:
  int m_fd = -1;
  std::filesystem::path m_name;
  bool m_renamed = false;
};

// fsync of the directory holding `path`, so that the rename is durable. Some file
// systems refuse fsync on directories (EINVAL); the data are safe regardless, so
// only real I/O errors are reported.
void syncDirectory(const std::filesystem::path& path) {
  std::filesystem::path directory = path.parent_path();
  if (directory.empty()) directory = ".";
  const int fd = ::open(directory.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;  // the file is written and renamed; durability is best effort here
  const int result = ::fsync(fd);
  const int error_number = errno;
  ::close(fd);
  if (result != 0 && error_number == EIO) failWrite(path, "fsync of directory", error_number);
}

}  // namespace

void writeFileAtomically(const std::filesystem::path& path, std::string_view contents) {
  if (path.filename().empty())
    throw std::runtime_error("cannot write " + path.string() + ": not a file name");

  int fd = -1;
  std::filesystem::path name;
  for (int attempt = 0; attempt < kMaxTemporaryNameAttempts; ++attempt) {
    name = temporaryName(path);
    fd = ::open(name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd >= 0 || errno != EEXIST) break;
  }
  if (fd < 0) {
    const int error_number = errno;
    failWrite(path, "creating temporary file " + name.string(), error_number);
  }
  TemporaryFile temporary(fd, name);

  const char* data = contents.data();
  std::size_t remaining = contents.size();
  while (remaining > 0) {
    const ssize_t written = ::write(temporary.fd(), data, remaining);
    if (written < 0) {
      const int error_number = errno;
      if (error_number == EINTR) continue;
      failWrite(path, "writing temporary file " + name.string(), error_number);
    }
    data += written;
    remaining -= static_cast<std::size_t>(written);
  }
  if (::fsync(temporary.fd()) != 0) {
    const int error_number = errno;
    failWrite(path, "fsync of temporary file " + name.string(), error_number);
  }
  if (const int error_number = temporary.close(); error_number != 0)
    failWrite(path, "closing temporary file " + name.string(), error_number);
  if (::rename(name.c_str(), path.c_str()) != 0) {
    const int error_number = errno;
    failWrite(path, "renaming temporary file " + name.string() + " over it", error_number);
  }
  temporary.markRenamed();
  syncDirectory(path);
}

std::string readFile(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int error_number = errno;
    throw std::runtime_error("cannot open " + path.string() + ": " + osError(error_number));
  }
  std::string contents;
  char buffer[1 << 16];
  for (;;) {
    const ssize_t count = ::read(fd, buffer, sizeof buffer);
    if (count == 0) break;
    if (count < 0) {
      if (errno == EINTR) continue;
      const int error_number = errno;
      ::close(fd);
      throw std::runtime_error("cannot read " + path.string() + ": " + osError(error_number));
    }
    contents.append(buffer, static_cast<std::size_t>(count));
  }
  ::close(fd);
  return contents;
}

}  // namespace la
