// Keeps the temporary directories of a failed test and names them
// (tests/support/test_meshes.h makeTempDir): what a failure wrote is there
// to look at, and a passing run leaves nothing behind. Linked into every
// test suite; registers itself before main runs the tests.
#include <gtest/gtest.h>

#include <string>

#include "support/test_meshes.h"

namespace tessera::testing {
namespace {

class KeepFailedTestDirs : public ::testing::EmptyTestEventListener {
  void OnTestEnd(const ::testing::TestInfo& test) override {
    if (test.result()->Failed())
      keepTempDirs(std::string("the failed test ") + test.test_suite_name() + "." + test.name() +
                   " wrote there");
  }
};

[[maybe_unused]] const bool kRegistered = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new KeepFailedTestDirs);  // gtest owns it
  return true;
}();

}  // namespace
}  // namespace tessera::testing
