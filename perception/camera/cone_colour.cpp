#include "perception/camera/cone_colour.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <stdexcept>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace fsd {

const ConfigSection<ConeColourConfig>& cone_colour_section() {
  static const auto s =
      ConfigSection<ConeColourConfig>("perception.camera.colour")
          .number("min_saturation", &ConeColourConfig::min_saturation, 0.05, 0.95, "",
                  "HSV saturation (0..1) below which a pixel has no hue worth a vote (stripes, asphalt, grey).")
          .number("min_value", &ConeColourConfig::min_value, 0.0, 0.9, "",
                  "HSV value (0..1) below which a pixel is too dark for its hue to count.")
          .number("red_max", &ConeColourConfig::red_max, 0.0, 30.0, "deg", "Hue band edge: red below, orange above.")
          .number("edge_margin", &ConeColourConfig::edge_margin, 0.0, 20.0, "deg",
                  "A cone whose mean hue is this close to the edge between two cone colours gets a lower confidence "
                  "(zero on the edge).")
          .boolean("red", &ConeColourConfig::red,
                   "Name red cones (FSAC: red left boundary); off (FSG events), a red hue is read as orange.")
          .number("orange_max", &ConeColourConfig::orange_max, 15.0, 60.0, "deg",
                  "Hue band edge: orange below, yellow above.")
          .number("yellow_max", &ConeColourConfig::yellow_max, 40.0, 100.0, "deg",
                  "Hue band edge: yellow below, green (no cone colour) above.")
          .number("blue_min", &ConeColourConfig::blue_min, 100.0, 220.0, "deg",
                  "Hue band edge: green below, blue above.")
          .number("blue_max", &ConeColourConfig::blue_max, 220.0, 300.0, "deg",
                  "Hue band edge: blue below, purple (no cone colour) above.")
          .number("red_min", &ConeColourConfig::red_min, 280.0, 360.0, "deg", "Hue band edge: purple below, red above.")
          .number("min_confidence", &ConeColourConfig::min_confidence, 0.0, 1.0, "",
                  "A colour less certain than this is reported as unknown.", true)
          .number("full_coverage", &ConeColourConfig::full_coverage, 0.01, 1.0, "",
                  "Share of the cone's silhouette that its coloured pixels must cover for full confidence.")
          .number("big_cone_height", &ConeColourConfig::big_cone_height, 0.3, 0.6, "m",
                  "An orange cone at least this tall is big orange (small 0.325 m, big 0.505 m).")
          .boolean("white_balance", &ConeColourConfig::white_balance,
                   "Normalise each ROI's white balance on its near-grey pixels before reading hues.")
          .number("max_white_gain", &ConeColourConfig::max_white_gain, 1.0, 2.0, "",
                  "Largest per-channel gain of that white balance correction.")
          .integer("working_pixels", &ConeColourConfig::working_pixels, 100, 100000, "px",
                   "Larger ROIs are shrunk to about this many pixels before clustering.")
          .number("max_hidden", &ConeColourConfig::max_hidden, 0.0, 1.0, "",
                  "A candidate whose body is hidden behind nearer candidates in the image by more than this share "
                  "is left to the LiDAR: its ROI shows those, so the camera neither verifies, rejects nor names it; "
                  "below it, the colour is judged on the pixels those in front do not cover.");
  return s;
}

