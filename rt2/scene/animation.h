// rt2/scene/animation.h — keyframed node animation: translation, rotation, scale and morph
// weight tracks sampled at a time, as glTF 2.0 defines them (§3.11 and Appendix C: STEP, LINEAR with
// spherical interpolation of rotations, CUBICSPLINE Hermite splines).
//
// Invariant: a Track's times are finite and strictly increasing, its values finite, and a
// rotation's keys non-zero (the loader checks them, rt2/io/gltf_scene.cpp). Evaluation is in
// double; before the first key a track holds its first value, after the last its last.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace rt2 {

enum class Interpolation { step, linear, cubic_spline };
enum class NodeProperty { translation, rotation, scale, weights };

// One property of one node over time.
struct Track {
  NodeProperty property = NodeProperty::translation;
  Interpolation interpolation = Interpolation::linear;
  std::vector<double> times;  // seconds
  // Per key, `width` numbers (x y z; a quaternion x y z w; a weight per morph target); a
  // cubic spline's key holds three such groups: in-tangent, value, out-tangent.
  std::vector<double> values;
  int width = 3;
};

// The numbers a key of `property` holds: 3, 4 for a rotation, and for morph weights the
// number of targets, `targets`.
inline int key_width(NodeProperty property, int targets) {
  return property == NodeProperty::rotation ? 4 : property == NodeProperty::weights ? targets : 3;
}

// A node's local transform as translation, rotation (a quaternion x y z w, normalized by
// matrix_of) and scale; its matrix is T * R * S. `weights`: its mesh's morph target weights when they are
// animated (else empty).
struct NodeTrs {
  std::array<double, 3> translation{0.0, 0.0, 0.0};
  std::array<double, 4> rotation{0.0, 0.0, 0.0, 1.0};
  std::array<double, 3> scale{1.0, 1.0, 1.0};
  std::vector<double> weights;
};

// A track's value at `seconds`: `width` numbers in `out`; a rotation is normalized.
void sample(const Track& track, double seconds, double* out);

// The tracks of one animation, each aimed at a node (by its index in the file).
struct Animation {
  std::string name;
  struct Channel {
    int node = -1;
    Track track;
  };
  std::vector<Channel> channels;

  // The last key's time over all channels (0 without keys).
  double duration() const;
  // Sets, in `trs` (indexed by node), every property this animation moves to its value at
  // `seconds`; the others keep theirs.
  void pose(double seconds, std::vector<NodeTrs>& trs) const;
};

// Which of a file's animations a loader poses the scene in, and when.
struct ScenePose {
  std::string animation;  // its name, or its index in decimal; "": the first
  double seconds = 0.0;
};

// An animation as a loaded scene lists it.
struct AnimationSummary {
  std::string name;
  double duration = 0.0;  // seconds
};

// A 4x4 matrix, column-major as glTF stores it: m[column * 4 + row].
using Matrix4d = std::array<double, 16>;
inline constexpr Matrix4d kIdentity4d = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Matrix4d operator*(const Matrix4d& a, const Matrix4d& b);

// T * R * S of `trs`, its rotation normalized first (a zero quaternion gives NaNs; the loader
// refuses it).
Matrix4d matrix_of(const NodeTrs& trs);

}  // namespace rt2
