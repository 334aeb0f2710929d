// The render core (render.h): tiles, blocks, passes and the staged batches give the same
// image bits whatever their sizes; a progressive render of P passes equals one pass; and the
// batched, breadth-first kernel computes what a plain depth-first Whitted tracer computes,
// up to the order in which each sample's terms are summed.
#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <stop_token>
#include <string>
#include <utility>
#include <vector>

#include "rt2/scene/builtin_scene.h"
#include "rt2/render/compiled_scene.h"
#include "rt2/image/image_compare.h"
#include "rt2/geometry/offset.h"
#include "rt2/geometry/optics.h"
#include "rt2/render/schedule.h"
#include "rt2/scene/shapes.h"
#include "rt2/render/trace.h"
#include "tests/rt2/test_util.h"

namespace rt2 {
namespace {

RenderSettings settings(int subpixels, int passes, int block = 16) {
  RenderSettings st;
  st.width = 48;
  st.height = 36;
  st.subpixels = subpixels;
  st.depth = 6;
  st.passes = passes;
  st.block = block;
  return st;
}

bool identical(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height &&
         std::memcmp(a.rgb.data(), b.rgb.data(), a.rgb.size() * sizeof(float)) == 0;
}

TEST(RenderCore, TilesBlocksPassesAndBackendsGiveIdenticalImages) {
  const Scene s = test::glass_scene();
  const Image ref = test::render_scene(s, settings(4, 1));
  for (int tile : {0, 1, 7, 16, 100})
    for (int block : {1, 5, 16, 256})
      for (int passes : {1, 3, 4})
        for (Backend b : {Backend::serial, Backend::omp, Backend::tbb}) {
          const Image img = test::render_scene(s, settings(4, passes, block), Schedule{b, 2, 3, tile});
          ASSERT_TRUE(identical(ref, img)) << "tile " << tile << " block " << block << " passes "
                                           << passes << " " << backend_name(b);
        }
}

// Packets (RenderSettings::packets) change how rays walk the BVH, never what they find:
// the image is the same bits with them on or off, on every instruction set, with both
// triangle tests, for glass that shadow rays cross (transmittance through triangles and
// spheres), mirrors, supersampling and blocks that are not multiples of 4.
TEST(RenderCore, PacketsOnOrOffGiveIdenticalImagesOnEveryIsaAndTest) {
  Scene s = test::glass_scene();
  Material glass = s.materials[s.sphere_materials.back()];
  glass.transparency = 0.6f;
  const std::uint32_t g = s.add_material("mesh glass", glass);
  s.meshes.push_back(make_icosphere(vec4(0.5f, 0.35f, 0.3f), 0.35f, 3, g));
  for (Isa isa : test::runnable_isas())
    for (bool watertight : {false, true})
      for (int block : {16, 7}) {
        RenderSettings st = settings(2, 1, block);
        st.watertight = watertight;
        st.packets = false;
        FrameResult single, packed;
        const Image ref = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, isa, &single);
        st.packets = true;
        const Image img = test::render_scene(s, st, {Backend::serial, 1, 1}, {}, isa, &packed);
        const std::string what = std::string(isa_name(isa)) + " watertight " +
                                 std::to_string(watertight) + " block " + std::to_string(block);
        EXPECT_TRUE(identical(ref, img)) << what;
        EXPECT_EQ(single.rays.total(), packed.rays.total()) << what;
        // The property is the packet walk's: most primary and shadow rays must take it.
        EXPECT_EQ(single.rays.primary_walk.packet_rays, 0u) << what;
        EXPECT_GT(packed.rays.primary_walk.packet_rays, packed.rays.primary / 2) << what;
        EXPECT_GT(packed.rays.shadow_walk.packet_rays, packed.rays.shadow / 4) << what;
      }
}

// A scene at the numbers' edges for the shading lanes: a quad 1e9 away whose normal's
// square overflows and one 1e-12 away whose square underflows (normalize's rescaling path),
// a checker plane whose cells run past 2^24 towards the horizon, a mirror sphere,
// a textured-free glass cube (refraction: the one-hit step, in the same passes), a light
// with a range (its window), one beyond float's reach (never in range) and an ordinary one.
Scene lanes_edge_scene() {
  Scene s;
  s.camera = Camera::look_at(vec4(0, 0, 0), vec4(0.05f, -0.1f, -1), vec4(0, 1, 0), 60.0f);
  s.ambient = vec4(0.1f, 0.1f, 0.1f);
  s.background = vec4(0.2f, 0.3f, 0.4f);
  Material far_wall;
  far_wall.diffuse = vec4(0.6f, 0.5f, 0.4f);
  Material tiny;
  tiny.specular = vec4(0.7f, 0.7f, 0.7f);
  tiny.shininess = 33.0f;
  tiny.reflectivity = 0.5f;
  Material mirror;
  mirror.diffuse = vec4(0.1f, 0.1f, 0.1f);
  mirror.specular = vec4(0.9f, 0.9f, 0.9f);
  mirror.reflectivity = 0.8f;
  Material checker;
  checker.diffuse2 = vec4(0.1f, 0.2f, 0.9f);
  checker.checker_scale = 1e-4f;
  checker.specular = vec4(0.3f, 0.0f, 0.0f);
  checker.reflectivity = 0.3f;
  Material glass;
  glass.transparency = 0.7f;
  glass.ior = 1.4f;
  glass.reflectivity = 0.1f;
  const std::uint32_t wall = s.add_material("wall", far_wall), small = s.add_material("tiny", tiny),
                      mir = s.add_material("mirror", mirror), chk = s.add_material("checker", checker),
                      gl = s.add_material("glass", glass);
  const auto quad = [&](float z, float lo_x, float hi_x, float lo_y, float hi_y, std::uint32_t m) {
    Mesh q;
    q.name = "quad";
    q.positions = {vec4(lo_x, lo_y, z), vec4(hi_x, lo_y, z), vec4(hi_x, hi_y, z), vec4(lo_x, hi_y, z)};
    q.faces = {{0, 1, 2}, {0, 2, 3}};
    q.face_materials = {m, m};
    s.meshes.push_back(q);
  };
  quad(-1e9f, -5e9f, 5e9f, -5e9f, 5e9f, wall);       // |n|^2 = 1e40 overflows
  quad(-1e-12f, 0.0f, 1e-12f, -1e-12f, 0.0f, small);  // |n|^2 = 1e-48 underflows
  s.meshes.push_back(make_cube(vec4(-0.6f, -0.5f, -3.0f), 0.3f, gl));
  s.meshes.push_back(make_icosphere(vec4(0.7f, -0.4f, -2.5f), 0.4f, 2, mir));
  s.spheres.push_back(Sphere{vec4(0.2f, 0.1f, -2.2f), 0.35f});
  s.sphere_materials.push_back(mir);
  s.planes.push_back(Plane{vec4(0, 1, 0), 1.0f});
  s.plane_materials.push_back(chk);
  s.lights.push_back(Light{vec4(2, 5, 1), vec4(1, 1, 1), 0.8f});
  s.lights.push_back(Light{vec4(-1, 0.5f, -2), vec4(1, 0.5f, 0.2f), 1.0f, 4.0f});
  s.lights.push_back(Light{vec4(1e20f, 1e20f, 1e20f), vec4(1, 1, 1), 1.0f});
  return s;
}

// Forked paths with several lights: a glass pane (refraction and reflection from every hit)
// inside a room of plain Phong walls, lit by three lights, so that a pass of the next
// depth holds two rays of one sample, both shaded in lanes.
Scene glass_pane_room() {
  Scene s;
  s.camera = Camera::look_at(vec4(0.1f, 0.2f, 1.5f), vec4(0, 0, -1), vec4(0, 1, 0), 50.0f);
  s.ambient = vec4(0.1f, 0.1f, 0.1f);
  Material wall;
  wall.diffuse = vec4(0.7f, 0.6f, 0.5f);
  wall.diffuse2 = vec4(0.2f, 0.3f, 0.8f);
  wall.checker_scale = 0.3f;
  wall.specular = vec4(0.3f, 0.3f, 0.3f);
  wall.shininess = 17.0f;
  Material glass;
  glass.transparency = 0.55f;
  glass.reflectivity = 0.45f;
  glass.ior = 1.33f;
  const std::uint32_t w = s.add_material("wall", wall), g = s.add_material("glass", glass);
  s.meshes.push_back(make_cube(vec4(0, 0, 0), 3.0f, w));  // seen from inside
  Mesh pane;
  pane.name = "pane";
  pane.positions = {vec4(-1.5f, -1.2f, -0.5f), vec4(1.5f, -1.2f, -0.7f), vec4(1.5f, 1.2f, -0.7f),
                    vec4(-1.5f, 1.2f, -0.5f)};
  pane.faces = {{0, 1, 2}, {0, 2, 3}};
  pane.face_materials = {g, g};
  s.meshes.push_back(pane);
  s.lights.push_back(Light{vec4(1.1f, 2.1f, 1.3f), vec4(1, 0.9f, 0.8f), 0.7f});
  s.lights.push_back(Light{vec4(-2.2f, 1.7f, -2.1f), vec4(0.6f, 0.7f, 1.0f), 0.9f});
  s.lights.push_back(Light{vec4(0.3f, -2.5f, 2.2f), vec4(0.3f, 1.0f, 0.4f), 0.37f});
  return s;
}

// Hits from behind: the camera inside a mirror shell of flat triangles (no vertex normals
// anywhere in the scene) holding the built-in scene's content, made flat too; or inside a
// mirror sphere holding a flat icosahedron. Every normal the lanes meet there is flipped.
Scene inside_mirror(bool shell) {
  Scene s = make_default_scene();
  for (Mesh& m : s.meshes) m.normals.clear();
  Material mirror;
  mirror.diffuse = vec4(0.2f, 0.3f, 0.2f);
  mirror.specular = vec4(0.5f, 0.5f, 0.5f);
  mirror.reflectivity = 0.7f;
  const std::uint32_t m = s.add_material("inside mirror", mirror);
  const vec4 eye = s.camera.position();
  if (shell) {
    Mesh ball = make_icosphere(eye, 40.0f, 2, m);
    ball.normals.clear();
    s.meshes.push_back(ball);
  } else {
    s.meshes.clear();
    s.planes.clear();
    s.plane_materials.clear();
    s.spheres.push_back(Sphere{eye, 3.0f});
    s.sphere_materials.push_back(m);
    Mesh ico = make_icosphere(eye + s.camera.forward() * 1.5f, 0.5f, 0, m);
    ico.normals.clear();
    s.meshes.push_back(ico);
    s.lights = {Light{eye + vec4(0.5f, 1.0f, 0.2f), vec4(1, 1, 1), 1.0f}};
  }
  return s;
}

// `scene` rendered with the shading lanes on and off (every hit considering every light, at
// `depth`), on every instruction set and with both triangle tests: the same image, rays and
// light counts; with `lanes_expected`, most shading points taken by the lanes, else none.
void expect_lanes_match_one_by_one(const Scene& scene, int depth, bool lanes_expected,
                                   const std::string& name) {
  for (Isa isa : test::runnable_isas())
    for (bool watertight : {false, true}) {
      RenderSettings st = settings(2, 1, 7);
      st.depth = depth;
      st.watertight = watertight;
      st.light_culling = LightCulling::none;  // every hit considers every light
      st.shading_lanes = false;
      FrameResult one, lanes;
      const Image ref = test::render_scene(scene, st, {Backend::serial, 1, 1}, {}, isa, &one);
      st.shading_lanes = true;
      const Image img = test::render_scene(scene, st, {Backend::serial, 1, 1}, {}, isa, &lanes);
      const std::string what =
          name + " " + isa_name(isa) + " watertight " + std::to_string(watertight);
      EXPECT_TRUE(identical(ref, img)) << what;
      EXPECT_EQ(one.rays.total(), lanes.rays.total()) << what;
      EXPECT_EQ(one.rays.lights.in_range, lanes.rays.lights.in_range) << what;
      EXPECT_EQ(one.rays.lights.points, lanes.rays.lights.points) << what;
      EXPECT_EQ(one.rays.lights.considered, lanes.rays.lights.considered) << what;
      // The property is the lanes': most hits must take them where they can.
      EXPECT_EQ(one.rays.lights.in_lanes, 0u) << what;
      if (lanes_expected)
        EXPECT_GT(lanes.rays.lights.in_lanes, lanes.rays.lights.points / 2) << what;
      else
        EXPECT_EQ(lanes.rays.lights.in_lanes, 0u) << what;
    }
}

// The shading lanes (RenderSettings::shading_lanes) compute what the one-hit step
// computes: the image is the same bits with them on or off, on every instruction set, with
// both triangle tests, supersampling and deep mirrors; with lights up to the lanes' limit
// (and beyond it, where every hit takes the one-hit step) and none; on glass, whose hits
// take the one-hit step between lanes of the same pass; at the numbers' edges; from behind;
// where a pass's hits are all on one primitive; where paths fork and a pass holds two rays
// of one sample, with several lights.
TEST(RenderCore, ShadingLanesOnOrOffGiveIdenticalImagesOnEveryIsaAndAtTheEdges) {
  Scene glass = test::glass_scene();
  Material g = glass.materials[glass.sphere_materials.back()];
  g.transparency = 0.6f;
  glass.meshes.push_back(make_icosphere(vec4(0.5f, 0.35f, 0.3f), 0.35f, 3,
                                        glass.add_material("mesh glass", g)));
  struct Case {
    const char* name;
    Scene scene;
    std::size_t lights;  // 0: the scene's own
    bool lanes_expected;
  };
  std::vector<Case> cases;
  cases.push_back({"glass", glass, 0, true});
  cases.push_back({"edges", lanes_edge_scene(), 0, true});
  cases.push_back({"inside a shell", inside_mirror(true), 0, true});
  cases.push_back({"inside a sphere", inside_mirror(false), 0, true});
  cases.push_back({"glass pane in a room", glass_pane_room(), 0, true});
  for (std::size_t lights : {0u, 1u, 8u, 9u}) {
    Scene s = make_default_scene();
    if (lights == 0)
      s.lights.clear();
    else
      set_light_count(s, lights);
    cases.push_back({"built-in", s, lights, lights <= 8});
  }
  // Every lane of most passes on one primitive (the lanes take its data once), with a plane
  // whose D is not 0.
  Scene lowered = make_default_scene();
  lowered.planes[0].d = 0.1f;
  cases.push_back({"built-in, floor lowered", lowered, 1, true});
  for (const Case& c : cases)
    expect_lanes_match_one_by_one(c.scene, 10, c.lanes_expected,
                                  std::string(c.name) + " lights " + std::to_string(c.lights));
}

// The built-in scene in physically based materials, for the PBR lanes: the chair a smooth
// metal (roughness 0: mirror rays), the sphere at exactly the mirror threshold, and a row of
// spheres from rough dielectric to rough metal, one emissive, one transmissive (shaded one
// by one between lanes of its pass), an icosphere with vertex normals and a Phong floor
// (passes that mix the models), or with `pbr_floor` a rough physically based floor (every
// lane a PBR one); under a rotated sky, or none (a uniform environment).
Scene pbr_lanes_scene(bool sky, bool pbr_floor = false) {
  Scene s = make_default_scene();
  const auto pbr = [](vec4 base, float metallic, float roughness) {
    Material m;
    m.model = Shading::pbr;
    m.base_color = base;
    m.metallic = metallic;
    m.roughness = roughness;
    return m;
  };
  s.materials[s.sphere_materials[0]] = pbr(vec4(0.9f, 0.6f, 0.3f), 1.0f, 0.0f);  // the chair's too
  s.sphere_materials[0] = s.add_material("threshold", pbr(vec4(0.7f, 0.7f, 0.8f), 0.3f, 0.05f));
  Material glowing = pbr(vec4(0.2f, 0.8f, 0.3f), 0.0f, 0.6f);
  glowing.emissive = vec4(0.4f, 0.2f, 0.1f);
  Material clear = pbr(vec4(0.9f, 0.9f, 1.0f), 0.0f, 0.0f);
  clear.transmission = 1.0f;
  const Material row[] = {pbr(vec4(0.8f, 0.3f, 0.2f), 0.0f, 1.0f), pbr(vec4(0.5f, 0.5f, 0.5f), 0.5f, 0.3f),
                          pbr(vec4(0.9f, 0.8f, 0.2f), 1.0f, 0.7f), glowing, clear,
                          pbr(vec4(0.3f, 0.4f, 0.9f), 0.0f, 0.0501f)};
  for (std::size_t i = 0; i < std::size(row); ++i) {
    s.spheres.push_back({vec4(-0.6f + 0.3f * float(i), 0.12f, -0.7f), 0.12f});
    s.sphere_materials.push_back(s.add_material("row " + std::to_string(i), row[i]));
  }
  s.meshes.push_back(make_icosphere(vec4(-0.45f, 0.2f, 0.35f), 0.2f, 2,
                                    s.add_material("ico", pbr(vec4(0.6f, 0.9f, 0.6f), 0.2f, 0.4f))));
  if (sky) s.environment = EnvironmentDesc{"", 1.3f, 37.0f, vec4(0.4f, 0.6f, -0.5f)};
  if (pbr_floor) s.materials[s.plane_materials[0]] = pbr(vec4(0.6f, 0.6f, 0.55f), 0.0f, 0.8f);
  return s;
}

// The PBR shading lanes (pbr_lanes.h) compute what pbr.h computes for one hit: the image is
// the same bits with the lanes on or off, on every instruction set, with both triangle
// tests, at the depth limit (mirrors show the prefiltered map) and deeper, under a sky or
// none, with 0, 1, 8 and 9 lights (9: every hit one by one), lights with a range, and from
// inside a smooth sphere (every normal flipped).
TEST(RenderCore, PbrShadingLanesOnOrOffGiveIdenticalImagesOnEveryIsaAndAtTheEdges) {
  struct Case {
    std::string name;
    Scene scene;
    int depth;
    bool lanes_expected;
  };
  std::vector<Case> cases;
  for (bool sky : {false, true})
    for (int depth : {1, 8}) cases.push_back({"sky " + std::to_string(sky), pbr_lanes_scene(sky), depth, true});
  // no Phong material: the lanes that most points take are PBR ones
  cases.push_back({"all pbr", pbr_lanes_scene(true, true), 4, true});
  for (std::size_t lights : {0u, 8u, 9u}) {
    Scene s = pbr_lanes_scene(true);
    if (lights == 0)
      s.lights.clear();
    else
      set_light_count(s, lights);
    cases.push_back({"lights " + std::to_string(lights), s, 4, lights <= 8});
  }
  {
    Scene s = pbr_lanes_scene(true);
    s.lights[0].range = 4.0f;  // the window at every lit point, zero beyond
    s.lights.push_back(Light{vec4(-0.5f, 0.6f, 0.2f), vec4(0.3f, 0.5f, 1.0f), 0.8f, 0.7f});
    cases.push_back({"ranged lights", s, 4, true});
  }
  {
    Scene s = inside_mirror(false);
    for (std::uint32_t m : s.sphere_materials) {
      s.materials[m].model = Shading::pbr;
      s.materials[m].metallic = 1.0f;
      s.materials[m].roughness = 0.0f;
    }
    s.environment = EnvironmentDesc{};
    cases.push_back({"inside a smooth sphere", s, 6, true});
  }
  for (const Case& c : cases)
    expect_lanes_match_one_by_one(c.scene, c.depth, c.lanes_expected,
                                  c.name + " depth " + std::to_string(c.depth));
}

TEST(RenderCore, EightPassesOfOneSampleEqualOnePassOfEight) {
  for (Pattern pattern : {Pattern::grid, Pattern::circle}) {
    RenderSettings one = settings(8, 1), eight = settings(8, 8);
    one.pattern = eight.pattern = pattern;
    EXPECT_TRUE(identical(test::render_scene(test::glass_scene(), one),
                          test::render_scene(test::glass_scene(), eight)));
  }
}

TEST(RenderCore, AFilmHoldsThePassesSoFarAndTheirMeanIsAValidImage) {
  const Scene s = test::glass_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, settings(4, 4)});
  Film film(48, 36);
  const FrameResult first = render_pass(r, Schedule{Backend::serial, 1, 1}, film, 0);
  EXPECT_EQ(film.samples(0, 0), 1u);
  EXPECT_EQ(first.rays.primary, 48u * 36u);
  Image partial;
  EXPECT_EQ(film.resolve(partial), 0u);
  render_pass(r, Schedule{Backend::serial, 1, 1}, film, 1);
  EXPECT_EQ(film.samples(47, 35), 2u);
  // One sample's mean is its own colour, two samples' a different image, both finite.
  Image two;
  film.resolve(two);
  EXPECT_FALSE(identical(partial, two));
  for (float v : two.rgb) EXPECT_TRUE(std::isfinite(v));
}

