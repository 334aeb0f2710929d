// rt2cpr/report.cpp — console and JSON reporting.
#include "rt2cpr/report.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "rt2/base/error.h"
#include "rt2/image/image_compare.h"
#include "rt2/base/version.h"
#include "rt2cpr/failure.h"

namespace rt2cpr {

namespace fs = std::filesystem;

namespace {


std::string utc_now() {
  char buf[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&t));
  return buf;
}

// A float as the shortest decimal that reads back as the same float (0.01f -> 0.01, not
// 0.009999999776482582 as its double would print).
double json_float(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  for (int digits = 1; digits <= 9; ++digits) {
    char shorter[32];
    std::snprintf(shorter, sizeof shorter, "%.*g", digits, static_cast<double>(v));
    if (std::strtof(shorter, nullptr) == v) return std::strtod(shorter, nullptr);
  }
  return std::strtod(buf, nullptr);
}

const char* light_culling_name(rt2::LightCulling c) {
  switch (c) {
    case rt2::LightCulling::none: return "none";
    case rt2::LightCulling::tiled: return "tiled";
    case rt2::LightCulling::clustered: return "clustered";
    case rt2::LightCulling::bvh: return "bvh";
  }
  return "?";
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n == 0 ? 0.0 : (n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]));
}

// The median over frames of one field of each frame's record, in ms.
template <class T, class F>
double median_of(const std::vector<T>& frames, F field) {
  std::vector<double> v;
  for (const T& f : frames) v.push_back(field(f));
  return median(v);
}

// The share of its render threads' frame time a rank spent rendering tiles.
double busy_share(const RankStats& r, const std::vector<double>& frame_ms) {
  double frames = 0.0;
  for (double ms : frame_ms) frames += ms;
  return r.threads > 0 && frames > 0.0 ? r.busy_ms / (r.threads * frames) : 0.0;
}

std::string host_name() {
  char buf[256] = {};
  if (::gethostname(buf, sizeof buf - 1) != 0) return "unknown";
  return buf;
}

}  // namespace

