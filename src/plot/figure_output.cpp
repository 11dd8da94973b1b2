// Output surfaces of a figure: an image in memory (PNG), and SVG and PDF documents drawn by
// the same draw() into cairo's vector surfaces.
#include <cairo-pdf.h>
#include <cairo-svg.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <stdexcept>

#include "image/png.hpp"
#include "io/atomic_file.hpp"
#include "plot/figure.hpp"
#include "plot/figure_drawing.hpp"
#include "plot/svg_text.hpp"

namespace stiction::plot {

namespace {

image::Image to_image(cairo_surface_t* surface) {
  cairo_surface_flush(surface);
  const int w = cairo_image_surface_get_width(surface), h = cairo_image_surface_get_height(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  image::Image img(w, h);
  for (int y = 0; y < h; ++y) {
    const auto* row =
        reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride);
    for (int x = 0; x < w; ++x) {
      // Premultiplied ARGB in native byte order; the figure is opaque (white background).
      const std::uint32_t p = row[x];
      img.set(x, y,
              image::Rgba{static_cast<std::uint8_t>(p >> 16), static_cast<std::uint8_t>(p >> 8),
                          static_cast<std::uint8_t>(p), 255});
    }
  }
  return img;
}

struct SurfaceDeleter {
  void operator()(cairo_surface_t* s) const { cairo_surface_destroy(s); }
};
struct ContextDeleter {
  void operator()(cairo_t* c) const { cairo_destroy(c); }
};
using SurfacePtr = std::unique_ptr<cairo_surface_t, SurfaceDeleter>;
using ContextPtr = std::unique_ptr<cairo_t, ContextDeleter>;

cairo_status_t append_to_string(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::string*>(closure)->append(reinterpret_cast<const char*>(data), length);
  return CAIRO_STATUS_SUCCESS;
}

// Draws into a vector surface writing into `bytes`, scaled from pixels by `scale`; with
// `texts`, text is handed back there instead of drawn.
FigureLayout draw_vector(const Figure& figure, cairo_surface_t* surface, double scale,
                         std::vector<PlacedText>* texts = nullptr) {
  ContextPtr cr(cairo_create(surface));
  cairo_scale(cr.get(), scale, scale);
  FigureLayout layout = draw_figure(figure, cr.get(), texts);
  cr.reset();
  cairo_surface_finish(surface);
  if (cairo_surface_status(surface) != CAIRO_STATUS_SUCCESS) {
    throw io::IoError(std::string("cairo: ") +
                      cairo_status_to_string(cairo_surface_status(surface)));
  }
  return layout;
}

}  // namespace

image::Image render(const Figure& figure, FigureLayout* layout) {
  const PixelSize size = pixel_size(figure);
  if (size.width < 200 || size.height < 150 || size.width > 16384 || size.height > 16384) {
    throw std::invalid_argument("figure size must be between 200x150 and 16384x16384 pixels");
  }
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, size.width, size.height));
  ContextPtr cr(cairo_create(surface.get()));
  FigureLayout drawn = draw(figure, cr.get());
  cr.reset();
  if (layout) *layout = std::move(drawn);
  return to_image(surface.get());
}

image::Image render(const Figure& figure, text::Font& /*font*/) { return render(figure, nullptr); }

FigureLayout write_figure(const Figure& figure, const std::filesystem::path& path, Format format,
                          double dpi) {
  if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
  if (figure.print) dpi = figure.print->dpi;
  const PixelSize size = pixel_size(figure);
  if (format == Format::png) {
    FigureLayout layout;
    const image::Image img = render(figure, &layout);
    image::write_png(path, img, image::PngSpeed::small, dpi);
    return layout;
  }
  std::string bytes;
  FigureLayout layout;
  if (format == Format::svg) {
    // One user unit per pixel; the document says "px" so viewers show it at its pixel size.
    SurfacePtr surface(
        cairo_svg_surface_create_for_stream(append_to_string, &bytes, size.width, size.height));
    cairo_svg_surface_set_document_unit(surface.get(), CAIRO_SVG_UNIT_PX);
    std::vector<PlacedText> texts;
    layout = draw_vector(figure, surface.get(), 1.0, &texts);
    surface.reset();
    std::optional<PageSize> page;
    if (figure.print) page = PageSize{figure.print->width_mm, figure.print->height_mm};
    bytes = add_svg_text(bytes, texts, page);
  } else {
    // The page is the figure's size at `dpi`: 1600 px at 100 dpi is 16 in (1152 pt) wide. A
    // print figure's page is its size in mm exactly; its pixels (rounded from the page) are
    // scaled by one factor so the drawing fills the page within a fraction of a point.
    double scale = 72.0 / (dpi > 0.0 ? dpi : 100.0);
    double page_width = size.width * scale, page_height = size.height * scale;
    if (figure.print) {
      page_width = figure.print->width_mm / 25.4 * 72.0;
      page_height = figure.print->height_mm / 25.4 * 72.0;
      scale = std::min(page_width / size.width, page_height / size.height);
    }
    SurfacePtr surface(
        cairo_pdf_surface_create_for_stream(append_to_string, &bytes, page_width, page_height));
    // Reproducible files: the creation date comes from SOURCE_DATE_EPOCH when it is set.
    if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
      const std::time_t t = static_cast<std::time_t>(std::strtoll(epoch, nullptr, 10));
      char date[32];
      std::strftime(date, sizeof date, "%Y-%m-%dT%H:%M:%S", std::gmtime(&t));
      cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATE_DATE, date);
    }
    cairo_pdf_surface_set_metadata(surface.get(), CAIRO_PDF_METADATA_CREATOR, "stiction");
    layout = draw_vector(figure, surface.get(), scale);
  }
  io::write_file_atomically(path, bytes);
  return layout;
}

}  // namespace stiction::plot
