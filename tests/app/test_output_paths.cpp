#include <gtest/gtest.h>

#include <fstream>

#include "sutura/app/output_paths.hpp"

namespace fs = std::filesystem;
using sutura::app::output_path_problem;
using sutura::app::resolve_output_path;

namespace {
fs::path fresh_dir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("sutura_paths_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}
}  // namespace

TEST(OutputPaths, AcceptsPlainRelativePathsAndCreatesParents) {
  fs::path out = fresh_dir("ok");
  EXPECT_EQ(output_path_problem("a.png"), "");
  EXPECT_EQ(output_path_problem("shots/deep/a.png"), "");
  fs::path p = resolve_output_path(out / "new", "shots/deep/a.png");
  EXPECT_TRUE(fs::is_directory(out / "new" / "shots" / "deep"));
  EXPECT_EQ(p.filename(), "a.png");
  EXPECT_EQ(fs::canonical(p.parent_path()), fs::canonical(out / "new" / "shots" / "deep"));
  fs::remove_all(out);
}

TEST(OutputPaths, RejectsEscapes) {
  EXPECT_NE(output_path_problem(""), "");
  EXPECT_NE(output_path_problem("/etc/passwd"), "");
  EXPECT_NE(output_path_problem("../a.png"), "");
  EXPECT_NE(output_path_problem("a/../../b.png"), "");
  EXPECT_NE(output_path_problem("a/.."), "");
  EXPECT_NE(output_path_problem("dir/"), "");
  // Control characters (issue 27): a NUL cut "evil.sh\0.obj" short to evil.sh.
  EXPECT_NE(output_path_problem(fs::path(std::string("evil.sh\0.obj", 12))).find("byte 0x00, NUL"), std::string::npos);
  EXPECT_NE(output_path_problem("a\nb.obj").find("byte 0x0a, newline"), std::string::npos);
  EXPECT_NE(output_path_problem("a\tb.obj"), "");
  EXPECT_EQ(output_path_problem("caf\xc3\xa9 1.obj"), "");  // UTF-8 and spaces are fine
  fs::path out = fresh_dir("esc");
  EXPECT_THROW(resolve_output_path(out, "/tmp/x.png"), std::invalid_argument);
  EXPECT_THROW(resolve_output_path(out, "a/../../x.png"), std::invalid_argument);
  fs::remove_all(out);
}

TEST(OutputPaths, RejectsSymlinkLeadingOutside) {
  fs::path out = fresh_dir("link");
  fs::path outside = fresh_dir("outside");
  fs::create_directory_symlink(outside, out / "escape");
  EXPECT_THROW(resolve_output_path(out, "escape/x.png"), std::invalid_argument);
  EXPECT_THROW(resolve_output_path(out, "escape/sub/x.png"), std::invalid_argument);
  EXPECT_FALSE(fs::exists(outside / "sub"));  // nothing created outside
  fs::create_symlink(outside / "target.png", out / "file.png");
  EXPECT_THROW(resolve_output_path(out, "file.png"), std::invalid_argument);
  // A symlink that stays inside is fine.
  fs::create_directories(out / "real");
  fs::create_directory_symlink(out / "real", out / "alias");
  EXPECT_NO_THROW(resolve_output_path(out, "alias/x.png"));
  fs::remove_all(out);
  fs::remove_all(outside);
}

TEST(OutputPaths, RejectsExistingDirectoryAsFile) {
  fs::path out = fresh_dir("dir");
  fs::create_directories(out / "a.png");
  EXPECT_THROW(resolve_output_path(out, "a.png"), std::invalid_argument);
  fs::remove_all(out);
}