// A pass asked to stop renders no tile it has not started: stopped before it begins, the
// film gains no sample and the result says it is not complete; the same pass unstopped is
// complete and fills every pixel.
TEST(RenderCore, AStoppedPassSkipsItsTilesAndSaysItIsIncomplete) {
  const Scene s = test::glass_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, settings(2, 2)});
  for (Backend b : {Backend::serial, Backend::omp, Backend::tbb}) {
    Film film(48, 36);
    std::stop_source stop;
    stop.request_stop();
    const FrameResult stopped = render_pass(r, Schedule{b, 2, 4, 8}, film, 0, {}, stop.get_token());
    EXPECT_FALSE(stopped.complete) << backend_name(b);
    EXPECT_EQ(stopped.rays.primary, 0u);
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x) ASSERT_EQ(film.samples(x, y), 0u);
    const FrameResult whole = render_pass(r, Schedule{b, 2, 4, 8}, film, 0, {}, std::stop_source().get_token());
    EXPECT_TRUE(whole.complete);
    for (int y = 0; y < 36; ++y)
      for (int x = 0; x < 48; ++x) ASSERT_EQ(film.samples(x, y), 1u);
  }
}

// Stopped from the progress callback after the first tile, a pass keeps the tiles it
// rendered whole (every pixel of a tile has its sample or none) and skips the rest.
TEST(RenderCore, AStopMidPassLeavesWholeTilesOnly) {
  const Scene s = test::glass_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, settings(1, 1)});
  Film film(48, 36);
  std::stop_source stop;
  const Schedule sched{Backend::serial, 1, 1, 8};
  const FrameResult f = render_pass(r, sched, film, 0, [&](int, int) { stop.request_stop(); },
                                    stop.get_token());
  EXPECT_FALSE(f.complete);
  int filled = 0;
  for (const Tile& t : make_tiles(sched, 48, 36)) {
    const std::uint32_t first = film.samples(t.x0, t.y0);
    for (int y = t.y0; y < t.y1; ++y)
      for (int x = t.x0; x < t.x1; ++x) ASSERT_EQ(film.samples(x, y), first);
    filled += first == 1;
  }
  EXPECT_EQ(filled, 1);
}

