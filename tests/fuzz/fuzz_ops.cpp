// Fuzz target for the geometric ops: bytes choose a sequence of incise, patch, join, resect
// and remesh ops whose points lie on a generated tube (radius 4 mm, length 30 mm, 1,440
// faces; a point is an angle and a height, so it is on the surface the ops see until an op
// moves it), written as a session and replayed with tight limits. Success or a SessionError
// is the expected outcome; a SessionError that says "internal error" (an op's own check
// failed, as the many-point incisions of issue 27 did) is a finding, and so is any other
// exception, a sanitizer report or a hang past libFuzzer's -timeout.
// Built with libFuzzer by scripts/fuzz.sh; corpus_main.cpp replays the committed corpus
// (tests/fuzz/corpus/ops) in every ctest.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <unistd.h>

#include "sutura/app/replay.hpp"
#include "sutura/app/session.hpp"

namespace {

// Reads the input front to back; past its end every value is 0.
class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  [[nodiscard]] bool empty() const { return at_ >= size_; }
  std::uint8_t byte() { return at_ < size_ ? data_[at_++] : 0; }
  /// A value in [lo, hi] in 65,536 steps.
  double in(double lo, double hi) {
    const unsigned v = unsigned(byte()) << 8 | byte();
    return lo + (hi - lo) * double(v) / 65535.0;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_, at_ = 0;
};

constexpr double kRadius = 4.0, kLength = 30.0;

// The tube's surface point at angle theta and height z, as a JSON array.
std::string surface_point(double theta, double z) {
  std::ostringstream os;
  os.precision(6);
  os << '[' << kRadius * std::cos(theta) << ", " << kRadius * std::sin(theta) << ", " << z << ']';
  return os.str();
}

std::string point(Bytes& b) {
  const double theta = b.in(0.0, 2.0 * M_PI);
  return surface_point(theta, b.in(-1.0, kLength + 1.0));
}

std::string ops_session(Bytes& b) {
  std::string s = "{\"format\": \"sutura-session\", \"version\": 3}\n"
                  "{\"op\": \"generate\", \"object\": \"t\", \"shape\": \"tube\", \"radius\": 4, "
                  "\"length\": 30, \"segments_around\": 24, \"segments_along\": 30}\n";
  std::string last_start = point(b), last_end = point(b);
  for (int op = 0; op < 4 && !b.empty(); ++op) {
    std::ostringstream os;
    os.precision(6);
    switch (b.byte() % 5) {
      case 0: {  // an incision of 2 to 40 points, drawn as a run of nearby points or scattered
        const int n = 2 + b.byte() % 39;
        os << "{\"op\": \"incise\", \"object\": \"t\", \"points\": [";
        const double theta0 = b.in(0.0, 2.0 * M_PI), z0 = b.in(0.0, kLength);
        const double dtheta = b.in(-0.3, 0.3), dz = b.in(-1.5, 1.5);
        const bool scattered = b.byte() % 4 == 0;
        for (int i = 0; i < n; ++i) {
          std::string p;
          if (scattered) {
            p = point(b);
          } else {
            const double theta = theta0 + i * dtheta + b.in(-0.02, 0.02);
            p = surface_point(theta, z0 + i * dz / (n - 1) * 4);
          }
          if (i == 0) last_start = p;
          if (i == n - 1) last_end = p;
          os << (i ? ", " : "") << p;
        }
        os << "]}";
        break;
      }
      case 1:  // a patch in the last incision
        os << "{\"op\": \"patch\", \"object\": \"t\", \"start\": " << last_start << ", \"end\": " << last_end
           << ", \"width\": " << b.in(0.5, 6.0) << (b.byte() % 2 ? ", \"shape\": \"ellipse\"" : "") << "}";
        break;
      case 2:  // a suture of two chains drawn between points
        os << "{\"op\": \"join\", \"object\": \"t\", \"chains\": [{\"from\": " << point(b) << ", \"to\": " << point(b)
           << "}, {\"from\": " << point(b) << ", \"to\": " << point(b) << "}]}";
        break;
      case 3: {  // a resection between two planes across the tube, maybe with anastomosis
        const double z1 = b.in(1.0, kLength - 1.0), z2 = b.in(1.0, kLength - 1.0);
        os << "{\"op\": \"resect\", \"object\": \"t\", \"planes\": [{\"origin\": [0, 0, " << z1
           << "], \"normal\": [" << b.in(-0.5, 0.5) << ", 0, -1]}, {\"origin\": [0, 0, " << z2
           << "], \"normal\": [0, " << b.in(-0.5, 0.5) << ", 1]}], \"radius\": 6"
           << (b.byte() % 2 ? ", \"anastomosis\": true" : "") << "}";
        break;
      }
      default:  // a local remesh
        os << "{\"op\": \"remesh\", \"object\": \"t\", \"near\": " << point(b) << ", \"radius\": " << b.in(0.5, 10.0)
           << ", \"target_edge_length\": " << b.in(0.3, 3.0) << "}";
    }
    s += os.str() + "\n";
  }
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace fs = std::filesystem;
  using namespace sutura::app;
  Bytes bytes(data, size);
  const std::string text = ops_session(bytes);
  const fs::path session_file = fs::temp_directory_path() / "fuzz_ops.jsonl";
  ReplayOptions options;
  options.out_dir = fs::temp_directory_path() / ("sutura_fuzz_ops_" + std::to_string(::getpid()));
  options.limits.faces_per_object = 40'000;
  options.limits.faces_in_all = 40'000;
  options.limits.undo_megabytes = 64;
  options.time_limit = 10.0;
  options.threads = 1;
  try {
    replay(parse_session(text, session_file), options);
  } catch (const SessionError& e) {
    if (std::string(e.what()).find("internal error") != std::string::npos) {
      std::fprintf(stderr, "fuzz_ops: %s\nsession:\n%s", e.what(), text.c_str());
      std::abort();
    }
  }
  std::error_code ec;
  fs::remove_all(options.out_dir, ec);
  return 0;
}
