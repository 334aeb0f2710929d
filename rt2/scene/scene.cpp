// rt2/scene/scene.cpp — scene bookkeeping, validation, features and extra lights.
#include "rt2/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rt2/base/error.h"

namespace rt2 {

std::uint32_t Scene::add_material(const std::string& name, const Material& m) {
  materials.push_back(m);
  material_names.push_back(name);
  return static_cast<std::uint32_t>(materials.size() - 1);
}

int Scene::find_material(const std::string& name) const {
  for (std::size_t i = 0; i < material_names.size(); ++i)
    if (material_names[i] == name) return static_cast<int>(i);
  return -1;
}

std::size_t Scene::triangle_count() const {
  std::size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangle_count();
  for (const Mesh& m : instanced_meshes) n += m.triangle_count();
  return n;
}

std::size_t Scene::placed_triangle_count() const {
  std::size_t n = 0;
  for (const Mesh& m : meshes) n += m.triangle_count();
  for (const Instance& in : instances)
    if (in.mesh < instanced_meshes.size()) n += instanced_meshes[in.mesh].triangle_count();
  return n;
}

namespace {

bool same_faces(const std::vector<Mesh>& a, const std::vector<Mesh>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].faces != b[i].faces || a[i].face_materials != b[i].face_materials ||
        a[i].normals.empty() != b[i].normals.empty() ||
        a[i].texcoords.empty() != b[i].texcoords.empty())
      return false;
  return true;
}

}  // namespace

bool same_topology(const Scene& a, const Scene& b) {
  return same_faces(a.meshes, b.meshes) && same_faces(a.instanced_meshes, b.instanced_meshes);
}

Aabb Scene::bounds() const {
  Aabb b;
  for (const Sphere& s : spheres) {
    b.grow(s.center - vec4(s.radius, s.radius, s.radius));
    b.grow(s.center + vec4(s.radius, s.radius, s.radius));
  }
  for (const Mesh& m : meshes) b.grow(m.bounds());
  if (!instances.empty()) {
    std::vector<Aabb> object;
    for (const Mesh& m : instanced_meshes) object.push_back(m.bounds());
    for (const Instance& in : instances)
      if (in.mesh < object.size() && !object[in.mesh].is_empty())
        b.grow(world_box(object[in.mesh], in.to_world));
  }
  return b;
}

float Scene::size() const {
  const Aabb b = bounds();
  if (b.is_empty()) return 1.0f;
  const vec4 e = b.extent();
  const float s = std::max(std::max(e[0], e[1]), e[2]);
  return s > 0.0f && std::isfinite(s) ? s : 1.0f;
}

unsigned Scene::features(std::size_t light_count) const {
  unsigned f = 0;
  std::vector<bool> used(materials.size(), false);
  auto use = [&](std::uint32_t m) {
    if (m < used.size()) used[m] = true;
  };
  if (!spheres.empty()) f |= kSpheres;
  if (!planes.empty()) f |= kPlanes;
  for (auto m : sphere_materials) use(m);
  for (auto m : plane_materials) use(m);
  for (const Mesh& mesh : meshes) {
    if (!mesh.faces.empty()) f |= kTriangles;
    for (auto m : mesh.face_materials) use(m);
  }
  for (const Instance& in : instances) {
    if (in.mesh >= instanced_meshes.size()) continue;
    const Mesh& mesh = instanced_meshes[in.mesh];
    if (!mesh.faces.empty()) f |= kTriangles;
    if (in.material != kMeshMaterials)
      use(in.material);
    else
      for (auto m : mesh.face_materials) use(m);
  }
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (!used[i]) continue;
    const Material& m = materials[i];
    if (m.reflectivity > 0.0f) f |= kReflection;
    if (m.transparency > 0.0f) f |= kRefraction;
    if (m.has_specular() && light_count > 0) f |= kSpecular;
  }
  return f;
}

namespace {

bool finite(const vec4& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) &&
         std::isfinite(v[3]);
}

void check(bool ok, const std::string& what) {
  if (!ok) throw Error(what);
}

}  // namespace