// An MPI job resolves each tile where it was rendered (rt2cpr/mpi/): a tile's means are the
// whole film's bits for those pixels, and clearing it empties those pixels alone.
TEST(RenderCore, ATileResolvesToTheWholeFilmsBitsAndClearsAlone) {
  const Scene s = test::glass_scene();
  const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
  const Renderer r(c, View{s.camera, settings(3, 1)});
  Film film(48, 36);
  render_pass(r, Schedule{Backend::serial, 1, 1}, film, 0);
  Image whole;
  film.resolve(whole);
  const Tile tile{5, 7, 30, 19};
  std::vector<float> rgb(tile.pixels() * 3);
  EXPECT_EQ(film.resolve(tile, rgb.data()), 0u);
  for (int y = tile.y0; y < tile.y1; ++y)
    ASSERT_EQ(std::memcmp(&rgb[3 * std::size_t((y - tile.y0) * tile.width())],
                          whole.pixel(tile.x0, y), std::size_t(tile.width()) * 3 * sizeof(float)),
              0) << "row " << y;
  film.clear(tile);
  EXPECT_EQ(film.samples(tile.x0, tile.y0), 0u);
  EXPECT_EQ(film.samples(tile.x1 - 1, tile.y1 - 1), 0u);
  EXPECT_EQ(film.samples(tile.x0 - 1, tile.y0), 3u);
  EXPECT_EQ(film.samples(tile.x1, tile.y1 - 1), 3u);
  EXPECT_EQ(film.samples(tile.x0, tile.y1), 3u);
}

