#include "devices/uwb/serial_port.h"

#include <fcntl.h>
#include <poll.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "engine/core/error.h"

namespace recon::uwb {

namespace {

speed_t BaudConstant(int baud) {
  switch (baud) {
    case 9600:
      return B9600;
    case 19200:
      return B19200;
    case 38400:
      return B38400;
    case 57600:
      return B57600;
    case 115200:
      return B115200;
    case 230400:
      return B230400;
  }
  throw UserError("unsupported baud rate " + std::to_string(baud) +
                  " (9600, 19200, 38400, 57600, 115200, 230400)");
}

}  // namespace

SerialPort::SerialPort(const std::string& path, int baud) : path_(path) {
  const speed_t speed = BaudConstant(baud);
  fd_ = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    std::string hint;
    if (error == EACCES) hint = " (add yourself to the dialout group, then log in again)";
    if (error == ENOENT) hint = " (is the beacon plugged in? `recon devices list` shows ports)";
    throw UserError("cannot open the serial port " + path + ": " + std::strerror(error) + hint);
  }
  termios tty{};
  if (::tcgetattr(fd_, &tty) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw UserError(path + " is not a serial port: " + std::strerror(error));
  }
  ::cfmakeraw(&tty);  // no echo, no line editing, no CR/LF translation: bytes as they are
  tty.c_cflag &= ~(PARENB | CSTOPB | CSIZE | CRTSCTS);
  tty.c_cflag |= CS8 | CLOCAL | CREAD;  // 8N1, ignore modem lines
  ::cfsetispeed(&tty, speed);
  ::cfsetospeed(&tty, speed);
  if (::tcsetattr(fd_, TCSANOW, &tty) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    throw UserError("cannot configure the serial port " + path + ": " + std::strerror(error));
  }
}

SerialPort::~SerialPort() {
  if (fd_ >= 0) ::close(fd_);
}

void SerialPort::Fail(const std::string& why) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  last_error_ = why;
}

bool SerialPort::Read(std::string& out, int timeout_ms) {
  if (fd_ < 0) return false;
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, timeout_ms);
  if (ready < 0) {
    if (errno == EINTR) return true;
    Fail("polling " + path_ + " failed: " + std::strerror(errno));
    return false;
  }
  if (ready == 0) return true;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(fd_, buffer, sizeof(buffer));
    if (n > 0) {
      out.append(buffer, static_cast<size_t>(n));
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) break;
    // 0 bytes after poll said readable, or EIO: the other side hung up (unplugged, or a
    // pseudo-terminal's master closed).
    Fail(path_ + " hung up" + (n < 0 ? std::string(": ") + std::strerror(errno) : ""));
    return false;
  }
  if (p.revents & (POLLHUP | POLLERR)) {
    Fail(path_ + " hung up");
    return false;
  }
  return true;
}

bool SerialPort::Write(std::string_view bytes) {
  while (!bytes.empty()) {
    if (fd_ < 0) return false;
    const ssize_t n = ::write(fd_, bytes.data(), bytes.size());
    if (n > 0) {
      bytes.remove_prefix(static_cast<size_t>(n));
    } else if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      pollfd p{fd_, POLLOUT, 0};
      ::poll(&p, 1, 100);
    } else {
      Fail("writing to " + path_ + " failed: " + std::strerror(errno));
      return false;
    }
  }
  return true;
}

}  // namespace recon::uwb
