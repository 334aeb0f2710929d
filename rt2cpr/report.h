// rt2cpr/report.h — what rt2cpr tells its user: the set-up, per-frame timing with median,
// min and max, ray counts by kind, Mrays/s, image error against a reference, what each
// process of an MPI job did, and all of it as JSON for --stats (keys in snake_case).
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rt2/render/compiled_scene.h"
#include "rt2/image/image.h"
#include "rt2/render/renderer.h"
#include "rt2/render/schedule.h"
#include "rt2cpr/options.h"
#include "rt2cpr/rank_stats.h"

namespace rt2cpr {

class Report {
 public:
  Report(const Options& o, const rt2::Scene& scene, const rt2::CompiledScene& compiled,
         const rt2::Renderer& renderer, double load_ms, double build_ms);
  // A frame, and how many of its passes were rendered (fewer under --time-budget).
  void add_frame(const rt2::FrameResult& r, int passes);
  // A frame's light update (--animate-lights): moving the lights and rebuilding their tree.
  void add_light_update(const rt2::LightBvh::BuildTimes& t) { light_updates_.push_back(t); }
  // A frame's pose of an animated scene (--time, --fps): loading it at the frame's time and
  // placing it (trees, lights), in ms, and how the triangle trees were placed.
  void add_pose(double load_ms, double place_ms, rt2::CompiledScene::Placed placed) {
    poses_.push_back({load_ms, place_ms, placed});
  }
  // The processes of an MPI job, rank by rank (rt2cpr_mpi; none for rt2cpr).
  void set_ranks(std::vector<RankStats> ranks) { ranks_ = std::move(ranks); }
  // Image error of the last frame against a reference of the same size (RMSE, PSNR, SSIM).
  void compare(const rt2::Image& image, const rt2::Image& reference);
  void print_setup() const;
  void print_summary() const;
  nlohmann::json json() const;

 private:
  double median_ms() const;
  void print_ranks() const;
  nlohmann::json j_;
  std::vector<double> frame_ms_;
  rt2::RayCounts rays_;                        // the last frame's
  std::vector<rt2::StageTimes> stages_;         // per frame
  std::vector<rt2::LightBvh::BuildTimes> light_updates_;  // per frame, --animate-lights
  struct Pose {
    double load_ms, place_ms;
    rt2::CompiledScene::Placed placed;
  };
  std::vector<Pose> poses_;  // per frame after the first, an animated scene
  std::vector<RankStats> ranks_;
  int passes_ = 0;
  std::uint64_t nonfinite_ = 0;
};

}  // namespace rt2cpr
