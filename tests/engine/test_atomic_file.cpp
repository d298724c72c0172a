// Atomic file output: content lands complete or not at all, and no temporary is left behind.
#include <gtest/gtest.h>

#include <stdexcept>

#include "sutura/engine/atomic_file.hpp"
#include "temp_dir.hpp"

namespace sutura::engine {
namespace {

using testing::read_bytes;
using testing::TempDir;
using testing::write_bytes;
namespace fs = std::filesystem;

TEST(AtomicFile, WritesNewFile) {
  const TempDir dir;
  write_file_atomically(dir / "out.txt", "hello\n");
  EXPECT_EQ(read_bytes(dir / "out.txt"), "hello\n");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"out.txt"}));
}

TEST(AtomicFile, ReplacesExistingFile) {
  const TempDir dir;
  write_bytes(dir / "out.txt", "old content that is longer than the new one");
  write_file_atomically(dir / "out.txt", "new");
  EXPECT_EQ(read_bytes(dir / "out.txt"), "new");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"out.txt"}));
}

TEST(AtomicFile, WritesEmptyAndBinaryContent) {
  const TempDir dir;
  write_file_atomically(dir / "empty.bin", "");
  EXPECT_TRUE(fs::exists(dir / "empty.bin"));
  EXPECT_EQ(fs::file_size(dir / "empty.bin"), 0u);
  const std::string binary("a\0b\xff", 4);
  write_file_atomically(dir / "binary.bin", binary);
  EXPECT_EQ(read_bytes(dir / "binary.bin"), binary);
}

TEST(AtomicFile, WriterGetsAHiddenSiblingTemporary) {
  const TempDir dir;
  fs::path seen;
  write_atomically(dir / "mesh.obj", [&](const fs::path& tmp) {
    seen = tmp;
    EXPECT_TRUE(fs::exists(tmp));
    write_bytes(tmp, "x");
  });
  EXPECT_EQ(seen.parent_path(), dir.path());
  EXPECT_NE(seen.filename(), "mesh.obj");
  EXPECT_EQ(seen.filename().string().front(), '.');
  EXPECT_FALSE(fs::exists(seen));
  EXPECT_EQ(read_bytes(dir / "mesh.obj"), "x");
}

TEST(AtomicFile, ThrowingWriterLeavesPreviousFileAndNoTemporary) {
  const TempDir dir;
  write_bytes(dir / "out.txt", "previous");
  EXPECT_THROW(write_atomically(dir / "out.txt",
                                [](const fs::path& tmp) {
                                  write_bytes(tmp, "half of the new con");
                                  throw std::logic_error("writer failed");
                                }),
               std::logic_error);
  EXPECT_EQ(read_bytes(dir / "out.txt"), "previous");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"out.txt"}));
}

TEST(AtomicFile, ThrowingWriterWithoutPreviousFileLeavesNothing) {
  const TempDir dir;
  EXPECT_THROW(write_atomically(dir / "out.txt", [](const fs::path&) { throw 42; }), int);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicFile, FailedRenameNamesTheTargetAndCleansUp) {
  const TempDir dir;
  fs::create_directory(dir / "taken");
  write_bytes(dir / "taken" / "keep.txt", "keep");
  try {
    write_file_atomically(dir / "taken", "data");
    ADD_FAILURE() << "expected the rename over a directory to fail";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find((dir / "taken").string()), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"taken"}));
  EXPECT_EQ(read_bytes(dir / "taken" / "keep.txt"), "keep");
}

TEST(AtomicFile, MissingDirectoryIsAnError) {
  const TempDir dir;
  EXPECT_THROW(write_file_atomically(dir / "no" / "such" / "dir.txt", "data"), std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(AtomicFile, PathWithoutFileNameIsAnError) {
  const TempDir dir;
  EXPECT_THROW(write_file_atomically(dir.path() / "", "data"), std::runtime_error);
  EXPECT_TRUE(dir.entries().empty());
}

}  // namespace
}  // namespace sutura::engine
