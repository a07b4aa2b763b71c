// The CSV rows mrqp-candecode writes (docs/protocol.md, "Decoding logs"): RFC 4180 — a field
// holding a comma, a double quote, CR or LF is enclosed in double quotes with its quotes doubled —
// and numbers that are always finite (a decoded value is finite by construction of the decoders;
// a non-finite one is written as an empty field rather than "nan").
#pragma once

#include <ostream>
#include <string>

#include "frame_decoder.hpp"

namespace mrqp::tools {

/// `field` as one RFC 4180 field.
std::string csvField(const std::string& field);

/// "t,iface,device,message,field,value\n" (without device when `with_device` is false).
void writeTraceRow(std::ostream& out, const TraceRow& row, bool with_device);

}  // namespace mrqp::tools
