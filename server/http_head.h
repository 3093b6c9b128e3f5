// The head of an HTTP/1.x response written by hand instead of by Beast's
// serializer, so that a session sends head and body in one gathered write
// and a cached head is reused as it is. The bytes are what Beast writes for
// the same message after HttpSession's finishing touches (Server, the
// payload's Content-Length, Connection).
#ifndef MESHWAVE_SERVER_HTTP_HEAD_H_
#define MESHWAVE_SERVER_HTTP_HEAD_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "slices_body.h"

namespace meshwave::server {

// Appends "HTTP/1.<minor> <status> <reason>\r\n" (version 10 or 11).
void AppendStatusLine(std::string& out, unsigned version, unsigned status);

// Whether a response with `status` carries Content-Length: not 1xx, 204 or
// 304 (RFC 9110 8.6; Beast's prepare_payload), except that a HEAD answer
// always states the length, as GET's would be.
bool SendsContentLength(unsigned status, bool head);

// Appends the fields of `response` ("Name: value\r\n" each, in order), then
// "Server: meshwave" and, when SendsContentLength, "Content-Length:
// <body_bytes>". Server, Content-Length and Connection fields that the
// handler set are left out: the session decides those.
void AppendFields(std::string& out, const Response& response, uint64_t body_bytes, bool head);

// The Connection field for `keep_alive` at `version` ("" where it is the
// version's default: keep-alive for 1.1, close for 1.0).
std::string_view ConnectionField(unsigned version, bool keep_alive);

}  // namespace meshwave::server

#endif  // MESHWAVE_SERVER_HTTP_HEAD_H_
