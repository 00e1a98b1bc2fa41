#pragma once
// The camera driver: reads frames with OpenCV's VideoCapture from a V4L2 device (/dev/video0 or an index), a
// GStreamer pipeline (a string with '!') or a video file, on its own thread, and hands the latest frame over to one
// consumer (DESIGN.md §4: a latest-value slot; a frame nobody took before the next arrived is counted as dropped).
//
// Frames are stamped with the run's clock when the read returns, minus the configured capture latency. A source
// that fails to open or stops delivering is released and reopened after reconnect_delay, for ever, counting each
// attempt; a video file ends the stream at its end unless loop_file is set. stop() returns after the current read
// (a V4L2 read gives up after the driver's timeout if the device hangs).
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include "common/clock.hpp"
#include "common/config.hpp"
#include "drivers/camera/frame.hpp"

namespace cv {
class VideoCapture;
}

namespace fsd {

struct CameraDriverConfig {
  bool enabled = false;                // fsd run on the car opens the camera only when set
  std::string source = "/dev/video0";  // V4L2 device or index, GStreamer pipeline, or video file
  int width = 640;
  int height = 480;
  double fps = 20.0;
  std::string fourcc = "MJPG";   // pixel format requested from a V4L2 device; "" = the device's default
  std::string calibration;       // calibration file (docs/camera.md); "" = none
  double latency = 0.0;          // s from exposure to the read returning, subtracted from the stamp
  double reconnect_delay = 1.0;  // s between attempts to (re)open a failed source
  bool loop_file = false;        // a video file starts over at its end instead of ending the stream
  bool pace_file = true;         // a video file plays at `fps` (else as fast as it decodes)
};

const ConfigSection<CameraDriverConfig>& camera_driver_section();  // prefix "drivers.camera"

enum class CameraSourceKind { Device, Pipeline, File };
CameraSourceKind classify_camera_source(const std::string& source);

struct CameraStats {
  std::uint64_t frames = 0;         // delivered to the slot
  std::uint64_t dropped = 0;        // replaced in the slot before anyone took them
  std::uint64_t read_failures = 0;  // reads that returned no image
  std::uint64_t open_failures = 0;
  std::uint64_t reconnects = 0;       // times a failing open source was released to be reopened
  std::uint64_t size_mismatches = 0;  // frames whose size differs from the configured one
  bool open = false;
  bool finished = false;  // a video file reached its end
};

class CameraSource {
 public:
  CameraSource(CameraDriverConfig cfg, const Clock& clock);
  ~CameraSource();
  CameraSource(const CameraSource&) = delete;
  CameraSource& operator=(const CameraSource&) = delete;

  void start();  // starts the reader thread (once)
  void stop();   // stops and joins it; idempotent

  // Waits up to `timeout` for a frame newer than the last one taken. Nothing on timeout, after stop(), or when
  // a file has ended and its last frame was taken.
  std::optional<Frame> next_frame(std::chrono::milliseconds timeout);
  CameraStats stats() const;
  const CameraDriverConfig& config() const { return cfg_; }

 private:
  void run();
  bool open(cv::VideoCapture& cap);
  void publish(Frame f);
  bool wait_stoppable(std::chrono::duration<double> d);  // false when stopping

  CameraDriverConfig cfg_;
  const Clock& clock_;
  CameraSourceKind kind_;
  std::thread thread_;
  std::atomic<bool> stopping_{false};

  mutable std::mutex m_;
  std::condition_variable cv_;
  std::optional<Frame> slot_;
  CameraStats stats_;
};

}  // namespace fsd
