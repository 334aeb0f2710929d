// rt2cpr/local_job.cpp — rt2cpr's frame loop (see local_job.h).
#include "rt2cpr/local_job.h"

#include <cstdio>

#include "rt2/base/error.h"
#include "rt2/render/schedule.h"
#include "rt2cpr/clock.h"
#include "rt2cpr/progress.h"

namespace rt2cpr {

void LocalJob::check(const Options& o) const {
  if (!o.rank0_renders)
    throw rt2::Error("--rank0 serve: one process renders every tile; rt2cpr_mpi's rank 0 can "
                     "serve");
}

void LocalJob::render_frames(const Options& o, RenderSetup& setup, Report& report,
                             rt2::Image& image, const FrameSink& each) {
  rt2::Film& film = setup.film;
  ProgressBar bar(!o.quiet);
  const int passes = o.render.passes;
  for (int f = 0; f < o.frames; ++f) {
    bar.start_frame(f, o.frames);
    if (f > 0) film.clear();
    rt2::FrameResult frame;
    const auto start = Clock::now();
    // The frame's pose of an animated scene, inside the frame's time.
    if (f > 0)
      if (const auto posed = setup.pose(o, f)) report.add_pose(posed->load_ms, posed->place_ms, posed->placed);
    // The frame's lights: moved and their tree rebuilt, inside the frame's time.
    if (o.animate_lights)
      report.add_light_update(
          setup.compiled.move_lights(frame_seconds(o, f), rt2::effective_threads(o.schedule)));
    int done = 0;
    double last_pass_ms = 0.0;
    for (int p = 0; p < passes; ++p) {
      // --time-budget: the next pass only if it fits, guessing it takes as long as the last.
      if (p > 0 && o.time_budget > 0.0 && ms_since(start) + last_pass_ms > o.time_budget * 1e3)
        break;
      const rt2::FrameResult r =
          rt2::render_pass(setup.renderer, o.schedule, film, p,
                           [&](int d, int n) { bar.update(p * n + d, passes * n); });
      frame.rays += r.rays;
      frame.portions = r.portions;
      last_pass_ms = r.ms;
      ++done;
      if (!o.quiet && passes > 1 && o.frames == 1)
        std::printf("pass %d of %d: %.2f ms\n", p + 1, passes, r.ms);
    }
    frame.ms = ms_since(start);
    frame.nonfinite_pixels = film.resolve(image);
    bar.end_frame();
    report.add_frame(frame, done);
    if (!o.quiet && o.frames > 1) std::printf("frame %d: %.2f ms\n", f + 1, frame.ms);
    each(f, image);
  }
}

}  // namespace rt2cpr
