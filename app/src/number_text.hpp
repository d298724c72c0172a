#pragma once
// Numbers as text in messages and reports: one formatter for the session layer.
#include <cstdio>
#include <string>

namespace sutura::app::detail {

/// `v` with `decimals` (0 ... 17) digits after the point, as printf's "%.*f" in the C locale
/// (the program never sets another); beyond 63 characters (|v| > 1e50 or so) the text is cut.
inline std::string fixed(double v, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  return buf;
}

/// `v` with 6 significant digits, as "%.6g".
inline std::string general(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

}  // namespace sutura::app::detail
