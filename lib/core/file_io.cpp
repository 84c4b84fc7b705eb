#include "core/file_io.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>

#include "core/diagnostics.h"

namespace sdg {

namespace {
// Appends gather in a buffer up to kWriteBuffer; a piece of kDirectWrite or
// more arriving at an empty buffer is written as it is, uncopied.
constexpr size_t kWriteBuffer = size_t(1) << 20;
constexpr size_t kDirectWrite = size_t(1) << 16;
}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path)
    : path_(std::move(path)), temporary_(path_ + ".tmp-" + std::to_string(::getpid())) {
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd_ < 0) throw RunError("cannot write " + path_ + ": " + std::strerror(errno));
}

AtomicFileWriter::~AtomicFileWriter() {
  if (fd_ < 0) return;
  ::close(fd_);
  ::unlink(temporary_.c_str());
}

void AtomicFileWriter::fail(int error) {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temporary_.c_str());
  throw RunError("cannot write " + path_ + ": " + std::strerror(error));
}

void AtomicFileWriter::writeAll(const char* data, size_t size) {
  size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      fail(errno);
    }
    done += static_cast<size_t>(n);
  }
}

void AtomicFileWriter::append(std::string_view text) {
  if (fd_ < 0) throw RunError("cannot write " + path_ + ": written after it was committed");
  if (buffer_.empty() && text.size() >= kDirectWrite) {
    writeAll(text.data(), text.size());
    return;
  }
  buffer_.append(text);
  if (buffer_.size() >= kWriteBuffer) {
    writeAll(buffer_.data(), buffer_.size());
    buffer_.clear();
  }
}

void AtomicFileWriter::append(std::span<const uint8_t> bytes) {
  append(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

void AtomicFileWriter::commit(Durability durability) {
  if (fd_ < 0) throw RunError("cannot write " + path_ + ": committed twice");
  writeAll(buffer_.data(), buffer_.size());
  buffer_.clear();
  if (durability == Durability::Synced && ::fdatasync(fd_) != 0) fail(errno);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    throw RunError("cannot write " + path_ + ": " + std::strerror(error));
  }
  if (std::rename(temporary_.c_str(), path_.c_str()) != 0) {
    const int error = errno;
    ::unlink(temporary_.c_str());
    throw RunError("cannot write " + path_ + ": " + std::strerror(error));
  }
}

void writeFileAtomic(const std::string& path, std::span<const uint8_t> bytes, Durability durability) {
  AtomicFileWriter file(path);
  // Straight from the caller's bytes: frames' files are never copied.
  file.writeAll(reinterpret_cast<const char*>(bytes.data()), bytes.size());
  file.commit(durability);
}

void writeFileAtomic(const std::string& path, const std::string& text, Durability durability) {
  writeFileAtomic(path, std::span<const uint8_t>(reinterpret_cast<const uint8_t*>(text.data()), text.size()),
                  durability);
}

void syncDirectory(const std::string& dir) {
  int fd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) throw RunError("cannot open the folder " + dir + ": " + std::strerror(errno));
  int result = ::fsync(fd);
  int error = errno;
  ::close(fd);
  if (result != 0 && error != EINVAL) throw RunError("cannot sync the folder " + dir + ": " + std::strerror(error));
}

std::string fileHash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  uint64_t h = 0xCBF29CE484222325ULL;
  char block[65536];
  while (in.read(block, sizeof block) || in.gcount() > 0)
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= static_cast<unsigned char>(block[i]);
      h *= 0x100000001B3ULL;
    }
  char text[32];
  std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
  return text;
}

}  // namespace sdg