Report::Report(const Options& o, const rt2::Scene& scene, const rt2::CompiledScene& compiled,
               const rt2::Renderer& renderer, double load_ms, double build_ms) {
  const rt2::RenderSettings& st = renderer.settings();
  const rt2::Accel& accel = compiled.accel;
  const rt2::BvhStats& b = accel.stats;
  j_ = {
      {"scene", o.scene.empty() ? "built-in" : o.scene},
      {"preset", o.preset},
      {"width", st.width},
      {"height", st.height},
      {"subpixels", st.subpixels},
      {"pattern", rt2::pattern_name(st.pattern)},
      {"depth", st.depth},
      {"min_weight", json_float(st.min_weight)},
      {"lights", compiled.lights.size()},
      {"leaf_size", o.bvh.max_leaf_size},
      {"split", o.bvh.split == rt2::Split::sah ? "sah" : "midpoint"},
      {"bvh", !o.no_bvh},
      {"backend", rt2::backend_name(o.schedule.backend)},
      {"threads", rt2::effective_threads(o.schedule)},
      {"grain", o.schedule.grain},
      {"frames", o.frames},
      {"isa", rt2::isa_name(renderer.isa())},
      {"triangle_test", st.watertight ? "watertight" : "fast"},
      {"features", rt2::feature_names(compiled.features)},
      {"passes", st.passes},
      {"block", st.block},
      {"packets", st.packets},
      {"shading_lanes", st.shading_lanes},
      {"light_culling", light_culling_name(st.light_culling)},
      {"light_lists", st.light_lists == rt2::LightLists::bvh ? "bvh" : "brute-force"},
      {"light_slices", st.light_slices},
      {"shadows", st.shadows},
      {"stage_times", st.stage_times},
      {"animate_lights", o.animate_lights},
      {"lights_with_range", compiled.lights.size() - compiled.light_bvh.unbounded().size()},
      {"light_bvh_levels", compiled.light_bvh.levels()},
      {"light_bvh_bytes", compiled.light_bvh.bytes()},
      {"tile", o.schedule.tile},
      {"time_budget_s", o.time_budget},
      {"triangles", accel.tris.size()},
      {"instances", accel.instances.size()},
      {"placed_triangles", scene.placed_triangle_count()},
      {"spheres", accel.spheres.size()},
      {"planes", accel.planes.size()},
      {"degenerate_triangles", scene.degenerate_triangles},
      {"scene_load_ms", load_ms},
      {"bvh_build_ms", compiled.times.accel_ms},
      {"compile_ms", build_ms},
      {"bvh_width", rt2::bvh_width(accel.isa)},
      {"bvh_nodes", accel.wide_nodes},
      {"bvh_leaves", b.leaves},
      {"bvh_depth", b.max_depth},
      {"bvh_bytes", accel.bvh_bytes()},
      {"rt2_version", rt2::kVersion},
      {"git_commit", rt2::git_commit()},
      {"compiler", rt2::compiler()},
      {"baseline_isa", rt2::build_isa()},
      {"machine", host_name()},
      {"cpu", rt2::cpu_model()},
      {"date", utc_now()},
  };
  std::size_t pbr = 0;
  for (const rt2::Material& m : compiled.materials) pbr += m.model == rt2::Shading::pbr;
  if (scene.animation >= 0) {
    const rt2::AnimationSummary& a = scene.animations[std::size_t(scene.animation)];
    j_["animation"] = {{"name", a.name}, {"index", scene.animation},
                       {"duration", a.duration}, {"time", o.pose.seconds}, {"fps", o.fps}};
  }
  j_["animations"] = scene.animations.size();
  j_["materials"] = compiled.materials.size();
  j_["materials_pbr"] = pbr;
  j_["textures"] = compiled.textures.size();
  j_["environment"] = !scene.environment ? "none"
                      : scene.environment->image.empty() ? "sky"
                                                         : scene.environment->image;
  j_["environment_ms"] = compiled.times.environment_ms;
  j_["brdf_table_ms"] = compiled.times.brdf_table_ms;
  j_["textures_ms"] = compiled.times.textures_ms;
  j_["allow_outside_assets"] = o.assets.allow_outside_assets;
  j_["max_texture_pixels"] = o.assets.max_image_pixels;
  j_["tonemap"] = rt2::tone_curve_name(o.display.curve);
  j_["exposure"] = json_float(o.display.exposure);
}

void Report::add_frame(const rt2::FrameResult& r, int passes) {
  passes_ = passes;
  nonfinite_ = r.nonfinite_pixels;
  frame_ms_.push_back(r.ms);
  rays_ = r.rays;  // identical every frame unless the lights move
  stages_.push_back(r.rays.stages);
}

double Report::median_ms() const { return median(frame_ms_); }

void Report::compare(const rt2::Image& image, const rt2::Image& reference) {
  const rt2::ImageError e = rt2::compare_images(image, reference);
  // JSON has no infinity: identical images report PSNR as null.
  j_["reference"] = {{"rmse", e.rmse},
                     {"psnr", std::isfinite(e.psnr) ? nlohmann::json(e.psnr) : nlohmann::json()},
                     {"ssim", e.ssim},
                     {"edge_rmse", e.edge_rmse},
                     {"edge_pixels", e.edge_pixels}};
}

