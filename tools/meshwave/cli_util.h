// Small helpers shared by the CLI commands: error reporting and JSON output.
#ifndef MESHWAVE_TOOLS_CLI_UTIL_H_
#define MESHWAVE_TOOLS_CLI_UTIL_H_

#include <google/protobuf/message.h>

#include <string>

#include "meshwave/status.h"

namespace meshwave::cli {

// Prints "meshwave <command>: <status>" on stderr and returns exit code 1.
int Fail(const std::string& command, const Status& status);

// Prints a protobuf message as indented JSON on stdout (field names as in
// the .proto, zero values included so the output has a fixed shape).
void PrintJson(const google::protobuf::Message& message);

}  // namespace meshwave::cli

#endif  // MESHWAVE_TOOLS_CLI_UTIL_H_
