// libFuzzer harness: mrqp-candecode's reading of `candump -L` logs (tools/candecode): the bounded
// line reader, the line parser and the frame decoder with every device kind mapped, and the CSV
// writer on what they produce.
//
// Properties beyond "no crash, no undefined behaviour": a parsed line has a finite, non-negative
// timestamp, an 11-bit identifier <= 0x7FF unless extended, a valid length; every decoded value is
// finite; every CSV row the writer makes has exactly six fields by RFC 4180 (quoted interface names
// cannot shift the columns).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

#include "candump_log.hpp"
#include "csv_writer.hpp"
#include "frame_decoder.hpp"
#include "fuzz_check.hpp"
#include "line_reader.hpp"

namespace {

// Number of fields of one CSV record by RFC 4180 (quoted fields may hold commas and quotes).
int csvFields(const std::string& row) {
  int fields = 1;
  bool quoted = false;
  for (std::size_t i = 0; i < row.size(); ++i) {
    const char c = row[i];
    if (quoted) {
      if (c == '"') {
        if (i + 1 < row.size() && row[i + 1] == '"') {
          ++i;
        } else {
          quoted = false;
        }
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      ++fields;
    }
  }
  return quoted ? -1 : fields;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  mrqp::tools::DeviceMap map;
  map.arm_nodes = {1, 2, 3};
  map.ft_nodes = {5};
  map.mit_ids = {17};
  map.hand_boards = {0, 1};

  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  mrqp::tools::LineReader reader(in);
  std::string line, error;
  std::vector<mrqp::tools::TraceRow> rows;
  mrqp::tools::DecodeCounters counters;
  for (;;) {
    const mrqp::tools::LineStatus status = reader.next(line);
    if (status == mrqp::tools::LineStatus::End || status == mrqp::tools::LineStatus::Binary) break;
    if (status == mrqp::tools::LineStatus::TooLong) continue;
    MRQP_FUZZ_CHECK(line.size() <= mrqp::tools::LineReader::kMaxLineBytes);
    mrqp::tools::LogFrame f;
    if (!mrqp::tools::parseCandumpLine(line, f, error)) {
      MRQP_FUZZ_CHECK(!error.empty());
      continue;
    }
    MRQP_FUZZ_CHECK(std::isfinite(f.time) && f.time >= 0.0);
    MRQP_FUZZ_CHECK(f.extended || f.frame.id <= 0x7FFu);
    MRQP_FUZZ_CHECK(f.frame.len <= 64u);
    MRQP_FUZZ_CHECK(!f.iface.empty());
    rows.clear();
    mrqp::tools::decodeFrame(map, f, rows, counters);
    for (const mrqp::tools::TraceRow& r : rows) {
      MRQP_FUZZ_CHECK(std::isfinite(r.value));
      std::ostringstream csv;
      mrqp::tools::writeTraceRow(csv, r, true);
      std::string row = csv.str();
      MRQP_FUZZ_CHECK(!row.empty() && row.back() == '\n');
      row.pop_back();
      MRQP_FUZZ_CHECK(csvFields(row) == 6);
    }
  }
  return 0;
}
