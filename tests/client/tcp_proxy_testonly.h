// A loopback TCP proxy for the client's end-to-end tests: forwards to a
// server port and, on the bytes going back to the client, can cut the
// connection, stall it, or flip one byte. Records what it sent back, per
// connection. Plain POSIX sockets and one thread per direction.
#ifndef MESHWAVE_TESTS_CLIENT_TCP_PROXY_TESTONLY_H_
#define MESHWAVE_TESTS_CLIENT_TCP_PROXY_TESTONLY_H_

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace meshwave::testing {

class TcpProxy {
 public:
  explicit TcpProxy(uint16_t upstream) : upstream_(upstream) {
    listen_fd_ = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = 0;
    ::bind(listen_fd_, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(listen_fd_, 16);
    socklen_t len = sizeof a;
    ::getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    accept_thread_ = std::thread([this] { AcceptLoop(); });
  }
  ~TcpProxy() {
    {
      std::lock_guard<std::mutex> lock(mu_);
      stopping_ = true;
      for (int fd : fds_) ::shutdown(fd, SHUT_RDWR);
    }
    cv_.notify_all();
    ::shutdown(listen_fd_, SHUT_RDWR);
    accept_thread_.join();
    for (auto& t : threads_) t.join();
    for (int fd : fds_) ::close(fd);
    ::close(listen_fd_);
  }
  TcpProxy(const TcpProxy&) = delete;
  TcpProxy& operator=(const TcpProxy&) = delete;

  uint16_t port() const { return port_; }
  void set_upstream(uint16_t port) { upstream_ = port; }

  // The next `connections` connections are closed after `bytes` sent back.
  void CutAfter(size_t bytes, int connections) {
    std::lock_guard<std::mutex> lock(mu_);
    cut_after_ = bytes;
    cuts_ = connections;
  }
  // The next connection stops forwarding after `bytes` sent back, until
  // DropStalled closes it.
  void StallAfter(size_t bytes) {
    std::lock_guard<std::mutex> lock(mu_);
    stall_after_ = bytes;
    stalls_ = 1;
  }
  bool WaitStalled(std::chrono::milliseconds timeout) {
    std::unique_lock<std::mutex> lock(mu_);
    return cv_.wait_for(lock, timeout, [this] { return stalled_ > 0; });
  }
  void DropStalled() {
    std::lock_guard<std::mutex> lock(mu_);
    drop_stalled_ = true;
    cv_.notify_all();
  }
  // Flips one byte at this offset of what every later connection sends back.
  void CorruptAt(int64_t offset) { corrupt_at_ = offset; }

  int connections() const { return connections_.load(); }
  // What was sent back on each connection, in the order they were opened.
  std::vector<std::string> Transcripts() {
    std::lock_guard<std::mutex> lock(mu_);
    return transcripts_;
  }
  // Everything sent back to clients, all connections in order.
  std::string Transcript() {
    std::lock_guard<std::mutex> lock(mu_);
    std::string all;
    for (const auto& t : transcripts_) all += t;
    return all;
  }

 private:
  struct Faults {
    size_t cut_after = SIZE_MAX;
    size_t stall_after = SIZE_MAX;
    int64_t corrupt_at = -1;
  };

  static bool SendAll(int fd, const char* p, size_t n) {
    while (n > 0) {
      const ssize_t w = ::send(fd, p, n, MSG_NOSIGNAL);
      if (w <= 0) return false;
      p += w;
      n -= static_cast<size_t>(w);
    }
    return true;
  }

  void AcceptLoop() {
    for (;;) {
      const int client = ::accept(listen_fd_, nullptr, nullptr);
      if (client < 0) return;
      const int up = ::socket(AF_INET, SOCK_STREAM, 0);
      sockaddr_in a{};
      a.sin_family = AF_INET;
      a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
      a.sin_port = htons(upstream_.load());
      Faults f;
      size_t index = 0;
      {
        std::lock_guard<std::mutex> lock(mu_);
        if (stopping_) {
          ::close(client);
          ::close(up);
          return;
        }
        fds_.push_back(client);
        fds_.push_back(up);
        if (cuts_ > 0) {
          --cuts_;
          f.cut_after = cut_after_;
        }
        if (stalls_ > 0) {
          --stalls_;
          f.stall_after = stall_after_;
        }
        f.corrupt_at = corrupt_at_.load();
        index = transcripts_.size();
        transcripts_.emplace_back();
        ++connections_;
      }
      if (::connect(up, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
        ::shutdown(client, SHUT_RDWR);  // as if the server were down
        continue;
      }
      std::lock_guard<std::mutex> lock(mu_);
      threads_.emplace_back([client, up] {
        char buf[16384];
        ssize_t n;
        while ((n = ::recv(client, buf, sizeof buf, 0)) > 0) {
          if (!SendAll(up, buf, static_cast<size_t>(n))) break;
        }
        ::shutdown(up, SHUT_WR);
      });
      threads_.emplace_back(
          [this, client, up, f, index] { PumpBack(client, up, f, index); });
    }
  }

  void PumpBack(int client, int up, Faults f, size_t index) {
    char buf[16384];
    size_t sent = 0;
    ssize_t n;
    while ((n = ::recv(up, buf, sizeof buf, 0)) > 0) {
      size_t len = static_cast<size_t>(n);
      if (f.corrupt_at >= 0 && static_cast<size_t>(f.corrupt_at) >= sent &&
          static_cast<size_t>(f.corrupt_at) < sent + len) {
        buf[static_cast<size_t>(f.corrupt_at) - sent] ^= 0x20;
      }
      const size_t limit = std::min(f.cut_after, f.stall_after);
      const size_t allowed = sent + len > limit ? limit - sent : len;
      {
        std::lock_guard<std::mutex> lock(mu_);
        transcripts_[index].append(buf, allowed);
      }
      if (!SendAll(client, buf, allowed)) break;
      sent += allowed;
      if (allowed < len || sent == limit) {
        if (sent == f.stall_after) {
          std::unique_lock<std::mutex> lock(mu_);
          ++stalled_;
          cv_.notify_all();
          cv_.wait(lock, [this] { return drop_stalled_ || stopping_; });
        }
        break;
      }
    }
    ::shutdown(client, SHUT_RDWR);
    ::shutdown(up, SHUT_RDWR);
  }

  int listen_fd_ = -1;
  uint16_t port_ = 0;
  std::atomic<uint16_t> upstream_;
  std::atomic<int64_t> corrupt_at_{-1};
  std::atomic<int> connections_{0};
  std::mutex mu_;
  std::condition_variable cv_;
  bool stopping_ = false;
  size_t cut_after_ = SIZE_MAX;
  int cuts_ = 0;
  size_t stall_after_ = SIZE_MAX;
  int stalls_ = 0;
  int stalled_ = 0;
  bool drop_stalled_ = false;
  std::vector<int> fds_;
  std::vector<std::string> transcripts_;
  std::vector<std::thread> threads_;
  std::thread accept_thread_;
};

}  // namespace meshwave::testing

#endif  // MESHWAVE_TESTS_CLIENT_TCP_PROXY_TESTONLY_H_
