#include "http_head.h"

#include <charconv>

namespace meshwave::server {

void AppendStatusLine(std::string& out, unsigned version, unsigned status) {
  out += version >= 11 ? "HTTP/1.1 " : "HTTP/1.0 ";
  char digits[16];
  const auto end = std::to_chars(digits, digits + sizeof digits, status).ptr;
  out.append(digits, end);
  out += ' ';
  const auto reason = http::obsolete_reason(static_cast<http::status>(status));
  out.append(reason.data(), reason.size());
  out += "\r\n";
}

bool SendsContentLength(unsigned status, bool head) {
  if (head) return true;
  return !(status / 100 == 1 || status == 204 || status == 304);
}

void AppendFields(std::string& out, const Response& response, uint64_t body_bytes, bool head) {
  for (const auto& field : response) {
    const auto name = field.name();
    if (name == http::field::server || name == http::field::content_length ||
        name == http::field::connection) {
      continue;
    }
    const auto n = field.name_string();
    const auto v = field.value();
    out.append(n.data(), n.size());
    out += ": ";
    out.append(v.data(), v.size());
    out += "\r\n";
  }
  out += "Server: meshwave\r\n";
  if (SendsContentLength(response.result_int(), head)) {
    out += "Content-Length: ";
    char digits[24];
    const auto end = std::to_chars(digits, digits + sizeof digits, body_bytes).ptr;
    out.append(digits, end);
    out += "\r\n";
  }
}

std::string_view ConnectionField(unsigned version, bool keep_alive) {
  if (version >= 11) return keep_alive ? "" : "Connection: close\r\n";
  return keep_alive ? "Connection: keep-alive\r\n" : "";
}

}  // namespace meshwave::server
