// stiction's pictures from Python (python/stiction/_pictures.py is the public face): frames
// as NumPy arrays, the video and the figures written as `stiction run` writes them. A Python
// run keeps every row; the pictures are drawn from the rows the command line would have kept
// (services/run_outputs.hpp), so that they are the command line's to the byte.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bindings.hpp"
#include "image/image.hpp"
#include "plot/figure.hpp"
#include "render/gl.hpp"
#include "render/render_outputs.hpp"
#include "render/time_warp.hpp"
#include "render/video_encoder.hpp"
#include "run_handle.hpp"
#include "services/plot_outputs.hpp"
#include "services/render_loader.hpp"
#include "services/run_outputs.hpp"
#include "sys/interrupt.hpp"
#include "text/font.hpp"

namespace stiction::python {

namespace {

[[noreturn]] void raise(const char* error, const std::string& message) {
  py::object e = error_class(error)(message);
  PyErr_SetObject(e.get_type().ptr(), e.ptr());
  throw py::error_already_set();
}

// Runs `draw` with the GIL released; the renderer's and the figures' errors become the
// package's (a bad [render] table stays a SceneError, through bind_errors).
template <typename Draw>
auto drawing(const char* what, Draw&& draw) {
  std::string failure;
  const char* error = "Error";
  try {
    py::gil_scoped_release release;
    return draw();
  } catch (const render::GlError& e) {
    failure = std::string("OpenGL (OSMesa): ") + e.what();
  } catch (const render::VideoError& e) {
    failure = std::string("video: ") + e.what();
    error = "OutputError";
  } catch (const render::RenderError& e) {
    failure = std::string("render: ") + e.what();
  } catch (const image::ImageError& e) {
    failure = std::string(what) + ": " + e.what();
    error = "OutputError";
  } catch (const text::FontError& e) {
    failure = std::string("font: ") + e.what();
  }
  raise(error, failure);
}

// The pictures of one run. The thinned rows are made on first use and kept (a few thousand
// rows at most for the plots; a few per frame for the video).
class Pictures {
 public:
  explicit Pictures(std::shared_ptr<RunHandle> run) : run_(std::move(run)) {
    if (!run_->prepared)
      throw std::invalid_argument("a run that was not simulated has no pictures");
  }

  const render::RenderSettings& settings() const { return run_->prepared->render_settings; }

  const core::Trajectory& video_rows() {
    if (!video_rows_) {
      video_rows_ =
          services::video_rows(run_->result.trajectory, run_->prepared->scene.run, settings());
    }
    return *video_rows_;
  }

  const std::vector<render::FrameTime>& frame_times() {
    if (!frame_times_) {
      frame_times_ = services::video_frame_times(video_rows(), settings(),
                                                 services::slip_event_times(run_->result),
                                                 services::slip_event_kinds(run_->result));
    }
    return *frame_times_;
  }

  // The video's times as an array.
  py::array_t<double> times() {
    const std::vector<render::FrameTime>& f = frame_times();
    py::array_t<double> out(static_cast<py::ssize_t>(f.size()));
    for (std::size_t i = 0; i < f.size(); ++i) out.mutable_at(static_cast<py::ssize_t>(i)) = f[i].t;
    return out;
  }

  // (N, H, W, 4) RGBA frames at `times`, width x height pixels when given.
  py::array_t<std::uint8_t> frames(const std::vector<double>& times, std::optional<int> width,
                                   std::optional<int> height) {
    render::RenderSettings s = settings();
    if (width) s.width = *width;
    if (height) s.height = *height;
    if (s.width <= 0 || s.height <= 0 || s.width > 16384 || s.height > 16384)
      throw py::value_error("size: width and height must be 1 to 16384 pixels");
    const std::vector<render::FrameTime> at = with_speeds(times);
    const core::Trajectory& rows = video_rows();
    const std::vector<image::Image> images = drawing("frames", [&] {
      return services::render_frames_at(run_->prepared->scene, rows, s, at,
                                        services::slip_event_times(run_->result),
                                        services::slip_event_kinds(run_->result));
    });
    py::array_t<std::uint8_t> out({static_cast<py::ssize_t>(images.size()),
                                   static_cast<py::ssize_t>(s.height),
                                   static_cast<py::ssize_t>(s.width), py::ssize_t{4}});
    std::uint8_t* data = out.mutable_data();
    for (const image::Image& image : images) {
      data = std::copy(image.pixels.begin(), image.pixels.end(), data);
    }
    return out;
  }

