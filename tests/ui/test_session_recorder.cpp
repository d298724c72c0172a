// Recording: lines are appended and flushed as they happen, a failed action's line is taken
// back, and resuming continues an existing file.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <unistd.h>

#include "sutura/app/session.hpp"
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

TEST(SessionRecorder, ContinueInCopiesTheSessionAndNeverWritesIt) {
  const fs::path from = temp_file("opened");
  { std::ofstream(from) << "{\"format\": \"sutura-session\", \"version\": 1}\n{\"op\": \"x\"}"; }
  const std::string opened = read(from);
  const fs::path f = temp_file("continued");
  auto r = SessionRecorder::continue_in(from, f);
  EXPECT_EQ(r.lines(), 2);  // the missing final newline was added
  // New lines mean what they mean in the continued session's version (its header stays).
  EXPECT_EQ(r.format_version(), 1);
  EXPECT_EQ(SessionRecorder::create(temp_file("fresh"), "t").format_version(), sutura::app::kSessionFormatVersion);
  fs::remove(temp_file("fresh"));
  EXPECT_EQ(r.append({{"op", "y"}}), 3);
  EXPECT_EQ(read(f), "{\"format\": \"sutura-session\", \"version\": 1}\n{\"op\": \"x\"}\n{\"op\":\"y\"}\n");
  EXPECT_EQ(read(from), opened);
  r.drop_last();
  EXPECT_THROW(r.drop_last(), std::logic_error);  // the copied lines are never taken back
  const fs::path copy = temp_file("copy");
  r.save_as(copy);
  EXPECT_EQ(read(copy), read(f));
  // Never into an existing file, the opened session itself included.
  EXPECT_THROW(SessionRecorder::continue_in(from, from), std::runtime_error);
  EXPECT_EQ(read(from), opened);
  EXPECT_THROW(SessionRecorder::continue_in(temp_file("missing"), temp_file("never")), std::runtime_error);
  EXPECT_FALSE(fs::exists(temp_file("never")));
  const fs::path newer = temp_file("newer");
  { std::ofstream(newer) << "\n{\"format\": \"sutura-session\", \"version\": 99}\n"; }
  EXPECT_THROW(SessionRecorder::continue_in(newer, temp_file("never")), std::runtime_error);
  EXPECT_FALSE(fs::exists(temp_file("never")));
  fs::remove(newer);
  fs::remove(from);
  fs::remove(f);
  fs::remove(copy);
}

// A session's relative mesh paths are read from its own directory: a copy elsewhere (the
// recording that continues it, Save session as) names them again so that they reach the same
// meshes.
TEST(SessionRecorder, CopiesElsewhereKeepTheirMeshes) {
  const fs::path dir = fs::temp_directory_path() / ("sutura_rec_rebase_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "patient");
  std::ofstream(dir / "patient" / "vessel.ply") << "x";
  const fs::path opened = dir / "patient" / "plan.jsonl";
  const std::string header = "{\"format\": \"sutura-session\", \"version\": 3}\n";
  const std::string fix = "{\"op\": \"fix\", \"object\": \"a\", \"boundary\": \"all\"}\n";
  { std::ofstream(opened) << header << "{\"op\": \"load\", \"object\": \"a\", \"file\": \"vessel.ply\"}\n" << fix; }
  const std::string before = read(opened);
  auto r = SessionRecorder::continue_in(opened, dir / "out" / "rec.jsonl");
  const std::string absolute = (dir / "patient" / "vessel.ply").string();
  EXPECT_EQ(read(dir / "out" / "rec.jsonl"),
            header + "{\"file\":\"" + absolute + "\",\"object\":\"a\",\"op\":\"load\"}\n" + fix);
  EXPECT_EQ(read(opened), before);
  // Saved elsewhere, an absolute path stays as it is, and the copy reaches the mesh; onto the
  // opened session, refused.
  r.save_as(dir / "copy.jsonl");
  EXPECT_EQ(read(dir / "copy.jsonl"), read(dir / "out" / "rec.jsonl"));
  EXPECT_THROW(r.save_as(opened), std::runtime_error);
  EXPECT_EQ(read(opened), before);
  // Continued beside it, the relative path stays; saved one directory down, it is named again.
  auto beside = SessionRecorder::continue_in(opened, dir / "patient" / "rec2.jsonl");
  EXPECT_EQ(read(dir / "patient" / "rec2.jsonl"), before);
  beside.save_as(dir / "patient" / "sub" / "copy.jsonl");
  EXPECT_EQ(read(dir / "patient" / "sub" / "copy.jsonl"),
            header + "{\"file\":\"" + absolute + "\",\"object\":\"a\",\"op\":\"load\"}\n" + fix);
  fs::remove_all(dir);
}

// Nothing is lost (issue 27): a recording is never replaced nor shared, an action that cannot
// be written as JSON is refused before anything is written, and Save as never writes onto the
// recording.
TEST(SessionRecorder, AnExistingFileIsNeverReplaced) {
  const fs::path f = temp_file("existing");
  { std::ofstream(f) << "{\"format\": \"sutura-session\", \"version\": 3}\n{\"op\": \"x\"}\n"; }
  const std::string before = read(f);
  try {
    SessionRecorder::create(f, "test");
    FAIL() << "an existing file was opened for recording";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("exists already, and a recording is never overwritten"), std::string::npos)
        << e.what();
  }
  EXPECT_EQ(read(f), before);
  fs::remove(f);
}

TEST(SessionRecorder, TwoRecordersNeverShareAFile) {
  const fs::path f = temp_file("shared");
  auto first = SessionRecorder::create(f, "test");
  EXPECT_THROW(SessionRecorder::create(f, "test"), std::runtime_error);
  const fs::path other = temp_file("other");
  { std::ofstream(other) << "{\"format\": \"sutura-session\", \"version\": 3}\n"; }
  EXPECT_THROW(SessionRecorder::continue_in(other, f), std::runtime_error);
  first.append({{"op", "a"}});
  EXPECT_EQ(first.lines(), 2);
  EXPECT_EQ(read(f), "{\"description\":\"test\",\"format\":\"sutura-session\",\"units\":\"mm\",\"version\":" +
                         std::to_string(sutura::app::kSessionFormatVersion) + "}\n{\"op\":\"a\"}\n");
  fs::remove(f);
  fs::remove(other);
}

TEST(SessionRecorder, AnActionThatIsNotUtf8IsRefusedAndNothingWritten) {
  const fs::path f = temp_file("utf8");
  auto r = SessionRecorder::create(f, "test");
  const std::string before = read(f);
  EXPECT_THROW(r.append({{"op", "export"}, {"file", std::string("a\xff.ply")}}), std::runtime_error);
  EXPECT_EQ(read(f), before);
  EXPECT_EQ(r.lines(), 1);
  EXPECT_EQ(r.append({{"op", "b"}}), 2);
  fs::remove(f);
}

TEST(SessionRecorder, SaveAsNeverWritesOntoTheRecording) {
  const fs::path f = temp_file("save");
  auto r = SessionRecorder::create(f, "test");
  r.append({{"op", "a"}});
  const std::string text = read(f);
  EXPECT_THROW(r.save_as(f), std::runtime_error);
  EXPECT_EQ(read(f), text);
  const fs::path copy = temp_file("save_copy");
  { std::ofstream(copy) << "old"; }
  r.save_as(copy);  // a Save as target chosen by the user is replaced, whole
  EXPECT_EQ(read(copy), text);
  fs::remove(f);
  fs::remove(copy);
}