void Report::print_setup() const {
  // "N triangles" or, with instances, "N triangles (M placed by K instances)"
  std::string placed;
  if (const auto k = j_["instances"].get<std::size_t>(); k > 0)
    placed = " (" + std::to_string(j_["placed_triangles"].get<std::size_t>()) + " placed by " +
             std::to_string(k) + " instances)";
  std::printf("scene %s: %zu triangles%s, %zu spheres, %zu planes, %zu lights; features %s; "
              "loaded in %.1f ms\n",
              printable(j_["scene"].get<std::string>()).c_str(),
              j_["triangles"].get<std::size_t>(), placed.c_str(),
              j_["spheres"].get<std::size_t>(), j_["planes"].get<std::size_t>(),
              j_["lights"].get<std::size_t>(), j_["features"].get<std::string>().c_str(),
              j_["scene_load_ms"].get<double>());
  if (j_["materials_pbr"].get<std::size_t>() > 0 || j_["environment"] != "none" ||
      j_["textures"].get<std::size_t>() > 0)
    std::printf("materials: %zu, %zu physically based (BRDF table %.1f ms); %zu textures "
                "(opened in %.1f ms); environment %s (loaded and prefiltered in %.1f ms)\n",
                j_["materials"].get<std::size_t>(), j_["materials_pbr"].get<std::size_t>(),
                j_["brdf_table_ms"].get<double>(), j_["textures"].get<std::size_t>(),
                j_["textures_ms"].get<double>(),
                printable(j_["environment"].get<std::string>()).c_str(),
                j_["environment_ms"].get<double>());
  if (j_.contains("animation")) {
    const nlohmann::json& a = j_["animation"];
    std::printf("animation %d '%s' of %zu, %.3f s long: frames from %.3f s, %g a second\n",
                a["index"].get<int>(), printable(a["name"].get<std::string>()).c_str(),
                j_["animations"].get<std::size_t>(), a["duration"].get<double>(),
                a["time"].get<double>(), a["fps"].get<double>());
  }
  if (j_["degenerate_triangles"].get<std::size_t>() > 0)
    std::printf("dropped %zu degenerate triangles\n", j_["degenerate_triangles"].get<std::size_t>());
  std::printf("bvh %s, leaf size %u, %d-wide: %u nodes, %u leaves, depth %u, %.1f MB, built in "
              "%.1f ms\n",
              j_["split"].get<std::string>().c_str(), j_["leaf_size"].get<unsigned>(),
              j_["bvh_width"].get<int>(), j_["bvh_nodes"].get<unsigned>(),
              j_["bvh_leaves"].get<unsigned>(), j_["bvh_depth"].get<unsigned>(),
              double(j_["bvh_bytes"].get<std::size_t>()) / 1e6, j_["bvh_build_ms"].get<double>());
  std::printf("%dx%d, %d subpixels (%s), depth %d, min-weight %g, %s kernels; %s, %d threads, "
              "grain %d\n",
              j_["width"].get<int>(), j_["height"].get<int>(), j_["subpixels"].get<int>(),
              j_["pattern"].get<std::string>().c_str(), j_["depth"].get<int>(),
              j_["min_weight"].get<double>(), j_["isa"].get<std::string>().c_str(),
              j_["backend"].get<std::string>().c_str(), j_["threads"].get<int>(),
              j_["grain"].get<int>());
}

