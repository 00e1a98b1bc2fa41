// `fsd classify` and `fsd train-classifier` as a user runs them: the real binary, its exit status and output. Crops
// come from frames of the virtual car (truth: the simulator's cone and its colour) saved as PNG and JPEG.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "daemon/cli/rendered_camera_scenes.hpp"
#include "tests/daemon/fsd_process.hpp"
#include "tests/scratch_dir.hpp"

namespace fsd {
namespace {

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string out;
};
Result fsd(const std::string& args) {
  Result r;
  r.status = test::run_fsd(args, &r.out);
  return r;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// "prefix<i>ext", appended piece by piece (GCC 12 warns about a false overlap in a chain of operator+).
std::string numbered(const char* prefix, std::size_t i, const char* ext) {
  std::string s = prefix;
  s += std::to_string(i);
  s += ext;
  return s;
}

struct Crop {
  cv::Mat bgr;
  ConeColour colour;
};

// Crops of clearly visible cones 4-10 m away, cut at their silhouette with a margin, as a person crops a photo.
std::vector<Crop> rendered_cone_crops(std::size_t wanted) {
  std::vector<Crop> crops;
  RenderedScenesConfig cfg;
  cfg.tracks = {"../shared/tracks/epfl_track_4.csv", "../shared/tracks/epfl_track_5.csv"};
  cfg.frames_per_track = 4;
  cfg.seed = 4242;
  render_camera_scenes(cfg, [&](const RenderedFrame& f) {
    for (const auto& c : f.candidates) {
      if (!c.is_cone || c.visible_fraction < 0.95 || c.truncated || c.range < 4 || c.range > 10) continue;
      const int mx = c.truth_box.width / 5, my = c.truth_box.height / 8;
      const cv::Rect box =
          (c.truth_box + cv::Size(2 * mx, 2 * my) - cv::Point(mx, my)) & cv::Rect(0, 0, f.bgr.cols, f.bgr.rows);
      if (crops.size() < wanted) crops.push_back({f.bgr(box).clone(), c.colour});
    }
  });
  return crops;
}

class ClassifyCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = test::scratch_path(::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  fs::path dir_;
};

TEST_F(ClassifyCommand, NamesTheConeAndItsColourOfRenderedCrops) {
  const auto crops = rendered_cone_crops(12);
  ASSERT_GE(crops.size(), 8u);
  int right = 0;
  for (std::size_t i = 0; i < crops.size(); ++i) {
    const fs::path file = dir_ / numbered("crop", i, i % 2 ? ".jpg" : ".png");
    ASSERT_TRUE(cv::imwrite(file.string(), crops[i].bgr));
    const Result r = fsd("classify --json --image " + file.string());
    ASSERT_EQ(r.status, 0) << r.out;
    const nlohmann::json j = nlohmann::json::parse(r.out);
    ASSERT_TRUE(j.contains("cone") && j.contains("score") && j.contains("colour") && j.contains("confidence")) << r.out;
    EXPECT_EQ(j["cone"].get<bool>(), j["score"].get<double>() >= 0.0) << r.out;
    right += j["cone"].get<bool>() && j["colour"] == to_string(crops[i].colour);
    EXPECT_GE(j["confidence"].get<double>(), 0.0);
    EXPECT_LE(j["confidence"].get<double>(), 1.0);
  }
  EXPECT_GE(right, static_cast<int>(crops.size()) - 1) << "cones named with their colour";
  // Without --json: one readable line.
  const Result text = fsd("classify --image " + (dir_ / "crop0.png").string());
  EXPECT_EQ(text.status, 0);
  EXPECT_NE(text.out.find("colour " + std::string(to_string(crops[0].colour))), std::string::npos) << text.out;
}

TEST_F(ClassifyCommand, BadImagesExitTwoWithAMessage) {
  const fs::path empty = dir_ / "empty.png", text = dir_ / "text.png", truncated = dir_ / "truncated.jpg",
                 huge = dir_ / "huge.png";
  std::ofstream(empty).close();
  std::ofstream(text) << "this is not an image\n";
  // A real JPEG cut in half.
  std::vector<std::uint8_t> jpeg;
  cv::imencode(".jpg", cv::Mat(64, 48, CV_8UC3, cv::Scalar(30, 80, 200)), jpeg);
  std::ofstream(truncated, std::ios::binary).write(reinterpret_cast<const char*>(jpeg.data()), 40);
  // A PNG header claiming 30000 x 30000 px (a decompression bomb): refused before decoding.
  const unsigned char bomb[] = {0x89, 'P',  'N',  'G', '\r', '\n', 0x1A, '\n', 0, 0, 0, 13, 'I', 'H', 'D', 'R', 0,
                                0,    0x75, 0x30, 0,   0,    0x75, 0x30, 8,    2, 0, 0, 0,  0,   0,   0,   0};
  std::ofstream(huge, std::ios::binary).write(reinterpret_cast<const char*>(bomb), sizeof bomb);
  const struct {
    fs::path file;
    const char* message;
  } cases[] = {{empty, "empty file"},
               {text, "not a PNG or JPEG"},
               {truncated, "JPEG"},
               {huge, "too large"},
               {dir_ / "missing.png", "cannot read"}};
  for (const auto& c : cases) {
    const Result r = fsd("classify --json --image " + c.file.string());
    EXPECT_EQ(r.status, 2) << c.file << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.file << "\n" << r.out;
    EXPECT_NE(r.out.find(c.file.filename().string()), std::string::npos) << "names the file: " << r.out;
  }
  EXPECT_EQ(fsd("classify --json").status, 2);  // --image is required
}

TEST_F(ClassifyCommand, AMissingOrCorruptModelIsAClearError) {
  const auto crops = rendered_cone_crops(1);
  ASSERT_EQ(crops.size(), 1u);
  const fs::path image = dir_ / "cone.png", corrupt = dir_ / "corrupt.json";
  cv::imwrite(image.string(), crops[0].bgr);
  std::ofstream(corrupt) << "{\"format\": \"fsd-cone-classifier\", \"version\": 1, \"hog\": {}}";
  for (const auto& [model, message] : {std::pair{(dir_ / "none.json").string(), "cannot read the classifier model"},
                                       std::pair{corrupt.string(), "field 'hog.window': missing"}}) {
    const fs::path config = dir_ / "config.json";
    std::ofstream(config) << nlohmann::json{{"perception", {{"camera", {{"classifier", {{"model", model}}}}}}}}.dump();
    const Result r = fsd("classify --image " + image.string() + " --config " + config.string());
    EXPECT_EQ(r.status, 2) << r.out;
    EXPECT_NE(r.out.find(message), std::string::npos) << r.out;
  }
}

class TrainClassifierCommand : public ClassifyCommand {};

// Same seed, same model bytes; the held-back accuracy is printed, for rendered crops and for real crops.
TEST_F(TrainClassifierCommand, IsReproducibleAndPrintsItsAccuracy) {
  const auto crops = rendered_cone_crops(10);
  ASSERT_GE(crops.size(), 10u);
  const fs::path real = dir_ / "real";
  fs::create_directories(real / "cone");
  fs::create_directories(real / "not_cone");
  for (std::size_t i = 0; i < crops.size(); ++i) {
    cv::imwrite((real / "cone" / numbered("c", i, ".png")).string(), crops[i].bgr);
    cv::Mat ground(crops[i].bgr.size(), CV_8UC3, cv::Scalar(90 + 3 * static_cast<double>(i), 92, 95));
    cv::imwrite((real / "not_cone" / numbered("g", i, ".jpg")).string(), ground);
  }
  const std::string args =
      "train-classifier --frames 3 --seed 5 --track ../shared/tracks/epfl_track_2.csv "
      "--track ../shared/tracks/amz_fssim_thin.csv --real " +
      real.string();
  const Result a = fsd(args + " --out " + (dir_ / "a.json").string());
  const Result b = fsd(args + " --out " + (dir_ / "b.json").string());
  ASSERT_EQ(a.status, 0) << a.out;
  ASSERT_EQ(b.status, 0) << b.out;
  EXPECT_NE(a.out.find("held-back rendered crops: accuracy"), std::string::npos) << a.out;
  EXPECT_NE(a.out.find("held-back real crops: accuracy"), std::string::npos) << a.out;
  const std::string model = slurp(dir_ / "a.json");
  EXPECT_EQ(model, slurp(dir_ / "b.json"));
  const nlohmann::json j = nlohmann::json::parse(model);
  EXPECT_EQ(j["training"]["seed"], 5);
  EXPECT_EQ(j["training"]["real_crops_trained"], 16);  // 8 + 8 of the 10 + 10: every fifth is held back
  // Another seed renders other worlds: another model.
  const Result c = fsd("train-classifier --frames 3 --seed 6 --track ../shared/tracks/epfl_track_2.csv --out " +
                       (dir_ / "c.json").string());
  ASSERT_EQ(c.status, 0) << c.out;
  EXPECT_NE(slurp(dir_ / "c.json"), model);
}

TEST_F(TrainClassifierCommand, BadInputExitsTwo) {
  const fs::path bad = dir_ / "bad";
  fs::create_directories(bad / "cone");
  const struct {
    std::string args, message;
  } cases[] = {
      {"--frames 1 --real " + bad.string(), "not_cone"},
      {"--frames 1 --track " + (dir_ / "no_track.csv").string(), "no_track.csv"},
      {"--frames 0", "--frames"},
  };
  for (const auto& c : cases) {
    const Result r = fsd("train-classifier " + c.args + " --out " + (dir_ / "x.json").string());
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.out;
    EXPECT_NE(r.out.find(c.message), std::string::npos) << c.args << "\n" << r.out;
  }
  std::ofstream(bad / "cone" / "broken.png") << "garbage";
  fs::create_directories(bad / "not_cone");
  const Result r = fsd("train-classifier --frames 1 --real " + bad.string() + " --out " + (dir_ / "x.json").string());
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("broken.png"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(dir_ / "x.json"));
}

}  // namespace
}  // namespace fsd