  // OUT/video.mp4 (and OUT/frames/) as `stiction run` writes them. Ctrl-C stops the render,
  // keeps OUT/video.partial.mp4 and says so in "interrupted".
  py::dict write_video(const std::filesystem::path& out_dir, bool video, bool frames,
                       bool progress) {
    render::check_frame_count(run_->prepared->scene, settings());
    const core::Trajectory& rows = video_rows();
    services::VideoRequest request;
    request.out_dir = out_dir;
    request.video = video;
    request.frames = frames;
    request.progress = progress;
    request.cancel = &sys::interrupt_flag();
    std::optional<sys::ScopedInterrupt> interrupt;
    if (on_main_thread()) interrupt.emplace();
    const render::RenderResult rendered = drawing("frames", [&] {
      return services::write_run_video(run_->prepared->scene, run_->result, rows, settings(),
                                       request);
    });
    interrupt.reset();
    py::dict d;
    d["frames"] = rendered.frames;
    d["video"] = rendered.video.empty() ? py::object(py::none()) : py::cast(rendered.video);
    d["interrupted"] = rendered.interrupted;
    d["wall_seconds"] = rendered.wall_seconds;
    return d;
  }

  // The scene's figures into `dir`, as `stiction run` writes plots/. Returns the files written
  // and whether Ctrl-C stopped it between two figures.
  std::pair<std::vector<std::filesystem::path>, bool> write_plots(
      const std::filesystem::path& dir, std::optional<std::string> format) {
    std::optional<plot::Format> chosen;
    if (format) {
      chosen = plot::parse_format(*format);
      if (!chosen) throw py::value_error("format: '" + *format + "' is not png, svg or pdf");
    }
    if (!plot_rows_) plot_rows_ = services::plot_rows(run_->result.trajectory);
    std::optional<sys::ScopedInterrupt> interrupt;
    if (on_main_thread()) interrupt.emplace();
    std::vector<std::filesystem::path> written = drawing("plots", [&] {
      std::filesystem::create_directories(dir);
      return services::write_run_plots(run_->prepared->plot_specs, run_->result, *plot_rows_, dir,
                                       chosen);
    });
    const bool interrupted = sys::interrupted();
    interrupt.reset();
    return {std::move(written), interrupted};
  }

 private:
  // Each time with the speed the video plays it at: the video's own for one of its frame
  // times (exactly), the time-warp's at that time otherwise.
  std::vector<render::FrameTime> with_speeds(const std::vector<double>& times) {
    const std::vector<render::FrameTime>& video = frame_times();
    const std::vector<double> events = services::slip_event_times(run_->result);
    std::vector<render::FrameTime> out;
    for (double t : times) {
      const auto same = std::find_if(video.begin(), video.end(),
                                     [t](const render::FrameTime& f) { return f.t == t; });
      out.push_back({t, same != video.end() ? same->speed
                                            : render::playback_speed(
                                                  t, events, settings().slow_motion_around_events,
                                                  settings().event_slow_motion)});
    }
    return out;
  }

  std::shared_ptr<RunHandle> run_;
  std::optional<core::Trajectory> video_rows_;
  std::optional<core::Trajectory> plot_rows_;
  std::optional<std::vector<render::FrameTime>> frame_times_;
};

}  // namespace

void bind_pictures(py::module_& m) {
  py::class_<Pictures>(m, "_Pictures")
      .def(py::init<std::shared_ptr<RunHandle>>(), py::arg("run"))
      .def_property_readonly("size",
                             [](const Pictures& p) {
                               return std::pair{p.settings().width, p.settings().height};
                             })
      .def_property_readonly("fps", [](const Pictures& p) { return p.settings().fps; })
      .def("frame_times", &Pictures::times)
      .def("frames", &Pictures::frames, py::arg("times"), py::arg("width") = py::none(),
           py::arg("height") = py::none())
      .def("write_video", &Pictures::write_video, py::arg("dir"), py::arg("video") = true,
           py::arg("frames") = false, py::arg("progress") = false)
      .def("write_plots", &Pictures::write_plots, py::arg("dir"), py::arg("format") = py::none());
}

}  // namespace stiction::python
