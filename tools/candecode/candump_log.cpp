#include "candump_log.hpp"

#include <cctype>
#include <cstdlib>
#include <cstring>

namespace mrqp::tools {
namespace {

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// candump -L writes "%lld.%06ld": digits, a point, digits. Nothing else is a timestamp (no sign,
// exponent, "nan" or "inf"), and at most 12 + 9 digits keep it finite and exactly printable.
bool validTimestamp(const std::string& ts) {
  const std::size_t point = ts.find('.');
  const std::size_t int_digits = point == std::string::npos ? ts.size() : point;
  const std::size_t frac_digits = point == std::string::npos ? 0 : ts.size() - point - 1;
  if (int_digits == 0 || int_digits > 12 || frac_digits > 9 ||
      (point != std::string::npos && frac_digits == 0)) {
    return false;
  }
  for (std::size_t k = 0; k < ts.size(); ++k) {
    if (k != point && (ts[k] < '0' || ts[k] > '9')) return false;
  }
  return true;
}

bool validFdLength(unsigned n) {
  return n <= 8 || n == 12 || n == 16 || n == 20 || n == 24 || n == 32 || n == 48 || n == 64;
}

}  // namespace

bool parseCandumpLine(const std::string& line, LogFrame& out, std::string& error) {
  out = LogFrame{};
  mrqp_fw_frame_clear(&out.frame);
  size_t i = 0;
  if (line.empty() || line[0] != '(') {
    error = "expected '(' and a timestamp";
    return false;
  }
  const size_t close = line.find(')');
  if (close == std::string::npos) {
    error = "unterminated timestamp";
    return false;
  }
  const std::string ts = line.substr(1, close - 1);
  if (!validTimestamp(ts)) {
    error = "bad timestamp '" + ts + "' (expected seconds as digits, e.g. 1700000000.123456)";
    return false;
  }
  out.time = std::strtod(ts.c_str(), nullptr);
  i = close + 1;
  while (i < line.size() && line[i] == ' ') ++i;
  const size_t ifaceEnd = line.find(' ', i);
  if (ifaceEnd == std::string::npos || ifaceEnd == i) {
    error = "missing interface name";
    return false;
  }
  out.iface = line.substr(i, ifaceEnd - i);
  i = ifaceEnd;
  while (i < line.size() && line[i] == ' ') ++i;
  const size_t hash = line.find('#', i);
  if (hash == std::string::npos) {
    error = "missing '#' between identifier and data";
    return false;
  }
  const std::string id = line.substr(i, hash - i);
  if (id.empty() || (id.size() != 3 && id.size() != 8)) {
    error = "identifier '" + id + "' must have 3 or 8 hex digits";
    return false;
  }
  unsigned raw = 0;
  for (char c : id) {
    const int d = hexDigit(c);
    if (d < 0) {
      error = "identifier '" + id + "' is not hexadecimal";
      return false;
    }
    raw = raw * 16u + static_cast<unsigned>(d);
  }
  if (id.size() == 3 && raw > 0x7FFu) {
    error = "identifier '" + id + "' is above 0x7FF, the largest 11-bit identifier";
    return false;
  }
  if (id.size() == 8 && raw > 0x3FFFFFFFu) {
    error = "identifier '" + id + "' has bits above the 29-bit identifier and the error flag";
    return false;
  }
  out.raw_id = raw;
  out.extended = id.size() == 8;
  out.error_frame = out.extended && (raw & 0x20000000u) != 0;
  out.frame.id = out.extended ? (raw & 0x1FFFFFFFu) : raw;
  size_t p = hash + 1;
  if (p < line.size() && line[p] == '#') {  // CAN FD: '##' then one flags nibble
    ++p;
    if (p >= line.size() || hexDigit(line[p]) < 0) {
      error = "CAN FD frame without its flags digit";
      return false;
    }
    out.frame.flags = MRQP_FW_FRAME_FD;
    if (hexDigit(line[p]) & 0x1) out.frame.flags |= MRQP_FW_FRAME_BRS;
    ++p;
  } else if (p < line.size() && (line[p] == 'R' || line[p] == 'r')) {
    out.remote = true;
    out.frame.flags |= MRQP_FW_FRAME_RTR;
    return true;
  }
  std::string data = line.substr(p);
  while (!data.empty() && std::isspace(static_cast<unsigned char>(data.back()))) data.pop_back();
  if (data.size() % 2 != 0) {
    error = "odd number of data hex digits";
    return false;
  }
  const unsigned n = static_cast<unsigned>(data.size() / 2);
  const bool fd = (out.frame.flags & MRQP_FW_FRAME_FD) != 0;
  if ((!fd && n > 8) || (fd && !validFdLength(n))) {
    error = "invalid data length " + std::to_string(n);
    return false;
  }
  for (unsigned k = 0; k < n; ++k) {
    const int hi = hexDigit(data[2 * k]), lo = hexDigit(data[2 * k + 1]);
    if (hi < 0 || lo < 0) {
      error = "data is not hexadecimal";
      return false;
    }
    out.frame.data[k] = static_cast<uint8_t>(hi * 16 + lo);
  }
  out.frame.len = static_cast<uint8_t>(n);
  if (out.extended) out.frame.flags |= MRQP_FW_FRAME_EXT;
  return true;
}

}  // namespace mrqp::tools