void Report::print_summary() const {
  const nlohmann::json j = json();
  std::printf("fps median %.3f (min %.3f, max %.3f) over %zu frames; %.2f ms/frame median\n",
              j["fps_median"].get<double>(), j["fps_min"].get<double>(),
              j["fps_max"].get<double>(), frame_ms_.size(), j["frame_ms_median"].get<double>());
  std::printf("rays per frame: %llu primary, %llu shadow, %llu reflection, %llu refraction; "
              "%.2f Mrays/s\n",
              static_cast<unsigned long long>(rays_.primary),
              static_cast<unsigned long long>(rays_.shadow),
              static_cast<unsigned long long>(rays_.reflection),
              static_cast<unsigned long long>(rays_.refraction), j["mrays_per_s"].get<double>());
  const auto per_ray = [](const rt2::TraversalCounts& w, std::uint64_t rays) {
    return rays ? std::pair{double(w.nodes) / double(rays), 4.0 * double(w.blocks) / double(rays)}
                : std::pair{0.0, 0.0};
  };
  const auto [pn, pt] = per_ray(rays_.primary_walk, rays_.primary);
  const auto [sn, st] = per_ray(rays_.shadow_walk, rays_.shadow);
  const auto [rn, rtr] = per_ray(rays_.secondary_walk, rays_.reflection + rays_.refraction);
  std::printf("BVH nodes / triangles tested per ray: primary %.2f / %.2f, shadow %.2f / %.2f, "
              "secondary %.2f / %.2f\n", pn, pt, sn, st, rn, rtr);
  const auto in_packets = [](const rt2::TraversalCounts& w, std::uint64_t rays) {
    return rays ? 100.0 * double(w.packet_rays) / double(rays) : 0.0;
  };
  std::printf("rays walked in packets: primary %.1f %%, shadow %.1f %%, secondary %.1f %%\n",
              in_packets(rays_.primary_walk, rays_.primary),
              in_packets(rays_.shadow_walk, rays_.shadow),
              in_packets(rays_.secondary_walk, rays_.reflection + rays_.refraction));
  const rt2::LightCounts& l = rays_.lights;
  if (l.points > 0)
    std::printf("shading points shaded in SIMD lanes: %.1f %%\n",
                100.0 * double(l.in_lanes) / double(l.points));
  if (l.points > 0 && j["lights"].get<std::size_t>() > 0) {
    std::printf("lights per shading point: %.2f considered, %.2f in range (culling %s",
                double(l.considered) / double(l.points), double(l.in_range) / double(l.points),
                j["light_culling"].get<std::string>().c_str());
    if (l.lists > 0)
      std::printf("; %llu lists of %.1f lights", static_cast<unsigned long long>(l.lists),
                  double(l.list_entries) / double(l.lists));
    if (l.unoccluded > 0)
      std::printf("; %llu shadow rays proven unoccluded, not traced",
                  static_cast<unsigned long long>(l.unoccluded));
    std::printf(")\n");
  }
  if (j.contains("stage_ms")) {
    const auto& sm = j["stage_ms"];
    std::printf("stages, thread-ms per frame: generate %.2f, intersect %.2f, lights %.2f, shade "
                "%.2f, shadow %.2f, film %.2f\n",
                sm["generate"].get<double>(), sm["intersect"].get<double>(),
                sm["lights"].get<double>(), sm["shade"].get<double>(), sm["shadow"].get<double>(),
                sm["film"].get<double>());
  }
  if (j.contains("pose_ms"))
    std::printf("scene posed per frame: load %.2f ms, trees and lights %.2f ms (medians); "
                "trees refit %d, rebuilt after a refit %d, built %d times\n",
                j["pose_ms"]["load"].get<double>(), j["pose_ms"]["place"].get<double>(),
                j["pose_trees"]["refit"].get<int>(), j["pose_trees"]["rebuilt"].get<int>(),
                j["pose_trees"]["built"].get<int>());
  if (j.contains("light_update_ms")) {
    const auto& u = j["light_update_ms"];
    std::printf("light update per frame: %.2f ms (move and bounds %.2f, Morton %.2f, sort "
                "%.2f, tree %.2f)\n",
                u["total"].get<double>(), u["lights"].get<double>(),
                u["morton"].get<double>(), u["sort"].get<double>(), u["tree"].get<double>());
  }
  if (passes_ < j["passes"].get<int>())
    std::printf("time budget: %d of %d passes rendered\n", passes_, j["passes"].get<int>());
  if (nonfinite_ > 0)
    std::printf("warning: %llu pixels came out NaN or infinite and were written as black\n",
                static_cast<unsigned long long>(nonfinite_));
  print_ranks();
  if (j.contains("reference")) {
    const auto& r = j["reference"];
    std::printf("against reference: RMSE %.6f, PSNR %s dB, SSIM %.5f, edge RMSE %.6f over %zu "
                "edge pixels\n",
                r["rmse"].get<double>(),
                r["psnr"].is_null() ? "inf" : std::to_string(r["psnr"].get<double>()).c_str(),
                r["ssim"].get<double>(), r["edge_rmse"].get<double>(),
                r["edge_pixels"].get<std::size_t>());
  }
}

void Report::print_ranks() const {
  if (ranks_.empty()) return;
  std::printf("MPI: %zu processes; each one's tiles, render threads' busy time (share of their "
              "frame time) and bytes sent over %zu frames:\n", ranks_.size(), frame_ms_.size());
  for (const RankStats& r : ranks_) {
    std::printf("  rank %d (%s, %d threads): %llu tiles, %.1f thread-ms (%.0f %%), %.3f MB sent",
                r.rank, printable(r.host).c_str(), r.threads,
                static_cast<unsigned long long>(r.tiles),
                r.busy_ms, 100.0 * busy_share(r, frame_ms_), double(r.bytes_sent) / 1e6);
    if (r.rank == 0) std::printf("; serving messages %.2f ms", r.serve_ms);
    std::printf("\n");
  }
}

