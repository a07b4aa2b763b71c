// mrqp-candecode: decodes a `candump -L` log into per-device CSV traces (docs/protocol.md).
#include <sys/stat.h>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "candump_log.hpp"
#include "csv_writer.hpp"
#include "frame_decoder.hpp"
#include "line_reader.hpp"

namespace {

const char* kUsage =
    "usage: mrqp-candecode [options] <candump.log | ->\n"
    "  --arm LIST          CiA 402 arm drive node ids, e.g. 1-7 or 1,2,5\n"
    "  --ft LIST           force/torque sensor node ids (classic frames)\n"
    "  --mit LIST          MIT-mode hand actuator ids\n"
    "  --hand-board LIST   packed CAN FD hand board numbers\n"
    "  --increments-per-rev N   arm encoder scaling (default 524288)\n"
    "  --rated-torque-mnm N     arm torque scaling (default 1000)\n"
    "  --split DIR         also write one CSV per device into DIR\n"
    "Prints CSV rows 't,iface,device,message,field,value' (RFC 4180) on stdout and a summary on\n"
    "stderr. Exit status: 0 when frames were read and every line was readable, 3 when some lines\n"
    "were not, 1 when no frame was read (empty, garbage or binary input) or on an error, 2 for a\n"
    "bad command line.\n";

bool parseList(const std::string& s, std::set<unsigned>& out) {
  size_t i = 0;
  while (i < s.size()) {
    size_t j = s.find(',', i);
    if (j == std::string::npos) j = s.size();
    const std::string item = s.substr(i, j - i);
    const size_t dash = item.find('-');
    char* end = nullptr;
    const unsigned long a = std::strtoul(item.c_str(), &end, 0);
    if (end == item.c_str()) return false;
    unsigned long b = a;
    if (dash != std::string::npos) {
      const std::string hi = item.substr(dash + 1);
      b = std::strtoul(hi.c_str(), &end, 0);
      if (end == hi.c_str() || *end) return false;
    } else if (*end) {
      return false;
    }
    if (b < a || b > 2047) return false;
    for (unsigned long k = a; k <= b; ++k) out.insert(static_cast<unsigned>(k));
    i = j + 1;
  }
  return !out.empty();
}

/// A positive 32-bit scaling factor, or 0 when `text` is not one.
uint32_t parseScale(const std::string& text) {
  if (text.empty() || text[0] < '0' || text[0] > '9') return 0;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 0);
  if (*end != '\0' || errno == ERANGE || v > 0xFFFFFFFFull) return 0;
  return static_cast<uint32_t>(v);
}

int run(int argc, char** argv);

}  // namespace

int main(int argc, char** argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception& e) {
    std::cerr << "mrqp-candecode: " << e.what() << "\n";
  } catch (...) {
    std::cerr << "mrqp-candecode: unknown error\n";
  }
  return 1;
}

