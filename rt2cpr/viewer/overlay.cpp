// rt2cpr/viewer/overlay.cpp — the panel's widgets.
#include "rt2cpr/viewer/overlay.h"

#include <imgui.h>

#include <algorithm>
#include <thread>

#include "rt2/render/supersampling.h"

namespace rt2cpr::viewer {

bool draw_overlay(Controls& c, const OverlayInfo& info) {
  ImGui::SetNextWindowPos(ImVec2(8, 8), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowBgAlpha(0.75f);
  ImGui::Begin("rt2", nullptr, ImGuiWindowFlags_AlwaysAutoResize);
  const double mrays = info.render_ms > 0.0 ? double(info.rays.total()) / (info.render_ms * 1e3) : 0.0;
  ImGui::Text("%.1f fps  %.1f ms  %.1f Mrays/s", info.fps, info.render_ms, mrays);
  if (info.moving)
    ImGui::Text("moving: %dx%d (1/%d), 1 sample", info.width, info.height, info.scale);
  else
    ImGui::Text("still: %dx%d, pass %d of %d", info.width, info.height, info.pass, info.passes);
  ImGui::Text("rays: %llu primary, %llu shadow", (unsigned long long)info.rays.primary,
              (unsigned long long)info.rays.shadow);
  ImGui::Text("      %llu reflection, %llu refraction", (unsigned long long)info.rays.reflection,
              (unsigned long long)info.rays.refraction);
  ImGui::Text("%s kernels, %s, %d threads, speed %.3g/s", rt2::isa_name(info.isa),
              rt2::backend_name(c.schedule.backend), rt2::effective_threads(c.schedule),
              double(info.speed));
  if (!info.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", info.error.c_str());
  ImGui::Separator();

  // Values typed in (Ctrl+click) are clamped too: a setting out of range would fail every
  // request.
  constexpr ImGuiSliderFlags clamp = ImGuiSliderFlags_AlwaysClamp;
  bool changed = false;
  rt2::RenderSettings& s = c.settings;
  changed |= ImGui::SliderInt("depth", &s.depth, 0, 32, "%d", clamp);
  changed |= ImGui::SliderFloat("min-weight", &s.min_weight, 0.0f, 1.0f, "%.3f", clamp);
  if (ImGui::SliderInt("subpixels", &s.subpixels, 1, 64, "%d", clamp)) {
    s.passes = 1;
    changed = true;
  }
  static const char* const patterns[] = {"grid", "circle"};
  int pattern = s.pattern == rt2::Pattern::grid ? 0 : 1;
  if (ImGui::Combo("pattern", &pattern, patterns, 2)) {
    s.pattern = rt2::parse_pattern(patterns[pattern]);
    changed = true;
  }
  int lights = c.lights;
  if (ImGui::InputInt("lights (-1: scene's)", &lights, 1, 10, ImGuiInputTextFlags_EnterReturnsTrue)) {
    c.lights = std::clamp(lights, -1, 1'000'000);
    changed = true;
  }
  static const char* const tests[] = {"fast", "watertight"};
  int test = s.watertight ? 1 : 0;
  if (ImGui::Combo("triangle test", &test, tests, 2)) {
    s.watertight = test == 1;
    changed = true;
  }
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  int threads = rt2::effective_threads(c.schedule);
  if (ImGui::SliderInt("threads", &threads, 1, 2 * hardware, "%d", clamp)) {
    c.schedule.threads = threads;
    changed = true;
  }
  static const char* const backends[] = {"serial", "omp", "tbb"};
  int backend = int(c.schedule.backend);
  if (ImGui::Combo("backend", &backend, backends, 3)) {
    c.schedule.backend = rt2::parse_backend(backends[backend]);
    changed = true;
  }
  ImGui::Separator();
  ImGui::Text("WASD/arrows move, Q/E down/up, Shift faster, drag to look,\n"
              "wheel: speed, R reset, C print camera, %s save image,\n"
              "F1 this panel, Esc quit", info.screenshot_key.c_str());
  ImGui::End();
  return changed;
}

}  // namespace rt2cpr::viewer
