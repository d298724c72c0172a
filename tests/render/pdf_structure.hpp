#pragma once
// Test helper: a PDF's cross-reference table and stream lengths hold (poppler repairs a broken
// table, so a PDF that rasterises may still be wrong). Used by the render and app tests.
#include <cstddef>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

namespace sutura::testing {

/// Success when the file ends in startxref -> an xref table of `objects` + 1 entries (the free
/// head and one "n" entry per object), each entry's offset is where "<i> 0 obj" starts, and
/// every stream is exactly its /Length long (followed by "endstream", or a newline and it).
/// `objects` < 0: any count.
inline ::testing::AssertionResult pdf_structure_holds(const std::string& pdf, int objects = -1) {
  const std::size_t startxref = pdf.rfind("startxref\n");
  if (startxref == std::string::npos) return ::testing::AssertionFailure() << "no startxref";
  const std::size_t xref = std::stoul(pdf.substr(startxref + 10));
  if (pdf.compare(xref, 5, "xref\n") != 0) return ::testing::AssertionFailure() << "startxref misses the table";
  std::istringstream table(pdf.substr(xref + 5));
  int first = -1, count = 0;
  table >> first >> count;
  if (first != 0 || (objects >= 0 && count != objects + 1))
    return ::testing::AssertionFailure() << "table " << first << " " << count;
  std::string offset, generation, kind;
  table >> offset >> generation >> kind;
  if (kind != "f") return ::testing::AssertionFailure() << "entry 0 is not free";
  for (int i = 1; i < count; ++i) {
    table >> offset >> generation >> kind;
    if (kind != "n") return ::testing::AssertionFailure() << "entry " << i << " is not in use";
    const std::size_t at = std::stoul(offset);
    const std::string head = std::to_string(i) + " 0 obj\n";
    if (pdf.compare(at, head.size(), head) != 0) return ::testing::AssertionFailure() << "object " << i << " is not at " << at;
    const std::size_t end = pdf.find("endobj", at);
    const std::size_t length = pdf.find("/Length ", at);
    if (length == std::string::npos || length > end) continue;
    const std::size_t n = std::stoul(pdf.substr(length + 8));
    const std::size_t begin = pdf.find("stream\n", length) + 7;
    if (pdf.compare(begin + n, 9, "endstream") != 0 && pdf.compare(begin + n, 10, "\nendstream") != 0)
      return ::testing::AssertionFailure() << "object " << i << "'s stream is not " << n << " bytes";
  }
  return ::testing::AssertionSuccess();
}

}  // namespace sutura::testing