void Scene::validate() const {
  check(finite(ambient) && finite(background), "scene: ambient/background must be finite");
  check(finite(camera.position()) && finite(camera.forward()), "camera: non-finite position or direction");
  check(material_names.size() == materials.size(), "scene: one name per material");
  check(sphere_materials.size() == spheres.size(), "scene: one material per sphere");
  check(plane_materials.size() == planes.size(), "scene: one material per plane");
  for (std::size_t i = 0; i < materials.size(); ++i) {
    const Material& m = materials[i];
    const std::string at = "material '" + material_names[i] + "': ";
    check(finite(m.ambient) && finite(m.diffuse) && finite(m.specular) && finite(m.diffuse2),
          at + "colours must be finite");
    check(std::isfinite(m.shininess) && m.shininess >= 0.0f, at + "shininess must be >= 0");
    check(m.reflectivity >= 0.0f && m.reflectivity <= 1.0f, at + "reflectivity must be in [0, 1]");
    check(m.transparency >= 0.0f && m.transparency <= 1.0f, at + "transparency must be in [0, 1]");
    check(std::isfinite(m.ior) && m.ior > 0.0f, at + "ior must be > 0");
    check(std::isfinite(m.checker_scale) && m.checker_scale >= 0.0f,
          at + "checker_scale must be >= 0");
    check(finite(m.base_color) && finite(m.emissive), at + "base_color and emissive must be finite");
    check(m.metallic >= 0.0f && m.metallic <= 1.0f, at + "metallic must be in [0, 1]");
    check(m.roughness >= 0.0f && m.roughness <= 1.0f, at + "roughness must be in [0, 1]");
    check(m.transmission >= 0.0f && m.transmission <= 1.0f, at + "transmission must be in [0, 1]");
    check(std::isfinite(m.normal_scale), at + "normal_scale must be finite");
    for (const std::uint32_t t : {m.base_color_texture, m.metallic_roughness_texture,
                                  m.normal_texture, m.emissive_texture, m.roughness_texture,
                                  m.metallic_texture})
      check(t == kNoTexture || t < textures.size(), at + "texture index out of range");
  }
  if (environment) {
    check(std::isfinite(environment->intensity) && environment->intensity >= 0.0f,
          "environment: intensity must be finite and >= 0");
    check(std::isfinite(environment->rotation_degrees), "environment: rotation must be finite");
    check(finite(environment->sun_direction) &&
              float(dot(environment->sun_direction, environment->sun_direction)) > 0.0f,
          "environment: sun direction must be finite and non-zero");
  }
  for (std::size_t i = 0; i < lights.size(); ++i) {
    check(finite(lights[i].position) && finite(lights[i].color) &&
              std::isfinite(lights[i].intensity) && lights[i].intensity >= 0.0f,
          "light " + std::to_string(i) + ": position, color and intensity must be finite (intensity >= 0)");
    check(lights[i].range > 0.0f, "light " + std::to_string(i) + ": range must be > 0");
  }
  const auto n_mat = materials.size();
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const std::string at = "sphere " + std::to_string(i) + ": ";
    check(finite(spheres[i].center), at + "center must be finite");
    check(std::isfinite(spheres[i].radius) && spheres[i].radius > 0.0f, at + "radius must be > 0");
    check(sphere_materials[i] < n_mat, at + "material index out of range");
  }
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const std::string at = "plane " + std::to_string(i) + ": ";
    check(finite(planes[i].n) && std::isfinite(planes[i].d), at + "normal and offset must be finite");
    check(std::fabs(float(dot(planes[i].n, planes[i].n)) - 1.0f) < 1e-3f, at + "normal must be unit length");
    check(plane_materials[i] < n_mat, at + "material index out of range");
  }
  // Messages are made only for a failed check: a scene may have millions of elements.
  const auto check_mesh = [&](const Mesh& m) {
    const auto fail_unless = [&](bool ok, const char* what) {
      if (!ok) throw Error("mesh '" + m.name + "': " + what);
    };
    const auto all = [](const auto& items, auto&& ok) {
      return std::all_of(items.begin(), items.end(), ok);
    };
    fail_unless(m.face_materials.size() == m.faces.size(), "one material per face");
    fail_unless(m.normals.empty() || m.normals.size() == m.positions.size(),
                "normals must match positions");
    fail_unless(m.texcoords.empty() || m.texcoords.size() == m.positions.size(),
                "texture coordinates must match positions");
    fail_unless(all(m.texcoords, [](const auto& uv) { return std::isfinite(uv[0]) && std::isfinite(uv[1]); }),
                "non-finite texture coordinate");
    fail_unless(all(m.positions, [](const vec4& p) { return finite(p); }), "non-finite vertex");
    fail_unless(all(m.normals,
                    [](const vec4& n) { return finite(n) && std::fabs(float(dot(n, n)) - 1.0f) < 1e-3f; }),
                "vertex normals must be finite and unit length");
    const std::size_t n_pos = m.positions.size();
    fail_unless(all(m.faces, [&](const auto& f) { return f[0] < n_pos && f[1] < n_pos && f[2] < n_pos; }),
                "face index out of range");
    fail_unless(all(m.face_materials, [&](auto mi) { return mi < n_mat; }),
                "material index out of range");
  };
  for (const Mesh& m : meshes) check_mesh(m);
  for (const Mesh& m : instanced_meshes) {
    check_mesh(m);
    check(!m.faces.empty(), "mesh '" + m.name + "': an instanced mesh needs triangles");
  }
  std::vector<AreaRange> areas;
  if (!instances.empty())
    for (const Mesh& m : instanced_meshes) areas.push_back(area_range(m));
  for (std::size_t i = 0; i < instances.size(); ++i) {
    const Instance& in = instances[i];
    const auto fail_unless = [&](bool ok, const char* what) {
      if (!ok) throw Error("instance " + std::to_string(i) + ": " + what);
    };
    fail_unless(in.mesh < instanced_meshes.size(), "mesh index out of range");
    fail_unless(in.material == kMeshMaterials || in.material < n_mat, "material index out of range");
    fail_unless(in.to_world.finite(), "the transform must be finite");
    fail_unless(std::isnormal(in.to_world.determinant()) && in.to_world.inverse().finite(),
                "the transform must be invertible");
    fail_unless(areas_fit_float(areas[in.mesh], in.to_world),
                "the transform makes its triangles too large or too small for float arithmetic");
  }
}

