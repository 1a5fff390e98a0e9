#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace recon::robot {

/// A connected TCP socket (POSIX, blocking writes, Nagle off) that closes itself. Robots answer
/// on plain TCP; this is the one place that knows about file descriptors and errno.
class TcpSocket {
 public:
  TcpSocket() = default;
  /// Takes ownership of an already connected descriptor (e.g. from TcpListener::Accept).
  TcpSocket(int fd, std::string peer);
  ~TcpSocket();
  TcpSocket(TcpSocket&& other) noexcept;
  TcpSocket& operator=(TcpSocket&& other) noexcept;
  TcpSocket(const TcpSocket&) = delete;
  TcpSocket& operator=(const TcpSocket&) = delete;

  /// Connects to host:port within `timeout_s`. UserError naming host:port when the name does not
  /// resolve, the connection is refused, or nothing answers in time.
  static TcpSocket Connect(const std::string& host, int port, double timeout_s);

  /// Writes all of `size` bytes; false (with last_error()) when the peer is gone. Never raises
  /// SIGPIPE.
  bool SendAll(const void* data, size_t size);
  bool SendAll(const std::string& bytes) { return SendAll(bytes.data(), bytes.size()); }
  /// Waits up to `timeout_ms` for bytes and appends what arrived to `out` (possibly nothing).
  /// False once the peer has closed the connection or an error occurred (see last_error()).
  bool Receive(std::string& out, int timeout_ms);
  /// Shuts the connection down both ways (wakes a thread blocked in Receive) without closing
  /// the descriptor; Close() releases it.
  void Shutdown();
  void Close();

  bool open() const { return fd_ >= 0; }
  /// "host:port" of the other side, for messages.
  const std::string& peer() const { return peer_; }
  const std::string& last_error() const { return last_error_; }

 private:
  int fd_ = -1;
  std::string peer_;
  std::string last_error_;
};

/// A listening TCP socket on the loopback interface, for fakes in tests. Port 0 picks a free
/// (ephemeral) port; port() tells which.
class TcpListener {
 public:
  /// UserError naming the port when it cannot be bound (e.g. already in use).
  explicit TcpListener(int port);
  ~TcpListener();
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;

  /// Waits up to `timeout_ms` for a client; an unopened socket if none came.
  TcpSocket Accept(int timeout_ms);
  int port() const { return port_; }
  void Close();

 private:
  int fd_ = -1;
  int port_ = 0;
};

}  // namespace recon::robot
