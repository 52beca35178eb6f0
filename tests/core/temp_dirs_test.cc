// The suites' temporary directories (tests/support/test_meshes.h): a test
// process that exits normally leaves none behind, whatever it wrote there.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

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

}  // namespace
}  // namespace tessera
