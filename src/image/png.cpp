#include "image/png.hpp"

#include <png.h>
#include <unistd.h>
#include <zlib.h>

#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <system_error>
#include <thread>

#include "sys/temporaries.hpp"

namespace stiction::image {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

struct ErrorSink {
  char message[256] = {};
};

void on_png_error(png_structp png, png_const_charp message) {
  auto* sink = static_cast<ErrorSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message);
  png_longjmp(png, 1);
}

void on_png_warning(png_structp, png_const_charp) {}

// Only trivially destructible locals live in this frame: libpng may longjmp out of it.
bool encode(std::FILE* file, const Image& image, PngSpeed speed, double dpi, ErrorSink& sink) {
  png_structp png =
      png_create_write_struct(PNG_LIBPNG_VER_STRING, &sink, on_png_error, on_png_warning);
  if (!png) {
    std::snprintf(sink.message, sizeof sink.message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_init_io(png, file);
  if (speed == PngSpeed::fast) {
    png_set_compression_level(png, 1);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  } else {
    png_set_compression_level(png, 6);
  }
  png_set_IHDR(png, info, static_cast<png_uint_32>(image.width),
               static_cast<png_uint_32>(image.height), 8, PNG_COLOR_TYPE_RGB_ALPHA,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  if (dpi > 0.0) {
    const auto per_metre = static_cast<png_uint_32>(dpi / 0.0254 + 0.5);
    png_set_pHYs(png, info, per_metre, per_metre, PNG_RESOLUTION_METER);
  }
  png_write_info(png, info);
  for (int y = 0; y < image.height; ++y) {
    png_write_row(png, image.data(0, y));
  }
  png_write_end(png, nullptr);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

void write_png(const std::filesystem::path& path, const Image& image, PngSpeed speed,
               double dpi) {
  if (image.empty()) throw ImageError("cannot write an empty image to " + path.string());
  sys::Temporary created;
  try {
    created = sys::create_temporary(path);
  } catch (const std::system_error& e) {
    throw ImageError("cannot write " + path.string() + ": " + e.code().message());
  }
  const std::filesystem::path temp = created.path;
  ErrorSink sink;
  bool ok = false;
  {
    File file(::fdopen(created.fd, "wb"));
    if (!file) {
      const std::string why = std::strerror(errno);
      ::close(created.fd);
      ::unlink(temp.c_str());
      sys::forget_temporary(temp);
      throw ImageError("cannot write " + path.string() + ": " + why);
    }
    ok = encode(file.get(), image, speed, dpi, sink);
    if (ok && (std::fflush(file.get()) != 0 || std::ferror(file.get()))) {
      std::snprintf(sink.message, sizeof sink.message, "%s", std::strerror(errno));
      ok = false;
    }
  }
  std::error_code ec;
  if (ok) {
    std::filesystem::rename(temp, path, ec);
    sys::forget_temporary(temp);
    if (!ec) return;
    std::snprintf(sink.message, sizeof sink.message, "%s", ec.message().c_str());
  }
  std::filesystem::remove(temp, ec);
  sys::forget_temporary(temp);
  throw ImageError("cannot write " + path.string() + ": " + sink.message);
}

Image read_png(const std::filesystem::path& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    throw ImageError("cannot read " + path.string() + ": " + png.message);
  }
  png.format = PNG_FORMAT_RGBA;
  Image image(static_cast<int>(png.width), static_cast<int>(png.height));
  if (!png_image_finish_read(&png, nullptr, image.pixels.data(), 0, nullptr)) {
    std::string message = png.message;
    png_image_free(&png);
    throw ImageError("cannot read " + path.string() + ": " + message);
  }
  return image;
}

}  // namespace stiction::image