// ---- a depth-first Whitted tracer over the public queries: the oracle --------------------

// Transparency of everything on the segment (0, t_max), each surface crossing counted, by
// testing every primitive (brute force), as rt2/kernel/closest_hit.h defines it.
float transmittance_brute(const CompiledScene& c, const Ray& r, float t_max) {
  const Accel& a = c.accel;
  float tr = 1.0f;
  const auto cross = [&](std::uint32_t m) { tr *= c.materials[m].transparency; };
  for (std::uint32_t i = 0; i < a.planes.size(); ++i) {
    float t;
    if (intersect(a.planes[i], r, 0.0f, t_max, t)) cross(a.plane_materials[i]);
  }
  for (std::uint32_t i = 0; i < a.spheres.size(); ++i) {
    float t, t2;
    if (!intersect(a.spheres[i], r, 0.0f, t_max, t)) continue;
    cross(a.sphere_materials[i]);
    if (intersect(a.spheres[i], r, t, t_max, t2)) cross(a.sphere_materials[i]);
  }
  for (std::uint32_t i = 0; i < a.tris.size(); ++i) {
    float t, u, v;
    if (intersect(a.tris[i], r, 0.0f, t_max, t, u, v)) cross(a.tri_materials[i]);
  }
  return tr;
}

vec4 trace_depth_first(const CompiledScene& c, const RenderSettings& st, const Ray& ray,
                       float weight, int depth) {
  const Hit h = trace_closest(c.accel, ray);
  if (!h.found()) return weight * c.background;
  // The surface, as the kernel finds it (rt2/kernel/surface_point.h).
  const Accel& a = c.accel;
  vec4 p, ng, ns;
  const std::uint32_t i = prim_index(h.prim);
  if (prim_tag(h.prim) == kTriangleTag) {
    p = a.tris[i].point(h.u, h.v);
    ng = ns = normalize(a.tris[i].n);
    if (!a.tri_normals.empty()) {
      const auto& n = a.tri_normals[i];
      ns = normalize((1.0f - h.u - h.v) * n[0] + h.u * n[1] + h.v * n[2]);
    }
  } else if (prim_tag(h.prim) == kSphereTag) {
    ng = ns = sphere_normal(a.spheres[i], ray.at(h.t));
    p = a.spheres[i].center + ng * a.spheres[i].radius;
  } else {
    const vec4 q = ray.at(h.t);
    p = q - a.planes[i].n * (float(dot(q, a.planes[i].n)) + a.planes[i].d);
    ng = ns = a.planes[i].n;
  }
  const bool entering = dot(ray.dir, ng) < 0.0f;
  if (!entering) ng = -ng, ns = -ns;
  if (!(dot(ns, ray.dir) < 0.0f)) ns = ng;  // an interpolated normal facing away
  const vec4 above = offset_ray_origin(p, ng, c.offset_scale);
  const Material& m = c.materials[a.material_of(h.prim)];
  vec4 color = m.ambient * c.ambient;
  for (const Light& light : c.lights) {
    const vec4 to = light.position - above;
    const float dist = std::sqrt(float(dot(to, to)));
    const vec4 l = to / dist;
    const float n_dot_l = dot(ns, l);
    if (!(dot(l, ng) > 0.0f) || !(n_dot_l > 0.0f)) continue;
    const float passed = transmittance_brute(c, Ray(above, l), dist);
    vec4 term = m.diffuse_at(p + c.origin) * n_dot_l;
    const float r_dot_v = dot(2.0f * n_dot_l * ns - l, -ray.dir);
    if (m.has_specular() && r_dot_v > 0.0f) term += m.specular * std::pow(r_dot_v, m.shininess);
    color += term * light.radiance() * passed;
  }
  color = weight * color;
  if (depth >= st.depth) return color;
  if (m.transparency > 0.0f && weight * m.transparency > st.min_weight) {
    vec4 t;
    if (refract(ray.dir, ns, entering ? 1.0f / m.ior : m.ior, t))
      color += trace_depth_first(c, st, Ray(offset_ray_origin(p, -ng, c.offset_scale), t),
                                 weight * m.transparency, depth + 1);
    else
      color += trace_depth_first(c, st, Ray(above, reflect(ray.dir, ns)), weight * m.transparency,
                                 depth + 1);
  }
  if (m.reflectivity > 0.0f && weight * m.reflectivity > st.min_weight)
    color += trace_depth_first(c, st, Ray(above, reflect(ray.dir, ns)), weight * m.reflectivity,
                               depth + 1);
  return color;
}

