#pragma once
// Camera frames of the virtual car with the candidates a LiDAR would hand to the camera stage, and their truth: for
// training the cone classifier (`fsd train-classifier`) and for testing the camera stages on frames nobody trained on.
//
// Per track: a world with distractors (tyres, tyre stacks, posts, fences), cameras whose mount, field of view, sun
// and exposure vary by seed (a new one every frames_per_camera frames), and frames from poses along the track's centre line (offset and turned at random) at
// random times, so the lighting drifts and has its shadows and bright spells. Each frame goes through JPEG as the
// camera sends it. Candidates, in the vehicle frame like the LiDAR stages give them:
//   cones     every cone the camera sees within max_range, at its base centre moved towards the sensor (the LiDAR
//             sees the near half) plus centroid noise;
//   others    tyres, stacks and posts at their near side, points along fences, and bare ground (asphalt, grass);
// with the LiDAR envelope's size. Every draw comes from the seed (sim::Rng): the same seed gives the same frames.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <opencv2/core/mat.hpp>

#include "common/camera_geometry.hpp"
#include "common/types.hpp"
#include "perception/camera/camera_stage.hpp"

namespace fsd {

struct RenderedCandidate {
  Cone cone;           // as the LiDAR stages report it: vehicle frame, stage Lidar, no colour
  CandidateSize size;  // its cluster's envelope
  bool is_cone = false;
  ConeColour colour = ConeColour::Unknown;  // truth, for cones
  std::string kind;                         // cone, tyre, tyre_stack, post, fence, ground, grass
  double range = 0.0;                       // m from the camera to the base
  double visible_fraction = 1.0;            // cones: share of the silhouette not hidden by nearer objects
  bool truncated = false;                   // cones: the silhouette is cut by the image border
  bool crowded = false;    // not a cone, but a visible cone covers a quarter of its ROI: no clean label
  cv::Rect truth_box;      // cones: the silhouette's pixels (cut to the image)
  cv::Point2d truth_base;  // cones: the pixel of the base centre
};

struct RenderedFrame {
  std::string track;              // file stem
  int frame = 0;                  // index within the track, from 0
  cv::Mat bgr;                    // JPEG-decoded, as the driver delivers it
  CameraCalibration calibration;  // the camera's exact pinhole (intrinsics and mount)
  std::vector<RenderedCandidate> candidates;
};

struct RenderedScenesConfig {
  std::vector<std::string> tracks;  // track files (EUFS/FSDS CSV)
  int frames_per_track = 40;
  int frames_per_camera = 20;  // a new camera (mount, field of view, sun, exposure) after this many frames
  std::uint64_t seed = 1;
  double max_range = 20.0;       // m: candidates farther away are not offered
  double position_noise = 0.05;  // m, σ of the LiDAR centroid in x and y
  int ground_candidates = 3;     // bare-ground candidates per frame
  bool fsac_share = true;        // every other track in FSAC colours (red and blue), so red cones appear
  bool vary_camera = true;       // mount, field of view, sun and exposure drawn per track
};

// Renders the frames one by one (a world and a camera per track, frames in order) and hands each to `frame_fn`.
// Throws TrackError for a track that does not load.
void render_camera_scenes(const RenderedScenesConfig& cfg, const std::function<void(const RenderedFrame&)>& frame_fn);

}  // namespace fsd