namespace {

enum Band : int { kRed, kOrange, kYellow, kBlue, kGreen, kPurple, kBandCount };
constexpr int kConeBands = 4;  // the first four are cone colours

Band band_of(float h, const ConeColourConfig& c) {
  if (h < c.red_max || h >= c.red_min) return c.red ? kRed : kOrange;
  if (h < c.orange_max) return kOrange;
  if (h < c.yellow_max) return kYellow;
  if (h < c.blue_min) return kGreen;
  if (h < c.blue_max) return kBlue;
  return kPurple;
}

// Hue distance from the edges the band shares with another cone colour's band (red–orange, orange–yellow).
double distance_to_neighbour(double hue, int band, const ConeColourConfig& c) {
  double d = 360.0;
  const auto from = [&](double edge) { d = std::min(d, std::abs(hue - edge)); };
  if (band == kRed && c.red) from(hue > 180 ? c.red_max + 360 : c.red_max);
  if (band == kOrange) {
    if (c.red) from(c.red_max);
    from(c.orange_max);
  }
  if (band == kYellow) from(c.orange_max);
  return d;
}

ConeColour colour_of(int band) {
  constexpr std::array<ConeColour, kConeBands> kColours{ConeColour::Red, ConeColour::Orange, ConeColour::Yellow,
                                                        ConeColour::Blue};
  return kColours[static_cast<std::size_t>(band)];
}

// Silhouette prior: a big cone with margins (wider and taller than any cone, for the LiDAR centroid's error) on its
// base point at the projected scale; for a crop of unknown scale, a cone filling the crop.
constexpr double kPriorBaseHalf = 0.20, kPriorTopHalf = 0.08, kPriorHeight = 0.53, kPriorBelow = 0.03;  // m
// The core: what any cone on that base point covers whatever its size (inside the small cone's 0.114 m base radius
// and 0.325 m height, less the centroid's error). Along its line of sight the candidate is the nearest object there
// (a nearer one hiding it is occlusion.hpp's), so the core's pixels are its own; the prior's margins can hold a
// neighbour standing behind it, a big orange cone of a timing line beside a boundary cone say.
constexpr int kMinVotes = 4;                                                     // pixels: fewer say nothing
constexpr double kCoreBaseHalf = 0.08, kCoreTopHalf = 0.03, kCoreHeight = 0.26;  // m

cv::Mat quad_mask(cv::Size size, const std::array<cv::Point2d, 4>& quad) {
  cv::Mat mask(size, CV_8U, cv::Scalar(0));
  constexpr int kShift = 4;  // sub-pixel vertices
  std::array<cv::Point, 4> pts;
  for (std::size_t i = 0; i < 4; ++i)
    pts[i] = cv::Point(static_cast<int>(std::lround(quad[i].x * (1 << kShift))),
                       static_cast<int>(std::lround(quad[i].y * (1 << kShift))));
  cv::fillConvexPoly(mask, pts.data(), 4, cv::Scalar(255), cv::LINE_8, kShift);
  return mask;
}

// A cone-shaped quad on the view's base point at its scale: half widths at the bottom and the top, m.
std::array<cv::Point2d, 4> cone_quad(const ConeView& v, double base_half, double top_half, double height,
                                     double below) {
  const double s = v.px_per_m, bottom = v.base.y + below * s, top = v.base.y - height * s;
  return {cv::Point2d(v.base.x - base_half * s, bottom), cv::Point2d(v.base.x + base_half * s, bottom),
          cv::Point2d(v.base.x + top_half * s, top), cv::Point2d(v.base.x - top_half * s, top)};
}

cv::Mat silhouette_prior(cv::Size size, const ConeView& v) {
  const double w = size.width, h = size.height;
  cv::Mat mask = quad_mask(
      size, v.px_per_m > 0
                ? cone_quad(v, kPriorBaseHalf, kPriorTopHalf, kPriorHeight, kPriorBelow)
                : std::array<cv::Point2d, 4>{cv::Point2d(0.08 * w, 0.97 * h), cv::Point2d(0.92 * w, 0.97 * h),
                                             cv::Point2d(0.62 * w, 0.03 * h), cv::Point2d(0.38 * w, 0.03 * h)});
  if (cv::countNonZero(mask) == 0) mask.setTo(255);
  return mask;
}

// The core (above); empty for a crop of unknown scale, which the cone fills.
cv::Mat silhouette_core(cv::Size size, const ConeView& v) {
  if (v.px_per_m <= 0) return {};
  return quad_mask(size, cone_quad(v, kCoreBaseHalf, kCoreTopHalf, kCoreHeight, 0.0));
}

// The pixels that can be the candidate's own: not covered by a candidate in front, nor by one behind outside the
// candidate's own outline (a small cone's on its base point: what stands behind shows around it). Each
// candidate is a box of its size on its base with a margin for the positions' error; in the working image scaled by
// (fx, fy) from the ROI; empty when no other candidate is near.
constexpr double kBoxMargin = 0.03;  // m

cv::Rect box_of(const ImageSilhouette& o, double fx, double fy) {
  const double s = o.px_per_m * fy, x = o.base.x * fx, y = o.base.y * fy;
  const double half = (o.half_width + kBoxMargin) * s;
  const cv::Point top_left(static_cast<int>(std::floor(x - half)),
                           static_cast<int>(std::floor(y - (o.height + kBoxMargin) * s)));
  const cv::Point bottom_right(static_cast<int>(std::ceil(x + half)), static_cast<int>(std::ceil(y + kBoxMargin * s)));
  return {top_left, bottom_right};
}

cv::Mat shown_mask(cv::Size size, const ConeView& v, std::span<const ImageSilhouette> in_front,
                   std::span<const ImageSilhouette> behind, double fx, double fy) {
  if (in_front.empty() && behind.empty()) return {};
  cv::Mat shown(size, CV_8U, cv::Scalar(255));
  if (!behind.empty() && v.px_per_m > 0) {
    // A small cone's outline on the base point (v is in the working image already), the margin all round.
    const cv::Mat own =
        quad_mask(size, cone_quad(v, kSmallConeHalfWidth + kBoxMargin, kSmallConeTopHalfWidth + kBoxMargin,
                                  kSmallConeHeight + kBoxMargin, kBoxMargin));
    cv::Mat theirs(size, CV_8U, cv::Scalar(0));
    for (const auto& o : behind) cv::rectangle(theirs, box_of(o, fx, fy), cv::Scalar(255), cv::FILLED);
    shown.setTo(0, theirs & ~own);
  }
  for (const auto& o : in_front) cv::rectangle(shown, box_of(o, fx, fy), cv::Scalar(0), cv::FILLED);
  return shown;
}

// Grey-world white balance on the pixels that are nearly grey already (asphalt, white stripe, overcast sky): their
// mean is made neutral, each channel's gain bounded, so a cone's own colour cannot be balanced away.
void normalise_white(cv::Mat& bgr, const ConeColourConfig& cfg) {
  cv::Mat hsv, grey;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::inRange(hsv, cv::Scalar(0, 0, 0.2), cv::Scalar(360, 0.2, 0.97), grey);
  if (cv::countNonZero(grey) < 0.05 * static_cast<double>(grey.total())) return;
  const cv::Scalar mean = cv::mean(bgr, grey);
  const double neutral = (mean[0] + mean[1] + mean[2]) / 3;
  cv::Scalar gain;
  for (int c = 0; c < 3; ++c)
    gain[c] = std::clamp(neutral / std::max(mean[c], 1e-6), 1.0 / cfg.max_white_gain, cfg.max_white_gain);
  bgr = bgr.mul(gain);
}

// The working image's pixels as the vote needs them.
struct Pixels {
  cv::Mat H, S, V;  // CV_32F: degrees, 0..1, 0..1
  cv::Mat clipped;  // CV_8U: some channel at the sensor's limit, so the hue is off
  cv::Mat prior;    // CV_8U: the silhouette prior
  cv::Mat core;     // CV_8U: the silhouette's core (empty: unknown scale)
  cv::Mat band;     // CV_8S: hue band of the cone cluster's voting pixels, -1 elsewhere
};

// Rows of the cone's axis, bottom to top, as body paint (B), white stripe (W) or neither (N); counts the white runs
// with body below and above. Runs shorter than 5 % of the cone's height (at least 2 rows) are noise.
int count_stripes(const std::vector<char>& rows_bottom_up) {
  const int n = static_cast<int>(rows_bottom_up.size());
  const int min_run = std::max(2, static_cast<int>(std::lround(0.05 * n)));
  std::vector<std::pair<char, int>> runs;
  for (const char kind : rows_bottom_up) {
    if (!runs.empty() && runs.back().first == kind)
      ++runs.back().second;
    else
      runs.emplace_back(kind, 1);
  }
  std::vector<char> kept;  // significant body and white runs, neighbours of the same kind merged
  for (const auto& [kind, length] : runs)
    if (kind != 'N' && length >= min_run && (kept.empty() || kept.back() != kind)) kept.push_back(kind);
  int stripes = 0;
  for (std::size_t i = 1; i + 1 < kept.size(); ++i)
    if (kept[i] == 'W' && kept[i - 1] == 'B' && kept[i + 1] == 'B') ++stripes;
  return stripes;
}

// White stripes along the axis of a cone filling a crop: a narrow column band around the median column of its body
// pixels, from its lowest to its highest body row. White is unsaturated and about as bright as the body.
int stripes_on_axis(const Pixels& px, int winner, const ConeColourConfig& cfg) {
  std::vector<int> columns;
  std::vector<float> body_value;
  int top = px.band.rows, bottom = -1;
  for (int r = 0; r < px.band.rows; ++r)
    for (int c = 0; c < px.band.cols; ++c)
      if (px.band.at<std::int8_t>(r, c) == winner) {
        columns.push_back(c);
        body_value.push_back(px.V.at<float>(r, c));
        top = std::min(top, r), bottom = std::max(bottom, r);
      }
  if (columns.size() < 8 || bottom - top < 8) return 0;
  std::sort(columns.begin(), columns.end());
  const auto at = [&](double q) {
    return columns[static_cast<std::size_t>(q * static_cast<double>(columns.size() - 1))];
  };
  const int axis = at(0.5), half = std::max(1, static_cast<int>(std::lround(0.1 * (at(0.9) - at(0.1)))));
  std::nth_element(body_value.begin(), body_value.begin() + static_cast<long>(body_value.size() / 2), body_value.end());
  const float white_value = 0.7f * body_value[body_value.size() / 2];
  std::vector<char> rows;
  for (int r = bottom; r >= top; --r) {
    int in_band = 0, body = 0, white = 0;
    for (int c = std::max(0, axis - half); c <= std::min(px.band.cols - 1, axis + half); ++c) {
      ++in_band;
      if (px.band.at<std::int8_t>(r, c) == winner)
        ++body;
      else if (px.S.at<float>(r, c) < cfg.min_saturation && px.V.at<float>(r, c) >= white_value)
        ++white;
    }
    rows.push_back(2 * body >= in_band ? 'B' : 2 * white >= in_band ? 'W' : 'N');
  }
  return count_stripes(rows);
}

// Height of the cone's body paint above its base, m: its highest row with paint in the row below too.
double paint_height(const Pixels& px, int winner, const ConeView& v) {
  for (int r = 0; r + 1 < px.band.rows; ++r) {
    const auto painted = [&](int row) {
      for (int c = 0; c < px.band.cols; ++c)
        if (px.band.at<std::int8_t>(row, c) == winner) return true;
      return false;
    };
    if (painted(r) && painted(r + 1)) return (v.base.y - r) / v.px_per_m;
  }
  return 0.0;
}

}  // namespace

