// atomic_file: the target holds either the old or the new content, never a mix, and no
// temporary is left behind (success, failure before commit, failing rename).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "core/error.hpp"
#include "io/atomic_file.hpp"
#include "scratch.hpp"

using namespace cgdem::io;
using namespace cgdem::io::test;

TEST(AtomicFile, WritesAndLeavesNoTemporary) {
  const std::string dir = scratch_dir(), f = dir + "/out.txt";
  write_file_atomic(f, "first\n");
  EXPECT_EQ(slurp(f), "first\n");
  write_file_atomic(f, "second, longer content\n");
  EXPECT_EQ(slurp(f), "second, longer content\n");
  write_file_atomic(f, "");
  EXPECT_EQ(slurp(f), "");
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(AtomicFile, TemporaryNameIsInSameDirectory) {
  const std::string t = temporary_path("/a/b/c.h5");
  EXPECT_EQ(t.rfind("/a/b/c.h5.tmp-", 0), 0u) << t;
  EXPECT_THROW(temporary_path(""), cgdem::Error);
}

TEST(AtomicFile, ExceptionBeforeCommitKeepsPreviousFile) {
  const std::string dir = scratch_dir(), f = dir + "/result.dat";
  write_file_atomic(f, "previous good result\n");
  try {
    AtomicTarget t(f);
    std::ofstream(t.tmp_path()) << "half of a new res";  // the writer is interrupted here
    ASSERT_TRUE(std::filesystem::exists(t.tmp_path()));
    throw std::runtime_error("simulated crash during output");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(slurp(f), "previous good result\n");
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(AtomicFile, CommitReplacesFile) {
  const std::string dir = scratch_dir(), f = dir + "/result.dat";
  write_file_atomic(f, "old");
  AtomicTarget t(f);
  std::ofstream(t.tmp_path()) << "new";
  EXPECT_EQ(slurp(f), "old");  // not visible before commit
  t.commit();
  EXPECT_EQ(slurp(f), "new");
  EXPECT_EQ(count_temporaries(dir), 0);
}

TEST(AtomicFile, ErrorsNameTheFile) {
  const std::string dir = scratch_dir();
  try {
    write_file_atomic(dir + "/no_such_dir/x.txt", "data");
    FAIL() << "expected cgdem::Error";
  } catch (const cgdem::Error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_dir/x.txt"), std::string::npos) << e.what();
  }
  // Commit without the writer having produced the temporary: error, target not created.
  AtomicTarget t(dir + "/never.dat");
  EXPECT_THROW(t.commit(), cgdem::Error);
  EXPECT_FALSE(std::filesystem::exists(dir + "/never.dat"));
  EXPECT_EQ(count_temporaries(dir), 0);
}
