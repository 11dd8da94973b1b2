// Which files a fuzz input makes the program open (fuzz/open_watch.hpp): this file defines
// open, open64, openat, openat64, fopen, fopen64 and glibc's fortified __open_2 and
// __open64_2 in the fuzz executable, where they take precedence over the C library's (for
// the executable's own code and the shared libraries alike: urdfdom, tinyxml, libstdc++'s
// file streams), note the path while a watch is on, and call the C library's through
// dlsym(RTLD_NEXT). No C library header that declares them is included here, so that these
// definitions need not match its attributes.
#include "fuzz/open_watch.hpp"

#include <dlfcn.h>

#include <cstdarg>

namespace {

constexpr int kCreate = 0100;        // O_CREAT on Linux
constexpr int kTmpFile = 020000000;  // __O_TMPFILE on Linux

template <typename F>
F real(const char* name) {
  return reinterpret_cast<F>(dlsym(RTLD_NEXT, name));
}

unsigned mode_of(int flags, va_list args) {
  return (flags & (kCreate | kTmpFile)) != 0 ? va_arg(args, unsigned) : 0u;
}

}  // namespace

struct _IO_FILE;

extern "C" {

int open(const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const unsigned mode = mode_of(flags, args);
  va_end(args);
  stiction::fuzz::note_open(path);
  static const auto f = real<int (*)(const char*, int, ...)>("open");
  return f(path, flags, mode);
}

int open64(const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const unsigned mode = mode_of(flags, args);
  va_end(args);
  stiction::fuzz::note_open(path);
  static const auto f = real<int (*)(const char*, int, ...)>("open64");
  return f(path, flags, mode);
}

int openat(int dir, const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const unsigned mode = mode_of(flags, args);
  va_end(args);
  stiction::fuzz::note_open(path, dir);
  static const auto f = real<int (*)(int, const char*, int, ...)>("openat");
  return f(dir, path, flags, mode);
}

int openat64(int dir, const char* path, int flags, ...) {
  va_list args;
  va_start(args, flags);
  const unsigned mode = mode_of(flags, args);
  va_end(args);
  stiction::fuzz::note_open(path, dir);
  static const auto f = real<int (*)(int, const char*, int, ...)>("openat64");
  return f(dir, path, flags, mode);
}

int __open_2(const char* path, int flags) {
  stiction::fuzz::note_open(path);
  static const auto f = real<int (*)(const char*, int)>("__open_2");
  return f(path, flags);
}

int __open64_2(const char* path, int flags) {
  stiction::fuzz::note_open(path);
  static const auto f = real<int (*)(const char*, int)>("__open64_2");
  return f(path, flags);
}

_IO_FILE* fopen(const char* path, const char* mode) {
  stiction::fuzz::note_open(path);
  static const auto f = real<_IO_FILE* (*)(const char*, const char*)>("fopen");
  return f(path, mode);
}

_IO_FILE* fopen64(const char* path, const char* mode) {
  stiction::fuzz::note_open(path);
  static const auto f = real<_IO_FILE* (*)(const char*, const char*)>("fopen64");
  return f(path, mode);
}

}  // extern "C"