ConeColourClassifier::ConeColourClassifier(const ConeColourConfig& cfg) : cfg_(cfg) {
  if (!(cfg.red_max <= cfg.orange_max && cfg.orange_max <= cfg.yellow_max && cfg.yellow_max <= cfg.blue_min &&
        cfg.blue_min <= cfg.blue_max && cfg.blue_max <= cfg.red_min))
    throw std::invalid_argument(
        "cone colour: hue band edges must rise: red_max ≤ orange_max ≤ yellow_max ≤ "
        "blue_min ≤ blue_max ≤ red_min");
}

ColourResult ConeColourClassifier::classify(const cv::Mat& roi_bgr, const ConeView& view, double height_hint,
                                            std::span<const ImageSilhouette> in_front,
                                            std::span<const ImageSilhouette> behind) const {
  if (roi_bgr.type() != CV_8UC3 || roi_bgr.cols < 2 || roi_bgr.rows < 2)
    throw std::invalid_argument("cone colour needs an 8-bit BGR image of at least 2 x 2 pixels");
  ColourResult result;

  // 1. Working size and white balance.
  const double shrink = std::min(1.0, std::sqrt(cfg_.working_pixels / static_cast<double>(roi_bgr.total())));
  cv::Mat small;
  if (shrink < 1.0)
    cv::resize(roi_bgr, small, cv::Size(), shrink, shrink, cv::INTER_AREA);
  else
    small = roi_bgr;
  const double fx = static_cast<double>(small.cols) / roi_bgr.cols, fy = static_cast<double>(small.rows) / roi_bgr.rows;
  const ConeView v{cv::Point2d(view.base.x * fx, view.base.y * fy), view.px_per_m * fy};
  Pixels px;
  {
    std::array<cv::Mat, 3> bgr8;
    cv::split(small, bgr8.data());
    cv::Mat brightest = cv::max(cv::max(bgr8[0], bgr8[1]), bgr8[2]);
    px.clipped = brightest >= 240;
  }
  cv::Mat bgr;
  small.convertTo(bgr, CV_32FC3, 1.0 / 255);
  if (cfg_.white_balance) normalise_white(bgr, cfg_);

  // 2. HSV without V: chroma (S cos H, S sin H) per pixel; k-means with k = 2 from the silhouette prior.
  cv::Mat hsv;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);  // float: H 0..360, S and V 0..1
  std::array<cv::Mat, 3> planes;
  cv::split(hsv, planes.data());
  px.H = planes[0], px.S = planes[1], px.V = planes[2];
  cv::Mat cx, cy;
  cv::polarToCart(px.S, px.H, cx, cy, true);
  px.prior = silhouette_prior(small.size(), v);
  // The pixels of the other candidates are neither the cone's nor a colour to cluster: grey background to k-means.
  const cv::Mat shown = shown_mask(small.size(), v, in_front, behind, fx, fy);
  if (!shown.empty()) {
    px.prior &= shown;
    cx.setTo(0, ~shown);
    cy.setTo(0, ~shown);
  }
  const int n = static_cast<int>(small.total());
  cv::Mat samples(n, 2, CV_32F);
  cx.reshape(1, n).copyTo(samples.col(0));
  cy.reshape(1, n).copyTo(samples.col(1));
  const cv::Mat prior_flat = px.prior.reshape(1, n);
  cv::Mat labels(n, 1, CV_32S);
  for (int i = 0; i < n; ++i) labels.at<int>(i) = prior_flat.at<std::uint8_t>(i) ? 0 : 1;
  cv::Mat centres;
  cv::kmeans(samples, 2, labels, cv::TermCriteria(cv::TermCriteria::EPS | cv::TermCriteria::COUNT, 10, 1e-3), 1,
             cv::KMEANS_USE_INITIAL_LABELS, centres);

  // 3. The cone's cluster: the one that holds most of the core's coloured pixels; without enough of those, the one
  // inside the silhouette and saturated.
  px.core = silhouette_core(small.size(), v);
  if (!px.core.empty() && !shown.empty()) px.core &= shown;
  const cv::Mat core_flat = px.core.empty() ? cv::Mat() : px.core.reshape(1, n);
  const cv::Mat S_flat = px.S.reshape(1, n);
  std::array<int, 2> members{}, inside{}, core_coloured{};
  for (int i = 0; i < n; ++i) {
    const auto k = static_cast<std::size_t>(labels.at<int>(i));
    ++members[k];
    if (prior_flat.at<std::uint8_t>(i)) ++inside[k];
    if (!core_flat.empty() && core_flat.at<std::uint8_t>(i) && S_flat.at<float>(i) >= cfg_.min_saturation)
      ++core_coloured[k];
  }
  int cone = 0;
  if (core_coloured[0] + core_coloured[1] >= kMinVotes && core_coloured[0] != core_coloured[1]) {
    cone = core_coloured[1] > core_coloured[0] ? 1 : 0;
  } else {
    double best_score = -1;
    for (int k = 0; k < 2; ++k) {
      const auto kk = static_cast<std::size_t>(k);
      if (members[kk] == 0) continue;
      const double chroma = std::hypot(centres.at<float>(k, 0), centres.at<float>(k, 1));
      const double score = static_cast<double>(inside[kk]) / members[kk] + 0.5 * chroma;
      if (score > best_score) best_score = score, cone = k;
    }
  }

  // Votes by hue band of its saturated, bright enough pixels inside the silhouette. The most trusted pixels vote
  // when there are enough of them: in the core (the candidate's own, above), inside the cluster (its edge pixels
  // blend with the background: orange on grass blends to yellow) and not clipped (over-exposed paint drifts: orange
  // towards yellow).
  px.band = cv::Mat(small.size(), CV_8S, cv::Scalar(-1));
  cv::Mat member(small.size(), CV_8U, cv::Scalar(0));
  for (int i = 0; i < n; ++i)
    if (labels.at<int>(i) == cone && prior_flat.at<std::uint8_t>(i)) member.data[i] = 255;
  cv::Mat interior;
  cv::erode(member, interior, cv::Mat(), cv::Point(-1, -1), 1, cv::BORDER_REPLICATE);
  enum Tier { kCore, kTrusted, kUnclipped, kAll, kTiers };
  std::array<std::array<int, kBandCount>, kTiers> tiers{};
  for (int r = 0; r < small.rows; ++r)
    for (int c = 0; c < small.cols; ++c) {
      if (!member.at<std::uint8_t>(r, c)) continue;
      if (px.S.at<float>(r, c) < cfg_.min_saturation || px.V.at<float>(r, c) < cfg_.min_value) continue;
      const Band b = band_of(px.H.at<float>(r, c), cfg_);
      px.band.at<std::int8_t>(r, c) = static_cast<std::int8_t>(b);
      const bool unclipped = !px.clipped.at<std::uint8_t>(r, c);
      ++tiers[kAll][b];
      if (unclipped) ++tiers[kUnclipped][b];
      if (unclipped && interior.at<std::uint8_t>(r, c)) {
        ++tiers[kTrusted][b];
        if (!px.core.empty() && px.core.at<std::uint8_t>(r, c)) ++tiers[kCore][b];
      }
    }
  const auto cone_sum = [](const std::array<int, kBandCount>& v) {
    return std::accumulate(v.begin(), v.begin() + kConeBands, 0);
  };
  int tier = kCore;
  while (tier < kAll &&
         cone_sum(tiers[static_cast<std::size_t>(tier)]) < std::max<double>(kMinVotes, 0.15 * cone_sum(tiers[kAll])))
    ++tier;
  const std::array<int, kBandCount>& votes = tiers[static_cast<std::size_t>(tier)];
  const std::array<int, kBandCount>& all = tiers[kAll];
  const int winner = static_cast<int>(std::max_element(votes.begin(), votes.begin() + kConeBands) - votes.begin());
  const int won = votes[static_cast<std::size_t>(winner)];
  if (won == 0) return result;

  // 4. Confidence: purity among the cone colours times coverage of the silhouette (all of the winner's pixels).
  const double purity = static_cast<double>(won) / cone_sum(votes);
  const double coverage =
      static_cast<double>(all[static_cast<std::size_t>(winner)]) / std::max(1, cv::countNonZero(px.prior));
  result.best = colour_of(winner);
  result.confidence = purity * std::min(1.0, coverage / cfg_.full_coverage);
  double sx = 0, sy = 0;
  for (int r = 0; r < small.rows; ++r)
    for (int c = 0; c < small.cols; ++c)
      if (px.band.at<std::int8_t>(r, c) == winner && (tier == kAll || !px.clipped.at<std::uint8_t>(r, c))) {
        const double h = px.H.at<float>(r, c) * std::numbers::pi / 180;
        sx += std::cos(h), sy += std::sin(h);
      }
  result.hue = std::fmod(std::atan2(sy, sx) * 180 / std::numbers::pi + 360.0, 360.0);
  if (const double edge = distance_to_neighbour(result.hue, winner, cfg_); edge < cfg_.edge_margin)
    result.confidence *= edge / cfg_.edge_margin;
  const bool non_cone_wins = votes[kGreen] > won || votes[kPurple] > won;

  // 5. Big orange by size: the LiDAR's height, else the paint's height at the projected scale, else two stripes.
  if (result.best == ConeColour::Orange) {
    bool big = false;
    if (height_hint > 0) {
      big = height_hint >= cfg_.big_cone_height;
    } else if (v.px_per_m > 0) {
      // The paint's top is good to a pixel, the projected base to a couple (a third of a degree of the camera's pitch
      // at 460 px of focal length): a small cone 15 m away (40 px/m) measured up to 0.47 m on the virtual car. Big
      // only when taller than the bar by that much: the small cone is the common one.
      constexpr double kRowsUncertain = 2.0;
      result.height = paint_height(px, winner, v);
      big = result.height - kRowsUncertain / v.px_per_m >= cfg_.big_cone_height;
    } else {
      result.stripes = stripes_on_axis(px, winner, cfg_);
      big = result.stripes >= 2;
    }
    if (big) result.best = ConeColour::BigOrange;
  }
  if (result.confidence >= cfg_.min_confidence && !non_cone_wins) result.colour = result.best;
  return result;
}

}  // namespace fsd