nlohmann::json Report::json() const {
  nlohmann::json j = j_;
  const double med = median_ms();
  const auto [lo, hi] = std::minmax_element(frame_ms_.begin(), frame_ms_.end());
  j["frame_ms"] = frame_ms_;
  j["frame_ms_median"] = med;
  j["fps_median"] = med > 0 ? 1000.0 / med : 0.0;
  j["fps_min"] = frame_ms_.empty() ? 0.0 : 1000.0 / *hi;
  j["fps_max"] = frame_ms_.empty() ? 0.0 : 1000.0 / *lo;
  j["rays_primary"] = rays_.primary;
  j["rays_shadow"] = rays_.shadow;
  j["rays_reflection"] = rays_.reflection;
  j["rays_refraction"] = rays_.refraction;
  j["rays_total"] = rays_.total();
  j["nonfinite_pixels"] = nonfinite_;
  j["passes_rendered"] = passes_;
  const auto walk = [](const rt2::TraversalCounts& w) {
    return nlohmann::json{{"nodes", w.nodes},
                          {"triangles", 4 * w.blocks},
                          {"packets", w.packets},
                          {"rays_in_packets", w.packet_rays}};
  };
  j["bvh_walks"] = {{"primary", walk(rays_.primary_walk)},
                    {"shadow", walk(rays_.shadow_walk)},
                    {"secondary", walk(rays_.secondary_walk)}};
  j["mrays_per_s"] = med > 0 ? double(rays_.total()) / (med * 1e3) : 0.0;
  const rt2::LightCounts& l = rays_.lights;
  j["light_counts"] = {{"shading_points", l.points},
                       {"considered", l.considered},
                       {"in_range", l.in_range},
                       {"lists", l.lists},
                       {"list_entries", l.list_entries},
                       {"unoccluded", l.unoccluded},
                       {"in_simd_lanes", l.in_lanes},
                       {"considered_in_simd_lanes", l.light_lanes}};
  const auto stage = [&](std::uint64_t rt2::StageTimes::*field) {
    return median_of(stages_, [&](const rt2::StageTimes& s) { return double(s.*field) * 1e-6; });
  };
  if (j_["stage_times"].get<bool>())
    j["stage_ms"] = {{"generate", stage(&rt2::StageTimes::generate)},
                     {"intersect", stage(&rt2::StageTimes::intersect)},
                     {"lights", stage(&rt2::StageTimes::lights)},
                     {"shade", stage(&rt2::StageTimes::shade)},
                     {"shadow", stage(&rt2::StageTimes::shadow)},
                     {"film", stage(&rt2::StageTimes::film)}};
  if (!ranks_.empty()) {
    j["mpi_processes"] = ranks_.size();
    j["mpi_ranks"] = nlohmann::json::array();
    for (const RankStats& r : ranks_)
      j["mpi_ranks"].push_back({{"rank", r.rank},
                                {"host", r.host},
                                {"threads", r.threads},
                                {"tiles", r.tiles},
                                {"busy_ms", r.busy_ms},
                                {"busy_share", busy_share(r, frame_ms_)},
                                {"bytes_sent", r.bytes_sent},
                                {"serve_ms", r.serve_ms}});
  }
  if (!poses_.empty()) {
    j["pose_ms"] = {{"load", median_of(poses_, [](const Pose& p) { return p.load_ms; })},
                    {"place", median_of(poses_, [](const Pose& p) { return p.place_ms; })}};
    using P = rt2::CompiledScene::Placed;
    const auto count = [&](P how) {
      return std::count_if(poses_.begin(), poses_.end(), [&](const Pose& p) { return p.placed == how; });
    };
    j["pose_trees"] = {{"built", count(P::built)}, {"refit", count(P::refit)},
                       {"rebuilt", count(P::rebuilt)}};
  }
  if (!light_updates_.empty()) {
    using B = rt2::LightBvh::BuildTimes;
    const auto step = [&](double B::*field) {
      return median_of(light_updates_, [&](const B& b) { return b.*field; });
    };
    j["light_update_ms"] = {
        {"lights", step(&B::lights_ms)},
        {"morton", step(&B::morton_ms)}, {"sort", step(&B::sort_ms)},
        {"tree", step(&B::tree_ms)},
        {"total", median_of(light_updates_, [](const B& b) { return b.total_ms(); })}};
  }
  return j;
}

}  // namespace rt2cpr
