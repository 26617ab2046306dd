// Tests of core/atomic_file.h: contents read back byte for byte, failures name the
// path and the OS error, and a failed write leaves the old file and no temporary
// file behind. A concurrent reader must only ever see complete versions.

#include "core/atomic_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace la {
namespace {

namespace fs = std::filesystem;

// A fresh directory per test, removed afterwards.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    m_dir = fs::temp_directory_path() /
            ("atomic_file_test-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(m_dir);
    fs::create_directories(m_dir);
  }
  void TearDown() override {
    std::error_code ignored;  // best effort: a leftover directory in /tmp is harmless
    fs::remove_all(m_dir, ignored);
  }

  // Names in the test directory, to show that no temporary file was left behind.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(m_dir))
      names.push_back(entry.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
  }

  fs::path m_dir;
};

// The message of the std::runtime_error `write` throws; fails the test if none.
template <class Write>
std::string errorOf(Write write) {
  try {
    write();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected std::runtime_error";
  return "";
}

TEST_F(AtomicFileTest, WritesAndReadsBackExactly) {
  const fs::path path = m_dir / "out.json";
  std::string binary = "first line\nsecond\r\n";
  binary += std::string("\0\xff\x01 tail", 8);
  writeFileAtomically(path, binary);
  EXPECT_EQ(readFile(path), binary);

  const std::string shorter = "short";  // replacing must not leave old bytes behind
  writeFileAtomically(path, shorter);
  EXPECT_EQ(readFile(path), shorter);

  writeFileAtomically(path, "");
  EXPECT_EQ(readFile(path), "");
  EXPECT_EQ(entries(), std::vector<std::string>{"out.json"});
}

TEST_F(AtomicFileTest, NewFileGetsModeFromUmask) {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  const fs::path path = m_dir / "mode.txt";
  writeFileAtomically(path, "x");
  struct stat status {};
  ASSERT_EQ(::stat(path.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0666 & ~mask) << "umask " << std::oct << mask;
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsWithPathAndReason) {
  const fs::path path = m_dir / "no_such_dir" / "out.json";
  const std::string message = errorOf([&] { writeFileAtomically(path, "data"); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find(std::strerror(ENOENT)), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(m_dir / "no_such_dir"));
}

TEST_F(AtomicFileTest, TargetThatIsADirectoryIsLeftIntact) {
  const fs::path target = m_dir / "target";
  fs::create_directory(target);
  writeFileAtomically(target / "inside.txt", "kept");

  const std::string message = errorOf([&] { writeFileAtomically(target, "data"); });
  EXPECT_NE(message.find(target.string()), std::string::npos) << message;
  EXPECT_TRUE(fs::is_directory(target));
  EXPECT_EQ(readFile(target / "inside.txt"), "kept");
  EXPECT_EQ(entries(), std::vector<std::string>{"target"}) << "temporary file left behind";
}

// Makes write(2) fail part way with EFBIG: files may grow to `limit` bytes only.
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t limit) {
    ::getrlimit(RLIMIT_FSIZE, &m_saved);
    m_saved_handler = std::signal(SIGXFSZ, SIG_IGN);  // else the process is killed
    rlimit lowered = m_saved;
    lowered.rlim_cur = limit;
    m_ok = ::setrlimit(RLIMIT_FSIZE, &lowered) == 0;
  }
  ~FileSizeLimit() {
    ::setrlimit(RLIMIT_FSIZE, &m_saved);
    std::signal(SIGXFSZ, m_saved_handler);
  }
  bool ok() const { return m_ok; }

 private:
  rlimit m_saved{};
  void (*m_saved_handler)(int) = SIG_DFL;
  bool m_ok = false;
};

TEST_F(AtomicFileTest, FailureHalfWayLeavesOldFileIntact) {
  const fs::path path = m_dir / "curves.json";
  const std::string old_contents = "{\"curves\": []}\n";
  writeFileAtomically(path, old_contents);

  constexpr rlim_t kLimit = 4096;
  const std::string big(16 * kLimit, 'x');  // the first 4096 bytes get written
  std::string message;
  {
    FileSizeLimit limit(kLimit);
    ASSERT_TRUE(limit.ok()) << "cannot lower RLIMIT_FSIZE: " << std::strerror(errno);
    message = errorOf([&] { writeFileAtomically(path, big); });
  }
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find(std::strerror(EFBIG)), std::string::npos) << message;
  EXPECT_EQ(readFile(path), old_contents);
  EXPECT_EQ(entries(), std::vector<std::string>{"curves.json"}) << "temporary file left behind";
}

TEST_F(AtomicFileTest, ConcurrentReaderSeesOnlyCompleteVersions) {
  // A writer that truncated and rewrote in place would show a reader empty or mixed
  // contents; rename never does. 256 KiB versions take several write(2) calls.
  const fs::path path = m_dir / "shared.txt";
  const std::string version_a(256 * 1024, 'a'), version_b(256 * 1024, 'b');
  writeFileAtomically(path, version_a);

  std::atomic<bool> done{false};
  int reads = 0, torn = 0;
  std::thread reader([&] {
    do {
      const std::string seen = readFile(path);
      ++reads;
      if (seen != version_a && seen != version_b) ++torn;
    } while (!done.load());
  });
  constexpr int kWrites = 40;
  for (int i = 0; i < kWrites; ++i) writeFileAtomically(path, i % 2 ? version_a : version_b);
  done = true;
  reader.join();
  EXPECT_EQ(torn, 0) << "of " << reads << " reads";
  std::printf("%d reads during %d writes, none torn\n", reads, kWrites);
  EXPECT_EQ(readFile(path), version_a);
  EXPECT_EQ(entries(), std::vector<std::string>{"shared.txt"});
}

TEST_F(AtomicFileTest, ReadFileErrorsNameThePathAndReason) {
  const fs::path missing = m_dir / "missing.json";
  EXPECT_EQ(errorOf([&] { readFile(missing); }),
            "cannot open " + missing.string() + ": " + std::strerror(ENOENT));

  const std::string message = errorOf([&] { readFile(m_dir); });
  EXPECT_NE(message.find(m_dir.string()), std::string::npos) << message;
  EXPECT_NE(message.find(std::strerror(EISDIR)), std::string::npos) << message;
}

}  // namespace
}  // namespace la