void recenter_on_camera(Scene& scene) {
  const vec4 c = scene.camera.position();
  scene.origin += c;
  scene.camera.translate(-c);
  for (Light& l : scene.lights) l.position -= c;
  if (scene.light_field) {
    scene.light_field->box.lo -= c;
    scene.light_field->box.hi -= c;
  }
  for (Sphere& s : scene.spheres) s.center -= c;
  for (Plane& p : scene.planes) p.d += float(dot(p.n, c));
  for (Mesh& m : scene.meshes)
    for (vec4& v : m.positions) v -= c;
  for (Instance& in : scene.instances)
    for (int a = 0; a < 3; ++a) in.to_world.m[std::size_t(a)][3] -= double(c[a]);
}

// Extra lights sit on a ring of radius 1.5 R around the scene's centre, at height
// centre.y + R, where R is the bounding-sphere radius (1 for an empty scene). Light k of
// the extra ones is at angle 2 pi k / extra + 0.3 (so the first is not on an axis), white,
// with the intensity of the scene's first light (1 if it has none). With a scene's light
// field, the extra lights are the field's next ones instead.
void set_light_count(Scene& scene, std::size_t total, std::optional<RangeInterval> range) {
  if (scene.light_field && range) {  // the field's lights take the given ranges too
    scene.light_field->range_lo = range->lo;
    scene.light_field->range_hi = range->hi;
    const LightField& field = *scene.light_field;
    for (std::size_t i = field.first; i < scene.lights.size(); ++i)
      scene.lights[i].range = field.light(i - field.first).range;
  }
  if (total <= scene.lights.size()) {
    scene.lights.resize(total);
    return;
  }
  if (scene.light_field && scene.light_field->first <= scene.lights.size()) {
    const LightField& field = *scene.light_field;
    for (std::size_t k = scene.lights.size() - field.first; scene.lights.size() < total; ++k)
      scene.lights.push_back(field.light(k));
    return;
  }
  const Aabb b = scene.bounds();
  vec4 c(0.0f, 0.0f, 0.0f);
  float r = 1.0f;
  if (!b.is_empty()) {
    c = b.center();
    const vec4 e = b.extent() * 0.5f;
    r = std::max(1e-3f, std::sqrt(float(dot(e, e))));
  }
  const float intensity = scene.lights.empty() ? 1.0f : scene.lights.front().intensity;
  const std::size_t extra = total - scene.lights.size();
  for (std::size_t k = 0; k < extra; ++k) {
    const float a = 2.0f * std::numbers::pi_v<float> * float(k) / float(extra) + 0.3f;
    Light l;
    l.position = c + vec4(1.5f * r * std::cos(a), r, 1.5f * r * std::sin(a));
    l.intensity = intensity;
    if (range) {  // spread over the interval by the golden ratio
      const float f = float(std::fmod(double(k) * 0.6180339887498949, 1.0));
      l.range = range->lo + f * (range->hi - range->lo);
    }
    scene.lights.push_back(l);
  }
}

std::string feature_names(unsigned f) {
  static const char* names[] = {"reflection", "refraction", "specular",
                                "spheres",    "planes",     "triangles"};
  std::string s;
  for (int i = 0; i < 6; ++i) {
    if (!(f & (1u << i))) continue;
    if (!s.empty()) s += '+';
    s += names[i];
  }
  return s.empty() ? "none" : s;
}

}  // namespace rt2
