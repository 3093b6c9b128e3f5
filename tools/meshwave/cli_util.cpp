#include "cli_util.h"

#include <google/protobuf/util/json_util.h>

#include <iostream>

namespace meshwave::cli {

int Fail(const std::string& command, const Status& status) {
  std::cerr << "meshwave " << command << ": " << status.ToString() << "\n";
  return 1;
}

void PrintJson(const google::protobuf::Message& message) {
  google::protobuf::util::JsonPrintOptions options;
  options.add_whitespace = true;
  options.always_print_primitive_fields = true;
  options.preserve_proto_field_names = true;
  std::string out;
  auto status = google::protobuf::util::MessageToJsonString(message, &out, options);
  if (!status.ok()) {
    std::cerr << "meshwave: cannot print JSON: " << status.ToString() << "\n";
    return;
  }
  std::cout << out;
}

}  // namespace meshwave::cli
