#include "drivers/camera/camera_source.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>

#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "common/logging.hpp"

namespace fsd {

namespace {
constexpr int kFailuresBeforeReconnect = 3;

// The frame as 8-bit BGR, or empty for pixel formats a camera should not deliver through VideoCapture.
cv::Mat to_bgr(const cv::Mat& image) {
  cv::Mat bgr;
  switch (image.type()) {
    case CV_8UC3:
      return image;
    case CV_8UC1:
      cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
      return bgr;
    case CV_8UC4:
      cv::cvtColor(image, bgr, cv::COLOR_BGRA2BGR);
      return bgr;
    default:
      return bgr;
  }
}
}  // namespace

const ConfigSection<CameraDriverConfig>& camera_driver_section() {
  using C = CameraDriverConfig;
  static const auto s =
      ConfigSection<C>("drivers.camera")
          .boolean("enabled", &C::enabled, "fsd run on the car reads frames from this camera (no camera when false).")
          .string("source", &C::source, {},
                  "V4L2 device (/dev/video0 or an index), GStreamer pipeline (contains '!'), or video file.")
          .integer("width", &C::width, 16, 8192, "px", "Image width requested from the device and expected.")
          .integer("height", &C::height, 16, 8192, "px", "Image height requested from the device and expected.")
          .number("fps", &C::fps, 1.0, 240.0, "Hz", "Frame rate requested from the device; playback rate of files.")
          .string("fourcc", &C::fourcc, {"", "MJPG", "YUYV"},
                  "Pixel format requested from a V4L2 device; empty = default.")
          .string("calibration", &C::calibration, {},
                  "Camera calibration file (intrinsics, extrinsics, ground homography; docs/camera.md); empty = none.")
          .number("latency", &C::latency, 0.0, 1.0, "s", "Exposure-to-read delay subtracted from each frame's stamp.")
          .number("reconnect_delay", &C::reconnect_delay, 0.01, 60.0, "s",
                  "Wait between attempts to reopen a failed source.")
          .boolean("loop_file", &C::loop_file, "Start a video file over at its end instead of ending the stream.")
          .boolean("pace_file", &C::pace_file, "Play a video file at fps instead of as fast as it decodes.");
  return s;
}

CameraSourceKind classify_camera_source(const std::string& source) {
  if (source.find('!') != std::string::npos) return CameraSourceKind::Pipeline;
  if (source.rfind("/dev/video", 0) == 0) return CameraSourceKind::Device;
  if (!source.empty() && std::all_of(source.begin(), source.end(), [](unsigned char c) { return std::isdigit(c); }))
    return CameraSourceKind::Device;
  return CameraSourceKind::File;
}

CameraSource::CameraSource(CameraDriverConfig cfg, const Clock& clock)
    : cfg_(std::move(cfg)), clock_(clock), kind_(classify_camera_source(cfg_.source)) {}

CameraSource::~CameraSource() { stop(); }

void CameraSource::start() {
  if (thread_.joinable() || stopping_) return;
  thread_ = std::thread([this] { run(); });
}

void CameraSource::stop() {
  {
    std::lock_guard lock(m_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

bool CameraSource::wait_stoppable(std::chrono::duration<double> d) {
  std::unique_lock lock(m_);
  return !cv_.wait_for(lock, d, [this] { return stopping_.load(); });
}

bool CameraSource::open(cv::VideoCapture& cap) {
  // A local file that is not there: say so instead of letting every backend try and complain.
  if (kind_ == CameraSourceKind::File && cfg_.source.find("://") == std::string::npos) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(cfg_.source, ec)) return false;
  }
  bool ok = false;
  try {
    switch (kind_) {
      case CameraSourceKind::Device: {
        const bool index = cfg_.source.rfind("/dev/", 0) != 0;
        ok = index ? cap.open(std::stoi(cfg_.source), cv::CAP_V4L2) : cap.open(cfg_.source, cv::CAP_V4L2);
        if (ok) {
          if (cfg_.fourcc.size() == 4)
            cap.set(cv::CAP_PROP_FOURCC,
                    cv::VideoWriter::fourcc(cfg_.fourcc[0], cfg_.fourcc[1], cfg_.fourcc[2], cfg_.fourcc[3]));
          cap.set(cv::CAP_PROP_FRAME_WIDTH, cfg_.width);
          cap.set(cv::CAP_PROP_FRAME_HEIGHT, cfg_.height);
          cap.set(cv::CAP_PROP_FPS, cfg_.fps);
          cap.set(cv::CAP_PROP_BUFFERSIZE, 1);  // the newest frame, not a backlog
        }
        break;
      }
      case CameraSourceKind::Pipeline:
        ok = cap.open(cfg_.source, cv::CAP_GSTREAMER);
        break;
      case CameraSourceKind::File:
        ok = cap.open(cfg_.source, cv::CAP_ANY);
        break;
    }
  } catch (const std::exception& e) {  // cv::Exception from a backend, std::out_of_range from stoi
    logger("camera")->warn("camera '{}': open failed: {}", cfg_.source, e.what());
    ok = false;
  }
  return ok && cap.isOpened();
}

void CameraSource::publish(Frame f) {
  {
    std::lock_guard lock(m_);
    if (slot_) ++stats_.dropped;
    slot_ = std::move(f);
    ++stats_.frames;
  }
  cv_.notify_all();
}

void CameraSource::run() {
  auto log = logger("camera");
  cv::VideoCapture cap;
  std::uint32_t seq = 0;
  int consecutive_failures = 0;
  std::uint64_t open_attempts = 0, next_report = 1;
  bool warned_size = false;
  bool looping = false;
  const auto period = std::chrono::duration<double>(1.0 / cfg_.fps);
  auto next_due = std::chrono::steady_clock::now();
  auto set_open = [&](bool open) {
    std::lock_guard lock(m_);
    stats_.open = open;
  };
  auto count = [&](std::uint64_t CameraStats::*counter) {
    std::lock_guard lock(m_);
    ++(stats_.*counter);
  };

  while (!stopping_) {
    if (!cap.isOpened()) {
      if (!open(cap)) {
        count(&CameraStats::open_failures);
        if (++open_attempts == next_report) {  // 1st, 10th, 100th... failure: a dead camera does not flood the log
          log->warn("camera '{}': cannot open ({} attempts); retrying every {} s", cfg_.source, open_attempts,
                    cfg_.reconnect_delay);
          next_report *= 10;
        }
        if (!wait_stoppable(std::chrono::duration<double>(cfg_.reconnect_delay))) break;
        continue;
      }
      set_open(true);
      consecutive_failures = 0;
      open_attempts = 0;
      next_report = 1;
      next_due = std::chrono::steady_clock::now();
      if (!looping) log->info("camera '{}' open ({})", cfg_.source, cap.getBackendName());
      looping = false;
    }

    cv::Mat image;
    bool ok = false;
    try {
      ok = cap.read(image) && !image.empty();
      if (ok) {
        cv::Mat bgr = to_bgr(image);
        if (bgr.empty()) log->warn("camera '{}': unsupported pixel format (OpenCV type {})", cfg_.source, image.type());
        ok = !bgr.empty();
        image = bgr;
      }
    } catch (const cv::Exception& e) {
      log->warn("camera '{}': read failed: {}", cfg_.source, e.what());
    }
    if (!ok) {
      if (kind_ == CameraSourceKind::File) {
        cap.release();
        set_open(false);
        if (cfg_.loop_file && seq > 0) {  // start over (a file with no frame at all is retried slowly below)
          looping = true;
          continue;
        }
        if (seq > 0) {
          {
            std::lock_guard lock(m_);
            stats_.finished = true;
          }
          cv_.notify_all();
          log->info("camera '{}': end of file after {} frames", cfg_.source, seq);
          break;
        }
      }
      count(&CameraStats::read_failures);
      if (++consecutive_failures >= kFailuresBeforeReconnect && cap.isOpened()) {
        log->warn("camera '{}': {} reads failed; reconnecting", cfg_.source, consecutive_failures);
        cap.release();
        set_open(false);
        count(&CameraStats::reconnects);
      }
      if (!wait_stoppable(std::chrono::duration<double>(cap.isOpened() ? 0.01 : cfg_.reconnect_delay))) break;
      continue;
    }
    consecutive_failures = 0;

    Frame f;
    f.stamp = clock_.now() - cfg_.latency;
    f.seq = seq++;
    f.bgr = image;
    if (f.bgr.cols != cfg_.width || f.bgr.rows != cfg_.height) {
      count(&CameraStats::size_mismatches);
      if (!warned_size)
        log->warn("camera '{}': frames are {}×{}, configured {}×{}", cfg_.source, f.bgr.cols, f.bgr.rows, cfg_.width,
                  cfg_.height);
      warned_size = true;
    }
    publish(std::move(f));

    if (kind_ == CameraSourceKind::File && cfg_.pace_file) {
      next_due += std::chrono::duration_cast<std::chrono::steady_clock::duration>(period);
      const auto wait = next_due - std::chrono::steady_clock::now();
      if (wait > wait.zero() && !wait_stoppable(wait)) break;
    }
  }
  cap.release();
  set_open(false);
  cv_.notify_all();
}

std::optional<Frame> CameraSource::next_frame(std::chrono::milliseconds timeout) {
  std::unique_lock lock(m_);
  cv_.wait_for(lock, timeout, [this] { return slot_.has_value() || stopping_ || stats_.finished; });
  if (!slot_) return std::nullopt;
  std::optional<Frame> f = std::move(slot_);
  slot_.reset();
  return f;
}

CameraStats CameraSource::stats() const {
  std::lock_guard lock(m_);
  return stats_;
}

}  // namespace fsd
