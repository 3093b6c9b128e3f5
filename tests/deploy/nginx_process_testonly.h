// nginx from Debian's packages as the tests' load balancer and cache: a
// generated top-level config (temporary paths, a free 127.0.0.1 port, the
// given replica ports as upstream "meshwave_servers", a cache zone
// "meshwave") that includes deploy/nginx/meshwave-locations.conf, the
// behaviour compose ships. Runs as "nobody" when the test is root, and is
// stopped on destruction.
#ifndef MESHWAVE_TESTS_DEPLOY_NGINX_PROCESS_TESTONLY_H_
#define MESHWAVE_TESTS_DEPLOY_NGINX_PROCESS_TESTONLY_H_

#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "process/child_process_testonly.h"
#include "server/http_client_testonly.h"

namespace meshwave::testing {

inline std::filesystem::path NginxBinary() {
  for (const char* p : {"/usr/sbin/nginx", "/usr/bin/nginx"}) {
    if (std::filesystem::exists(p)) return p;
  }
  return {};
}

class NginxProcess {
 public:
  NginxProcess(const std::vector<uint16_t>& upstream_ports,
               const std::filesystem::path& locations_conf) {
    const auto bin = NginxBinary();
    if (bin.empty()) {
      error_ = "nginx not found (Debian: apt-get install nginx-light)";
      return;
    }
    std::string tmpl = (std::filesystem::temp_directory_path() / "meshwave_nginx_XXXXXX").string();
    if (::mkdtemp(tmpl.data()) == nullptr) {
      error_ = "cannot create a temporary directory";
      return;
    }
    dir_ = tmpl;
    // A copy beside the config: the repository may sit where "nobody"
    // cannot read. Byte for byte the shipped file.
    std::filesystem::copy_file(locations_conf, dir_ / "meshwave-locations.conf");
    std::filesystem::create_directories(dir_ / "tmp");
    std::filesystem::create_directories(dir_ / "cache");
    const auto account = UnprivilegedAccount();
    if (account) {
      for (const auto& p : std::filesystem::recursive_directory_iterator(dir_)) {
        if (::chown(p.path().c_str(), account->uid, account->gid) != 0) error_ = "chown failed";
      }
      if (::chown(dir_.c_str(), account->uid, account->gid) != 0) error_ = "chown failed";
      if (!error_.empty()) return;
    }
    for (int attempt = 0; attempt < 5 && port_ == 0; ++attempt) {
      const uint16_t port = FreeLoopbackPort();
      WriteConfig(port, upstream_ports);
      pid_ = SpawnChild({bin.string(), "-p", dir_.string() + "/", "-e",
                         (dir_ / "error.log").string(), "-c", (dir_ / "nginx.conf").string(),
                         "-g", "daemon off;"},
                        dir_ / "stdout.log", account);
      if (WaitReady(port)) port_ = port;
    }
    if (port_ == 0) error_ = "nginx did not start: " + Read("error.log") + Read("stdout.log");
  }

  ~NginxProcess() {
    // SIGTERM: fast shutdown of master and workers.
    if (pid_ > 0) StopChild(pid_, SIGTERM, std::chrono::seconds(10));
    std::error_code ec;
    if (!dir_.empty()) std::filesystem::remove_all(dir_, ec);
  }
  NginxProcess(const NginxProcess&) = delete;
  NginxProcess& operator=(const NginxProcess&) = delete;

  bool ok() const { return port_ != 0; }
  const std::string& error() const { return error_; }
  uint16_t port() const { return port_; }
  // One line per request: "METHOD URI STATUS cache=... upstream=...".
  std::string AccessLog() const { return Read("access.log"); }
  std::string ErrorLog() const { return Read("error.log"); }

 private:
  void WriteConfig(uint16_t port, const std::vector<uint16_t>& upstream_ports) {
    const std::string d = dir_.string();
    std::ofstream c(dir_ / "nginx.conf");
    c << "worker_processes 1;\n"
      << "pid " << d << "/nginx.pid;\n"
      << "error_log " << d << "/error.log info;\n"
      << "events { worker_connections 256; }\n"
      << "http {\n"
      << "  log_format t '$request_method $request_uri $status "
         "cache=$upstream_cache_status upstream=$upstream_addr';\n"
      << "  access_log " << d << "/access.log t;\n"
      << "  client_body_temp_path " << d << "/tmp/body;\n"
      << "  proxy_temp_path " << d << "/tmp/proxy;\n"
      << "  fastcgi_temp_path " << d << "/tmp/fastcgi;\n"
      << "  uwsgi_temp_path " << d << "/tmp/uwsgi;\n"
      << "  scgi_temp_path " << d << "/tmp/scgi;\n"
      << "  proxy_cache_path " << d << "/cache levels=1:2 keys_zone=meshwave:4m "
      << "max_size=256m inactive=1h use_temp_path=off;\n"
      << "  upstream meshwave_servers {\n";
    // Round robin starts with the first server: tests rely on that order.
    for (uint16_t p : upstream_ports) {
      c << "    server 127.0.0.1:" << p << " max_fails=1 fail_timeout=30s;\n";
    }
    c << "    keepalive 8;\n"
      << "  }\n"
      << "  server {\n"
      << "    listen 127.0.0.1:" << port << ";\n"
      << "    include " << d << "/meshwave-locations.conf;\n"
      << "  }\n"
      << "}\n";
  }

  bool WaitReady(uint16_t port) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(15);
    while (std::chrono::steady_clock::now() < end) {
      HttpConnection probe(port);
      if (probe.connected()) return true;
      if (!ProcessRuns(pid_)) {  // exited: port taken?
        WaitChild(pid_, std::chrono::seconds(1));
        pid_ = -1;
        return false;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    StopChild(pid_, SIGKILL, std::chrono::seconds(5));
    pid_ = -1;
    return false;
  }

  std::string Read(const std::string& name) const {
    std::ifstream in(dir_ / name);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }

  std::filesystem::path dir_;
  pid_t pid_ = -1;
  uint16_t port_ = 0;
  std::string error_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_DEPLOY_NGINX_PROCESS_TESTONLY_H_
