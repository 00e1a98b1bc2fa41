#pragma once
// Camera stage 3 (DESIGN.md §5b, the paper's §III.B.3): the colour of a verified cone from its ROI.
//
// The paper's method, made robust for real photos (other cameras, white balance, backgrounds, 20 to 400 px):
//  1. Shrink the ROI to a working size and normalise the white balance on its near-grey pixels (asphalt, the white
//     stripe), with a bounded gain, so a colour cast does not move hues across a band edge.
//  2. HSV without V: every pixel becomes its chroma (S·cos H, S·sin H), so brightness (shade, exposure) drops out and
//     hue wraps around red correctly; k-means with k = 2 (cv::kmeans) splits the pixels, started from where the cone
//     should be (a silhouette prior in the ROI) against the rest.
//  3. The cone's cluster is the one holding most of the coloured pixels of the silhouette's core (what any cone on
//     the base point covers: the candidate's own pixels, where the silhouette's margins can hold a neighbour standing
//     behind it), else the one inside the silhouette and saturated (the background is grey asphalt, green grass, sky
//     at the edges); its saturated, not-too-dark pixels inside the silhouette vote by hue band, those in the core
//     first. The white or black stripe and dark pixels have no reliable hue and do not vote. The candidates standing
//     in front (their image boxes) take no part: a cone partly behind another is named by the part that shows; nor
//     do those behind it, around the cone's own outline.
//  4. The colour is the winning cone band (red, orange, yellow, blue); its confidence is the share of the cone bands'
//     votes it won times how much of the silhouette those pixels cover, lowered when their mean hue lies within
//     edge_margin of another cone colour's band. Below min_confidence, or when a non-cone hue (green, purple)
//     outvotes it, the answer is Unknown: a wrong colour costs more than no colour.
//  5. Orange is big orange when the cone is tall: from the LiDAR's height when given, else from the height of the
//     orange pixels in the ROI at the projected scale, else (a crop of unknown scale) from two separate white
//     stripes (the big cone has two, the small one one).
#include <span>

#include <opencv2/core/mat.hpp>
#include <opencv2/core/types.hpp>

#include "common/config.hpp"
#include "common/types.hpp"
#include "perception/camera/occlusion.hpp"

namespace fsd {

struct ConeColourConfig {
  double min_saturation = 0.35;  // 0..1: pixels below have no hue worth a vote (stripes, asphalt, grey)
  double min_value = 0.15;       // 0..1: nor darker ones
  // Hue bands, degrees (OpenCV's 0..180 scale is half of this): red wraps around 0.
  double red_max = 6.0;            // red below this, orange from it (photos of orange cones reach 7°)
  double orange_max = 41.0;        // yellow from here
  double yellow_max = 75.0;        // green (not a cone colour) from here
  double blue_min = 170.0;         // blue from here
  double blue_max = 270.0;         // purple (not a cone colour) from here
  double red_min = 330.0;          // red again from here
  double edge_margin = 3.0;        // deg: a cone whose mean hue is this close to the edge of two cone colours is unsure
  bool red = true;                 // name red cones (FSAC's left boundary); off: a red hue reads as orange
  double min_confidence = 0.55;    // below: Unknown
  double full_coverage = 0.12;     // voting pixels covering this share of the silhouette count fully
  double big_cone_height = 0.415;  // m: an orange cone at least this tall is big orange (0.325 vs 0.505 m)
  bool white_balance = true;       // normalise the ROI's white balance on its near-grey pixels
  double max_white_gain = 1.25;    // bound of that correction per channel
  int working_pixels = 1600;       // larger ROIs are shrunk to about this many pixels
  double max_hidden = 0.7;         // share of a candidate hidden behind nearer ones above which the camera leaves it
};
const ConfigSection<ConeColourConfig>& cone_colour_section();  // prefix "perception.camera.colour"

// Where the cone stands in the ROI: its base centre and the image scale there. px_per_m = 0: unknown, a crop that
// the cone fills (`fsd classify`).
struct ConeView {
  cv::Point2d base;
  double px_per_m = 0.0;
};

struct ColourResult {
  ConeColour colour = ConeColour::Unknown;
  double confidence = 0.0;                // 0..1
  ConeColour best = ConeColour::Unknown;  // the winning band even when not confident enough
  double hue = 0.0;                       // degrees, circular mean of the winning band's votes
  double height = 0.0;                    // m, the orange pixels' height when measured, else 0
  int stripes = -1;                       // white stripes counted on a crop of unknown scale, -1 when not counted
};

class ConeColourClassifier {
 public:
  explicit ConeColourClassifier(const ConeColourConfig& cfg = {});
  // `roi_bgr`: CV_8UC3, at least 2 × 2 pixels. `height_hint`: the candidate's height from the LiDAR, m (0 = unknown).
  // `in_front`, `behind`: the other candidates standing in front of this one and behind it, in the ROI's pixels.
  // Those in front take no part (the colour is judged on the part of the cone that shows), nor those behind outside
  // a small cone's outline on this one's base point (a taller cone behind shows above and beside it).
  ColourResult classify(const cv::Mat& roi_bgr, const ConeView& view, double height_hint = 0.0,
                        std::span<const ImageSilhouette> in_front = {},
                        std::span<const ImageSilhouette> behind = {}) const;
  // The view of a crop the cone fills.
  static ConeView crop_view(cv::Size crop) { return {cv::Point2d(crop.width / 2.0, crop.height), 0.0}; }
  const ConeColourConfig& config() const { return cfg_; }

 private:
  ConeColourConfig cfg_;
};

}  // namespace fsd
