// Output files (rgraph/output_file.h): a failed write says why and leaves an
// earlier file whole; links and devices are written through, never replaced.
#include "rgraph/output_file.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <string>

#include "rgraph/error.h"

namespace fs = std::filesystem;
using namespace rgraph;

namespace {

class OutputFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rgraph-output-file-test-" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  size_t entries() const { return static_cast<size_t>(std::distance(fs::directory_iterator(dir_), {})); }
  // The message writeOutputFile throws, "" when it does not.
  static std::string failure(const std::string& p, const std::string& bytes) {
    try {
      writeOutputFile(p, bytes, "PNG file");
    } catch (const RuntimeError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

TEST_F(OutputFile, ReplacesAFileKeepingItsModeAndLeavesNoTemporary) {
  writeOutputFile(path("a"), "first");
  fs::permissions(path("a"), fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  writeOutputFile(path("a"), "second");
  EXPECT_EQ(read(path("a")), "second");
  EXPECT_EQ(fs::status(path("a")).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  EXPECT_EQ(entries(), 1u);
}

TEST_F(OutputFile, WritesThroughLinksAndKeepsThem) {
  writeOutputFile(path("target"), "old");
  fs::create_symlink("target", path("link"));
  fs::create_symlink("missing", path("dangling"));
  writeOutputFile(path("link"), "new");
  writeOutputFile(path("dangling"), "made");
  EXPECT_TRUE(fs::is_symlink(path("link")));
  EXPECT_TRUE(fs::is_symlink(path("dangling")));
  EXPECT_EQ(read(path("target")), "new");
  EXPECT_EQ(read(path("missing")), "made");
  EXPECT_EQ(outputFileTarget(path("link")), outputFileTarget(path("target")));
  EXPECT_EQ(outputFileTarget(path("dangling")), outputFileTarget(dir_.string() + "/./missing"));
}

TEST_F(OutputFile, ADeviceIsWrittenInPlaceAndItsErrorsReported) {
  EXPECT_EQ(failure("/dev/null", "x"), "");
  EXPECT_EQ(failure("/dev/full", "x"), "cannot write PNG file /dev/full: No space left on device");
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
  try {
    appendToFile("/dev/full", "line\n", "the status file");
    ADD_FAILURE() << "appending to /dev/full did not fail";
  } catch (const RuntimeError& e) {
    EXPECT_STREQ(e.what(), "cannot write the status file /dev/full: No space left on device");
  }
}

// A write that fails half way (a file size limit here, as a full disk): the
// earlier file is untouched and the temporary removed.
TEST_F(OutputFile, AFailedWriteLeavesTheEarlierFileWhole) {
  writeOutputFile(path("a"), "earlier");
  struct rlimit old {};
  ASSERT_EQ(::getrlimit(RLIMIT_FSIZE, &old), 0);
  auto* previous = std::signal(SIGXFSZ, SIG_IGN);  // write() then fails with EFBIG
  struct rlimit small = old;
  small.rlim_cur = 1000;
  ASSERT_EQ(::setrlimit(RLIMIT_FSIZE, &small), 0);
  const std::string message = failure(path("a"), std::string(5000, 'x'));
  ::setrlimit(RLIMIT_FSIZE, &old);
  std::signal(SIGXFSZ, previous);
  EXPECT_EQ(message, "cannot write PNG file " + path("a") + ": File too large");
  EXPECT_EQ(read(path("a")), "earlier");
  EXPECT_EQ(entries(), 1u) << "a temporary file was left";
}

TEST_F(OutputFile, ProblemsAreToldBeforeAnyWrite) {
  EXPECT_EQ(outputFileProblem(path("new")), "");
  EXPECT_EQ(entries(), 0u) << "the probe was left";
  EXPECT_EQ(outputFileProblem(path("no/such/x")), "no such folder '" + path("no/such") + "'");
  EXPECT_EQ(outputFileProblem(dir_.string()), "is a folder");
  EXPECT_EQ(outputFileProblem(dir_.string() + "/"), "names a folder, not a file");
  EXPECT_EQ(outputFileProblem(""), "no file name given");
  writeOutputFile(path("f"), "x");
  EXPECT_EQ(outputFileProblem(path("f/x")), "Not a directory");
  if (::geteuid() != 0) {  // root writes anywhere
    fs::permissions(path("f"), fs::perms::owner_read);
    EXPECT_EQ(outputFileProblem(path("f")), "Permission denied");
    EXPECT_NE(failure(path("f"), "y"), "");
    EXPECT_EQ(read(path("f")), "x") << "a read-only file was replaced";
  }
}

}  // namespace
