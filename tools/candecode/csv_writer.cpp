// CSV rows of decoded frames (csv_writer.hpp).
#include "csv_writer.hpp"

#include <cmath>
#include <cstdio>

namespace mrqp::tools {

std::string csvField(const std::string& field) {
  if (field.find_first_of(",\"\r\n") == std::string::npos) return field;
  std::string out = "\"";
  for (const char c : field) {
    if (c == '"') out.push_back('"');
    out.push_back(c);
  }
  out.push_back('"');
  return out;
}

void writeTraceRow(std::ostream& out, const TraceRow& row, bool with_device) {
  char t[40] = "";
  char v[40] = "";
  if (std::isfinite(row.time)) std::snprintf(t, sizeof t, "%.6f", row.time);
  if (std::isfinite(row.value)) std::snprintf(v, sizeof v, "%.9g", row.value);
  out << t << ',' << csvField(row.iface) << ',';
  if (with_device) out << csvField(row.device) << ',';
  out << csvField(row.message) << ',' << csvField(row.field) << ',' << v << '\n';
}

}  // namespace mrqp::tools