namespace {

int run(int argc, char** argv) {
  mrqp::tools::DeviceMap map;
  std::string input, split;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "mrqp-candecode: " << a << " needs a value\n" << kUsage;
        std::exit(2);
      }
      return argv[++i];
    };
    auto list = [&](std::set<unsigned>& dst) {
      const std::string v = value();
      if (!parseList(v, dst)) {
        std::cerr << "mrqp-candecode: " << a << ": bad id list '" << v << "'\n";
        std::exit(2);
      }
    };
    if (a == "--arm")
      list(map.arm_nodes);
    else if (a == "--ft")
      list(map.ft_nodes);
    else if (a == "--mit")
      list(map.mit_ids);
    else if (a == "--hand-board")
      list(map.hand_boards);
    else if (a == "--increments-per-rev")
      map.arm_scale.increments_per_rev = parseScale(value());
    else if (a == "--rated-torque-mnm")
      map.arm_scale.rated_torque_mNm = parseScale(value());
    else if (a == "--split")
      split = value();
    else if (a == "-h" || a == "--help") {
      std::cout << kUsage;
      return 0;
    } else if (input.empty())
      input = a;
    else {
      std::cerr << "mrqp-candecode: unexpected argument " << a << "\n" << kUsage;
      return 2;
    }
  }
  if (input.empty()) {
    std::cerr << kUsage;
    return 2;
  }
  if (map.arm_scale.increments_per_rev == 0 || map.arm_scale.rated_torque_mNm == 0) {
    std::cerr << "mrqp-candecode: scaling values must be integers in [1, 4294967295]\n";
    return 2;
  }
  std::ifstream file;
  if (input != "-") {
    file.open(input);
    if (!file) {
      std::cerr << "mrqp-candecode: cannot open " << input << ": " << std::strerror(errno) << "\n";
      return 1;
    }
  }
  std::istream& in = input == "-" ? std::cin : file;
  if (!split.empty() && mkdir(split.c_str(), 0755) != 0 && errno != EEXIST) {
    std::cerr << "mrqp-candecode: cannot create " << split << ": " << std::strerror(errno) << "\n";
    return 1;
  }
  std::map<std::string, std::ofstream> perDevice;
  mrqp::tools::DecodeCounters counters;
  long badLines = 0;
  bool binary = false;
  std::string line, error;
  std::vector<mrqp::tools::TraceRow> rows;
  mrqp::tools::LineReader reader(in);
  std::cout << "t,iface,device,message,field,value\n";
  for (;;) {
    const mrqp::tools::LineStatus status = reader.next(line);
    if (status == mrqp::tools::LineStatus::End) break;
    if (status == mrqp::tools::LineStatus::Binary) {
      std::cerr << "mrqp-candecode: " << input << ":" << reader.lineNumber()
                << ": a NUL byte: binary data, not a candump -L log\n";
      binary = true;
      break;
    }
    if (status == mrqp::tools::LineStatus::TooLong) {
      ++badLines;
      if (badLines <= 10)
        std::cerr << "mrqp-candecode: " << input << ":" << reader.lineNumber() << ": line longer than "
                  << mrqp::tools::LineReader::kMaxLineBytes << " bytes\n";
      continue;
    }
    if (line.empty()) continue;
    mrqp::tools::LogFrame f;
    if (!mrqp::tools::parseCandumpLine(line, f, error)) {
      ++badLines;
      if (badLines <= 10)
        std::cerr << "mrqp-candecode: " << input << ":" << reader.lineNumber() << ": " << error << "\n";
      continue;
    }
    rows.clear();
    mrqp::tools::decodeFrame(map, f, rows, counters);
    for (const auto& r : rows) {
      mrqp::tools::writeTraceRow(std::cout, r, true);
      if (split.empty()) continue;
      auto it = perDevice.find(r.device);
      if (it == perDevice.end()) {
        it = perDevice.emplace(r.device, std::ofstream(split + "/" + r.device + ".csv")).first;
        if (!it->second) {
          std::cerr << "mrqp-candecode: cannot write " << split << "/" << r.device << ".csv\n";
          return 1;
        }
        it->second << "t,iface,message,field,value\n";
      }
      mrqp::tools::writeTraceRow(it->second, r, false);
    }
  }
  std::cout.flush();
  std::cerr << "mrqp-candecode: " << reader.lineNumber() << " lines, " << counters.frames << " frames, "
            << counters.decoded << " decoded, " << counters.malformed << " malformed, " << counters.unknown
            << " unknown, " << counters.error_frames << " error frames, " << badLines
            << " unreadable lines\n";
  if (!std::cout) {
    std::cerr << "mrqp-candecode: cannot write the CSV to stdout\n";
    return 1;
  }
  if (binary) return 1;
  if (counters.frames == 0) {
    std::cerr << "mrqp-candecode: " << input << ": no frame read: not a candump -L log\n";
    return 1;
  }
  return badLines > 0 ? 3 : 0;
}

}  // namespace