// The kernel's primary rays (written a whole 4 x 4 packet at a time in SIMD, short packets
// at a block's edges row by row) are Camera::ray's, bit for bit, origin and direction with
// their w lanes, each with its sample's index; for cameras near and far from the origin, of
// narrow and wide views, with one subpixel and four on a circle, on every instruction set.
TEST(RenderCore, PrimaryRaysEqualCameraRayBitForBitOnEveryIsa) {
  const auto same = [](const vec4& a, const vec4& b) {
    for (int k = 0; k < 4; ++k)
      if (std::bit_cast<std::uint32_t>(a[k]) != std::bit_cast<std::uint32_t>(b[k])) return false;
    return true;
  };
  const Camera cameras[] = {
      make_default_scene().camera,
      Camera::look_at(vec4(1e6f, -3e5f, 2e7f), vec4(1e6f + 1.0f, -3e5f, 2e7f - 4.0f), vec4(0, 1, 0), 1.0f),
      Camera::look_at(vec4(0, 0, 0), vec4(0.3f, -0.2f, -1.0f), vec4(0.1f, 1.0f, 0.0f), 170.0f),
      Camera::look_at(vec4(1e-15f, 0, 0), vec4(0, 1e-15f, -1e-15f), vec4(0, 1, 0), 60.0f),
  };
  const CompiledScene c = CompiledScene::compile(make_default_scene(), BvhConfig{});
  int checked = 0;
  for (const Camera& cam : cameras)
    for (int subpixels : {1, 4})
      for (Isa isa : test::runnable_isas()) {
        RenderSettings st = settings(subpixels, 1);
        st.width = 37;  // blocks of 16 with edges of 5 and 13 pixels
        st.height = 29;
        st.pattern = Pattern::circle;  // offsets off the pixel grid
        const Renderer r(c, View{cam, st});
        const auto offsets = subpixel_offsets(st.subpixels, st.pattern);
        for (const Tile block : {Tile{0, 0, 16, 16}, Tile{16, 16, 32, 29}, Tile{32, 0, 37, 16}})
          for (const auto& [s0, s1] : {std::pair{0, subpixels}, std::pair{subpixels / 2, subpixels}}) {
            const std::size_t n = block.pixels() * std::size_t(s1 - s0);
            std::vector<Ray> rays(n);
            std::vector<std::uint32_t> samples(n);
            primary_rays(isa, r, block, s0, s1, rays.data(), samples.data());
            std::vector<int> seen(n, 0);
            for (std::size_t i = 0; i < n; ++i) {
              const std::uint32_t sample = samples[i];
              ASSERT_LT(sample, n);
              ++seen[sample];
              const int k = s0 + int(sample % std::uint32_t(s1 - s0));
              const int pixel = int(sample / std::uint32_t(s1 - s0));
              const int x = block.x0 + pixel % block.width(), y = block.y0 + pixel / block.width();
              const Ray want = cam.ray(float(x) + offsets[std::size_t(k)].x,
                                       float(y) + offsets[std::size_t(k)].y, st.width, st.height);
              EXPECT_TRUE(same(rays[i].org, want.org) && same(rays[i].dir, want.dir))
                  << isa_name(isa) << " ray " << i << " pixel " << x << "," << y << " sample " << k;
              ++checked;
            }
            for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "sample " << i;
          }
      }
  std::printf("[ measure  ] %d primary rays checked against Camera::ray\n", checked);
}

