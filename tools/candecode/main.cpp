// mrqp-candecode: decodes a `candump -L` log into per-device CSV traces (docs/protocol.md).
#include <sys/stat.h>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <string>

#include "candump_log.hpp"
#include "frame_decoder.hpp"

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
    "Prints CSV rows 't,iface,device,message,field,value' on stdout and a summary on stderr.\n";

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

void printRow(std::ostream& o, const mrqp::tools::TraceRow& r, bool withDevice) {
  char t[32], v[40];
  std::snprintf(t, sizeof t, "%.6f", r.time);
  std::snprintf(v, sizeof v, "%.9g", r.value);
  o << t << ',' << r.iface << ',';
  if (withDevice) o << r.device << ',';
  o << r.message << ',' << r.field << ',' << v << '\n';
}

}  // namespace

int main(int argc, char** argv) {
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
      map.arm_scale.increments_per_rev = static_cast<uint32_t>(std::strtoul(value().c_str(), nullptr, 0));
    else if (a == "--rated-torque-mnm")
      map.arm_scale.rated_torque_mNm = static_cast<uint32_t>(std::strtoul(value().c_str(), nullptr, 0));
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
    std::cerr << "mrqp-candecode: scaling values must be positive\n";
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
  long lineNo = 0, badLines = 0;
  std::string line, error;
  std::vector<mrqp::tools::TraceRow> rows;
  std::cout << "t,iface,device,message,field,value\n";
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    mrqp::tools::LogFrame f;
    if (!mrqp::tools::parseCandumpLine(line, f, error)) {
      ++badLines;
      if (badLines <= 10) std::cerr << "mrqp-candecode: " << input << ":" << lineNo << ": " << error << "\n";
      continue;
    }
    rows.clear();
    mrqp::tools::decodeFrame(map, f, rows, counters);
    for (const auto& r : rows) {
      printRow(std::cout, r, true);
      if (split.empty()) continue;
      auto it = perDevice.find(r.device);
      if (it == perDevice.end()) {
        it = perDevice.emplace(r.device, std::ofstream(split + "/" + r.device + ".csv")).first;
        it->second << "t,iface,message,field,value\n";
      }
      printRow(it->second, r, false);
    }
  }
  std::cerr << "mrqp-candecode: " << lineNo << " lines, " << counters.frames << " frames, "
            << counters.decoded << " decoded, " << counters.malformed << " malformed, " << counters.unknown
            << " unknown, " << counters.error_frames << " error frames, " << badLines
            << " unreadable lines\n";
  return badLines > 0 ? 3 : 0;
}
