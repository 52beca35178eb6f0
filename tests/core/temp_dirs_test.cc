// The suites' temporary directories (tests/support/test_meshes.h): a test
// process that exits normally leaves none behind, whatever it wrote there;
// a failed test keeps its directories and names them.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "support/test_meshes.h"

namespace tessera {
namespace {

// Runs `body` in a child process that then exits normally; returns what
// the child wrote to its pipe (the paths it made).
std::string inChild(void (*body)(int fd)) {
  int fds[2];
  if (pipe(fds) != 0) return "pipe failed";
  const pid_t child = fork();
  if (child == 0) {
    close(fds[0]);
    body(fds[1]);
    close(fds[1]);
    std::exit(0);  // runs the exit handlers, as the end of a test's main does
  }
  close(fds[1]);
  std::string out;
  char buffer[512];
  for (ssize_t n; (n = read(fds[0], buffer, sizeof buffer)) > 0;) out.append(buffer, static_cast<size_t>(n));
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  return out;
}

void makeTwoWithFiles(int fd) {
  for (int i = 0; i < 2; ++i) {
    const std::string dir = testing::makeTempDir("tessera-temp-dirs-test");
    std::filesystem::create_directories(dir + "/nested/deeper");
    std::ofstream(dir + "/nested/deeper/file.bin") << "payload";
    const std::string line = dir + "\n";
    if (write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) std::abort();
  }
}

TEST(TestSupport, TemporaryDirectoriesGoWhenTheProcessExits) {
  ASSERT_EQ(unsetenv("TESSERA_KEEP_TEST_DIRS"), 0);
  const std::string made = inChild(makeTwoWithFiles);
  size_t count = 0;
  for (size_t at = 0, end; (end = made.find('\n', at)) != std::string::npos; at = end + 1, ++count) {
    const std::string dir = made.substr(at, end - at);
    EXPECT_EQ(dir.rfind(std::filesystem::temp_directory_path().string(), 0), 0u) << dir;
    EXPECT_FALSE(std::filesystem::exists(dir)) << dir << " was left behind";
  }
  EXPECT_EQ(count, 2u);
}

TEST(TestSupport, TemporaryDirectoriesStayWhenAskedTo) {
  ASSERT_EQ(setenv("TESSERA_KEEP_TEST_DIRS", "1", 1), 0);
  const std::string made = inChild(makeTwoWithFiles);
  ASSERT_EQ(unsetenv("TESSERA_KEEP_TEST_DIRS"), 0);
  size_t count = 0;
  for (size_t at = 0, end; (end = made.find('\n', at)) != std::string::npos; at = end + 1, ++count) {
    const std::string dir = made.substr(at, end - at);
    EXPECT_TRUE(std::filesystem::exists(dir + "/nested/deeper/file.bin")) << dir;
    std::filesystem::remove_all(dir);
  }
  EXPECT_EQ(count, 2u);
}

// Not run by the suite: the failing test the next one runs in a process of
// its own. It prints the directory it made, then fails.
TEST(TestSupport, DISABLED_FailsAfterWritingADirectory) {
  const std::string dir = testing::makeTempDir("tessera-temp-dirs-failed");
  std::ofstream(dir + "/what-went-wrong.txt") << "evidence";
  std::printf("made %s\n", dir.c_str());
  std::fflush(stdout);
  ADD_FAILURE() << "failing on purpose";
}

TEST(TestSupport, AFailedTestKeepsItsDirectoriesAndNamesThem) {
  ASSERT_EQ(unsetenv("TESSERA_KEEP_TEST_DIRS"), 0);
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string command = self +
                              " --gtest_also_run_disabled_tests"
                              " --gtest_filter=TestSupport.DISABLED_FailsAfterWritingADirectory 2>&1";
  FILE* run = popen(command.c_str(), "r");
  ASSERT_NE(run, nullptr);
  std::string out;
  char buffer[512];
  for (size_t n; (n = fread(buffer, 1, sizeof buffer, run)) > 0;) out.append(buffer, n);
  const int status = pclose(run);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) != 0) << "the failing test passed:\n" << out;
  const size_t at = out.find("made ");
  ASSERT_NE(at, std::string::npos) << out;
  const std::string dir = out.substr(at + 5, out.find('\n', at) - at - 5);
  EXPECT_TRUE(std::filesystem::exists(dir + "/what-went-wrong.txt")) << dir << " was removed:\n" << out;
  EXPECT_NE(out.find("kept " + dir + ": the failed test TestSupport.DISABLED_FailsAfterWritingADirectory"),
            std::string::npos)
      << out;
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace tessera