TEST(RenderCore, TheBatchedKernelComputesWhatADepthFirstTracerComputes) {
  for (const Scene& s : {make_default_scene(), test::glass_scene()}) {
    const RenderSettings st = settings(2, 1);
    const CompiledScene c = CompiledScene::compile(s, BvhConfig{});
    const Image batched = test::render_scene(s, st);
    Image oracle(st.width, st.height);
    const auto offsets = subpixel_offsets(st.subpixels, st.pattern);
    for (int y = 0; y < st.height; ++y)
      for (int x = 0; x < st.width; ++x) {
        vec4 sum;
        for (const SubpixelOffset& o : offsets)
          sum += trace_depth_first(c, st, s.camera.ray(float(x) + o.x, float(y) + o.y, st.width, st.height),
                                   1.0f, 0);
        sum /= float(offsets.size());
        for (int k = 0; k < 3; ++k) oracle.row(y)[3 * x + k] = sum[k];
      }
    // Summation order and FTZ aside, the same arithmetic: RMSE far below the 1e-6 asked.
    const double rmse = compare_images(batched, oracle).rmse;
    std::printf("[ measure  ] batched kernel against the depth-first oracle: RMSE %.3g\n", rmse);
    EXPECT_LT(rmse, 1e-6);
  }
}

}  // namespace
}  // namespace rt2
