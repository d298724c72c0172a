// Recording: lines are appended and flushed as they happen, a failed action's line is taken
// back, and resuming continues an existing file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <unistd.h>

#include "sutura/ui/session_recorder.hpp"

namespace fs = std::filesystem;
using sutura::ui::SessionRecorder;

namespace {

fs::path temp_file(const std::string& name) {
  return fs::temp_directory_path() / ("sutura_rec_" + name + "_" + std::to_string(::getpid()) + ".jsonl");
}

std::string read(const fs::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(SessionRecorder, AppendsFlushedLinesAfterTheHeader) {
  const fs::path f = temp_file("append");
  auto r = SessionRecorder::create(f, "test");
  EXPECT_EQ(r.lines(), 1);
  EXPECT_EQ(r.append({{"op", "generate"}, {"object", "a"}, {"shape", "strip"}}), 2);
  // Visible in the file without closing the recorder (a crash loses nothing).
  const std::string text = read(f);
  EXPECT_NE(text.find("\"format\":\"sutura-session\""), std::string::npos);
  EXPECT_NE(text.find("\"op\":\"generate\""), std::string::npos);
  fs::remove(f);
}

TEST(SessionRecorder, DropLastTakesBackOnlyItsOwnLines) {
  const fs::path f = temp_file("drop");
  auto r = SessionRecorder::create(f, "test");
  r.append({{"op", "a"}});
  const std::string before = read(f);
  r.append({{"op", "b"}});
  r.drop_last();
  EXPECT_EQ(read(f), before);
  EXPECT_EQ(r.lines(), 2);
  r.drop_last();
  EXPECT_THROW(r.drop_last(), std::logic_error);  // the header stays
  EXPECT_EQ(r.append({{"op", "c"}}), 2);
  fs::remove(f);
}

TEST(SessionRecorder, ResumeContinuesAfterExistingLinesAndSaveAsCopies) {
  const fs::path f = temp_file("resume");
  { std::ofstream(f) << "{\"format\": \"sutura-session\", \"version\": 1}\n{\"op\": \"x\"}"; }
  auto r = SessionRecorder::resume(f);
  EXPECT_EQ(r.lines(), 2);  // the missing final newline was added
  EXPECT_EQ(r.append({{"op", "y"}}), 3);
  EXPECT_EQ(read(f), "{\"format\": \"sutura-session\", \"version\": 1}\n{\"op\": \"x\"}\n{\"op\":\"y\"}\n");
  const fs::path copy = temp_file("copy");
  r.save_as(copy);
  EXPECT_EQ(read(copy), read(f));
  fs::remove(f);
  fs::remove(copy);
}
