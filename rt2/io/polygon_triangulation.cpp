// rt2/io/polygon_triangulation.cpp — quads split along a diagonal, larger polygons ear-clipped
// in their plane with a bounding volume hierarchy over the reflex corners (internal; see
// rt2/io/polygon_triangulation.h). The algorithm is described at triangulate() below.
#include "rt2/io/polygon_triangulation.h"

#include <algorithm>
#include <cmath>

namespace rt2::io {
namespace {

struct Normal {
  double v[3] = {0.0, 0.0, 0.0};
};

// Newell's normal of the polygon (twice its area vector), in coordinates relative to the first
// corner so that a polygon far from the origin keeps its precision.
Normal newell_normal(std::span<const vec4> p) {
  Normal n;
  const double ox = p[0][0], oy = p[0][1], oz = p[0][2];
  for (std::size_t i = 0, count = p.size(); i < count; ++i) {
    const vec4& a = p[i];
    const vec4& b = p[i + 1 == count ? 0 : i + 1];
    const double ax = a[0] - ox, ay = a[1] - oy, az = a[2] - oz;
    const double bx = b[0] - ox, by = b[1] - oy, bz = b[2] - oz;
    n.v[0] += (ay - by) * (az + bz);
    n.v[1] += (az - bz) * (ax + bx);
    n.v[2] += (ax - bx) * (ay + by);
  }
  return n;
}

// (b − a) × (c − a) · n, in double.
double oriented(const vec4& a, const vec4& b, const vec4& c, const Normal& n) {
  const double ux = double(b[0]) - a[0], uy = double(b[1]) - a[1], uz = double(b[2]) - a[2];
  const double vx = double(c[0]) - a[0], vy = double(c[1]) - a[1], vz = double(c[2]) - a[2];
  return (uy * vz - uz * vy) * n.v[0] + (uz * vx - ux * vz) * n.v[1] + (ux * vy - uy * vx) * n.v[2];
}

// The fan (first, v, next(v)) over the ring from `first`, for corners ear clipping gave up on.
void fan(std::uint32_t first, const std::vector<std::uint32_t>& next,
         std::vector<CornerTriangle>& out) {
  for (std::uint32_t v = next[first]; next[v] != first; v = next[v])
    out.push_back({first, v, next[v]});
}

}  // namespace

std::size_t PolygonTriangulator::budget(std::size_t corners) {
  std::size_t log2 = 1;
  while ((std::size_t{1} << log2) < corners) ++log2;
  return 32 * corners * log2 + 100000;
}

// Ear clipping (Meisters 1975; testing only reflex corners as in Eberly, "Triangulation by
// Ear Clipping"; corners in Morton order as in mapbox/earcut): the corners form a ring; a convex
// corner b with neighbours a and c is an ear when no other corner that could block it (a reflex or
// flat one: if any corner lies in triangle abc, a reflex one does) lies in the triangle; the ear is
// cut off, and a and c, whose angles shrink, are looked at again. Corners repeated at the two ends
// of a bridge edge sit exactly on a triangle's corner: such a corner blocks the ear only if
// one of its edges enters the triangle. When a whole turn of the ring finds no ear, the
// polygon is not simple (or rounding made it look so): first the corners of zero turn are cut
// off (zero-area triangles; the region does not change), then an ear that only corners
// strictly inside would block, and last the corners left are fanned.
bool PolygonTriangulator::triangulate(std::span<const vec4> corners,
                                      std::vector<CornerTriangle>& out) {
  work_ = 0;
  if (corners.size() < 3) return true;
  if (corners.size() == 3) {
    out.push_back({0, 1, 2});
    return true;
  }
  if (corners.size() == 4) return triangulate_quad(corners, out);
  return ear_clip(corners, out);
}

// Both diagonals of a convex quad are inside it; tinyobjloader takes the shorter (its float
// arithmetic is repeated here exactly, so convex quads triangulate as they always did). In a
// concave quad only the diagonal from the reflex corner is inside: it is taken whatever its
// length. A quad for which neither is (a bow tie, or a degenerate one) keeps the shorter.
bool PolygonTriangulator::triangulate_quad(std::span<const vec4> p,
                                           std::vector<CornerTriangle>& out) {
  const float e02x = p[2][0] - p[0][0], e02y = p[2][1] - p[0][1], e02z = p[2][2] - p[0][2];
  const float e13x = p[3][0] - p[1][0], e13y = p[3][1] - p[1][1], e13z = p[3][2] - p[1][2];
  const float sqr02 = e02x * e02x + e02y * e02y + e02z * e02z;
  const float sqr13 = e13x * e13x + e13y * e13y + e13z * e13z;
  bool use02 = sqr02 < sqr13;
  const Normal n = newell_normal(p);
  const bool inside02 = oriented(p[0], p[1], p[2], n) > 0.0 && oriented(p[0], p[2], p[3], n) > 0.0;
  const bool inside13 = oriented(p[0], p[1], p[3], n) > 0.0 && oriented(p[1], p[2], p[3], n) > 0.0;
  if (inside02 != inside13) use02 = inside02;
  if (use02) {
    out.push_back({0, 1, 2});
    out.push_back({0, 2, 3});
  } else {
    out.push_back({0, 1, 3});
    out.push_back({1, 2, 3});
  }
  return true;
}

// The corners in 2D: dropped the axis along which the Newell normal is largest, the other two
// in the order that makes the polygon counter-clockwise. False if there is no plane (zero or
// non-finite normal: collinear corners, a figure eight, NaN).
bool PolygonTriangulator::project(std::span<const vec4> p) {
  const Normal n = newell_normal(p);
  const double ax = std::fabs(n.v[0]), ay = std::fabs(n.v[1]), az = std::fabs(n.v[2]);
  if (!std::isfinite(ax + ay + az) || ax + ay + az == 0.0) return false;
  const int k = ax >= ay && ax >= az ? 0 : (ay >= az ? 1 : 2);
  int u = (k + 1) % 3, v = (k + 2) % 3;  // (u, v, k) is right-handed
  if (n.v[k] < 0.0) std::swap(u, v);
  const std::size_t count = p.size();
  x_.resize(count);
  y_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    x_[i] = double(p[i][u]) - p[0][u];
    y_[i] = double(p[i][v]) - p[0][v];
    if (!std::isfinite(x_[i]) || !std::isfinite(y_[i])) return false;
  }
  return true;
}

// > 0 where the ring turns left at b (a convex corner), < 0 right (reflex), 0 straight on,
// back (a spike) or at a repeated corner.
double PolygonTriangulator::turn(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  return (x_[b] - x_[a]) * (y_[c] - y_[b]) - (y_[b] - y_[a]) * (x_[c] - x_[b]);
}

// Interleaves the bits of two 16-bit numbers (x in the even bits).
std::uint32_t morton(std::uint32_t x, std::uint32_t y) {
  const auto spread = [](std::uint32_t v) {
    v = (v | (v << 8)) & 0x00FF00FFu;
    v = (v | (v << 4)) & 0x0F0F0F0Fu;
    v = (v | (v << 2)) & 0x33333333u;
    return (v | (v << 1)) & 0x55555555u;
  };
  return spread(x) | (spread(y) << 1);
}

// The reflex (and flat) corners of the ring through `start`, sorted along a Morton curve into
// leaves of kLeaf, with a box per leaf and per pair of nodes above (a bounding volume
// hierarchy). Rebuilt when half of them have turned convex or gone: the corners left are
// fewer and further apart.
void PolygonTriangulator::build_tree(std::uint32_t start) {
  reflex_count_ = 0;
  double x0 = x_[start], y0 = y_[start], x1 = x0, y1 = y0;
  tree_items_.clear();
  std::uint32_t v = start;
  do {
    ++work_;
    reflex_[v] = turn(prev_[v], v, next_[v]) <= 0.0;
    in_tree_[v] = reflex_[v];
    if (reflex_[v]) {
      tree_items_.push_back(v);
      x0 = std::min(x0, x_[v]);
      x1 = std::max(x1, x_[v]);
      y0 = std::min(y0, y_[v]);
      y1 = std::max(y1, y_[v]);
    }
    v = next_[v];
  } while (v != start);
  reflex_count_ = built_reflex_ = tree_items_.size();
  late_reflex_.clear();

  const double sx = x1 > x0 ? 65535.0 / (x1 - x0) : 0.0, sy = y1 > y0 ? 65535.0 / (y1 - y0) : 0.0;
  order_.clear();
  for (const std::uint32_t i : tree_items_) {
    const auto qx = static_cast<std::uint32_t>((x_[i] - x0) * sx);
    const auto qy = static_cast<std::uint32_t>((y_[i] - y0) * sy);
    order_.push_back(std::uint64_t{morton(qx, qy)} << 32 | i);
  }
  std::sort(order_.begin(), order_.end());
  work_ += order_.size();
  for (std::size_t k = 0; k < order_.size(); ++k)
    tree_items_[k] = static_cast<std::uint32_t>(order_[k]);

  boxes_.clear();
  level_start_.assign(1, 0);
  for (std::size_t k = 0; k < tree_items_.size(); k += kLeaf) {
    Box b{INFINITY, INFINITY, -INFINITY, -INFINITY};
    for (std::size_t j = k; j < std::min(k + kLeaf, tree_items_.size()); ++j) {
      const std::uint32_t i = tree_items_[j];
      b = {std::min(b.x0, x_[i]), std::min(b.y0, y_[i]), std::max(b.x1, x_[i]),
           std::max(b.y1, y_[i])};
    }
    boxes_.push_back(b);
  }
  // Levels above: node k of a level covers nodes 2k and 2k + 1 of the one below.
  for (std::size_t below = 0, n = boxes_.size(); n > 1; n = (n + 1) / 2) {
    level_start_.push_back(boxes_.size());
    for (std::size_t k = 0; k < n; k += 2) {
      Box b = boxes_[below + k];
      if (k + 1 < n) {
        const Box& o = boxes_[below + k + 1];
        b = {std::min(b.x0, o.x0), std::min(b.y0, o.y0), std::max(b.x1, o.x1),
             std::max(b.y1, o.y1)};
      }
      boxes_.push_back(b);
    }
    below = level_start_.back();
  }
  level_start_.push_back(boxes_.size());
}

// Whether `box` may hold a point that triangle a b c (counter-clockwise) contains, closed:
// their boxes overlap, and for each edge the box corner furthest to its left is not right of
// it. The edge test has the form of turn(), and rounding is monotone, so a point in the box
// cannot come out left of an edge its box corner is right of.
bool PolygonTriangulator::may_hold(const Box& box, std::uint32_t a, std::uint32_t b,
                                   std::uint32_t c) const {
  if (box.x1 < std::min({x_[a], x_[b], x_[c]}) || box.x0 > std::max({x_[a], x_[b], x_[c]}) ||
      box.y1 < std::min({y_[a], y_[b], y_[c]}) || box.y0 > std::max({y_[a], y_[b], y_[c]}))
    return false;
  const std::uint32_t tri[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t p = tri[k], q = tri[(k + 1) % 3];
    const double dx = x_[q] - x_[p], dy = y_[q] - y_[p];
    const double x = dy >= 0.0 ? box.x0 : box.x1, y = dx >= 0.0 ? box.y1 : box.y0;
    if (dx * (y - y_[q]) - dy * (x - x_[q]) < 0.0) return false;
  }
  return true;
}

// After a neighbour was cut off, corner v's angle changed.
void PolygonTriangulator::update(std::uint32_t v) {
  const bool reflex = turn(prev_[v], v, next_[v]) <= 0.0;
  if (reflex == bool(reflex_[v])) return;
  reflex_[v] = reflex;
  if (!reflex) {
    --reflex_count_;
    return;
  }
  // A cut only shrinks the angles beside it; a zero-area cut can turn a corner reflex.
  ++reflex_count_;
  if (!in_tree_[v]) {
    in_tree_[v] = 1;
    late_reflex_.push_back(v);
  }
}

// Whether corner p keeps b from being an ear (triangle a b c, counter-clockwise). Strict: p in
// the closed triangle blocks, except at a corner of it, where it blocks only if an edge of p
// enters the triangle. Relaxed: only a p strictly inside blocks.
bool PolygonTriangulator::blocks(std::uint32_t p, std::uint32_t a, std::uint32_t b, std::uint32_t c,
                                 bool strict) const {
  if (!alive_[p] || !reflex_[p] || p == a || p == b || p == c) return false;
  const double da = turn(a, b, p), db = turn(b, c, p), dc = turn(c, a, p);
  if (!strict) return da > 0.0 && db > 0.0 && dc > 0.0;
  if (da < 0.0 || db < 0.0 || dc < 0.0) return false;
  const std::uint32_t tri[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t at = tri[k];
    if (x_[p] != x_[at] || y_[p] != y_[at]) continue;
    // The triangle's angle at `at` runs from the next corner to the previous one.
    const std::uint32_t from = tri[(k + 1) % 3], to = tri[(k + 2) % 3];
    const double fx = x_[from] - x_[at], fy = y_[from] - y_[at];
    const double tx = x_[to] - x_[at], ty = y_[to] - y_[at];
    for (const std::uint32_t q : {prev_[p], next_[p]}) {
      const double dx = x_[q] - x_[at], dy = y_[q] - y_[at];
      if (fx * dy - fy * dx > 0.0 && dx * ty - dy * tx > 0.0) return true;
    }
    return false;
  }
  return true;
}

// Whether b is an ear: convex, and no reflex corner blocks it (those of late_reflex_, then
// those of the tree's leaves whose boxes may hold a point of the triangle).
bool PolygonTriangulator::is_ear(std::uint32_t b, bool strict) {
  const std::uint32_t a = prev_[b], c = next_[b];
  if (!(turn(a, b, c) > 0.0)) return false;
  if (reflex_count_ == 0) return true;
  for (const std::uint32_t p : late_reflex_) {
    ++work_;
    if (blocks(p, a, b, c, strict)) return false;
  }
  if (boxes_.empty()) return true;
  const std::size_t top = level_start_.size() - 2;
  stack_.assign(1, {top, 0});
  while (!stack_.empty()) {
    const auto [level, k] = stack_.back();
    stack_.pop_back();
    ++work_;
    if (!may_hold(boxes_[level_start_[level] + k], a, b, c)) continue;
    if (level > 0) {
      stack_.push_back({level - 1, 2 * k});
      if (level_start_[level - 1] + 2 * k + 1 < level_start_[level])
        stack_.push_back({level - 1, 2 * k + 1});
      continue;
    }
    for (std::size_t j = k * kLeaf; j < std::min((k + 1) * kLeaf, tree_items_.size()); ++j) {
      ++work_;
      if (blocks(tree_items_[j], a, b, c, strict)) return false;
    }
  }
  return true;
}

void PolygonTriangulator::clip(std::uint32_t b, std::vector<CornerTriangle>& out) {
  const std::uint32_t a = prev_[b], c = next_[b];
  out.push_back({a, b, c});
  next_[a] = c;
  prev_[c] = a;
  alive_[b] = 0;
  if (reflex_[b]) --reflex_count_;
  --left_;
  update(a);
  update(c);
}

// Cuts off every corner of zero turn (repeated, or on a straight line or a spike between its
// neighbours) in one turn of the ring: zero-area triangles, the region unchanged.
bool PolygonTriangulator::clip_zero_area(std::uint32_t& start, std::vector<CornerTriangle>& out) {
  bool clipped = false;
  std::uint32_t v = start;
  for (std::size_t steps = left_; steps > 0 && left_ > 3; --steps) {
    ++work_;
    const std::uint32_t after = next_[v];
    if (turn(prev_[v], v, after) == 0.0) {
      clip(v, out);
      clipped = true;
    }
    v = after;
  }
  start = v;
  return clipped;
}

// Cuts off one ear that only corners strictly inside it would block.
bool PolygonTriangulator::clip_relaxed_ear(std::uint32_t& start, std::vector<CornerTriangle>& out) {
  std::uint32_t v = start;
  for (std::size_t steps = left_; steps > 0 && work_ <= budget_; --steps, v = next_[v]) {
    ++work_;
    if (is_ear(v, false)) {
      start = next_[v];
      clip(v, out);
      return true;
    }
  }
  return false;
}

bool PolygonTriangulator::ear_clip(std::span<const vec4> corners,
                                   std::vector<CornerTriangle>& out) {
  const auto count = static_cast<std::uint32_t>(corners.size());
  prev_.resize(count);
  next_.resize(count);
  for (std::uint32_t i = 0; i < count; ++i) {
    prev_[i] = i == 0 ? count - 1 : i - 1;
    next_[i] = i + 1 == count ? 0 : i + 1;
  }
  if (!project(corners)) {
    fan(0, next_, out);
    return false;
  }
  alive_.assign(count, 1);
  reflex_.assign(count, 0);
  in_tree_.assign(count, 0);
  left_ = count;
  build_tree(0);
  // A simple polygon needs 3 to 10 n log2 n units (tested); this leaves a margin and still
  // bounds the time a self-intersecting one takes to a few times that of a simple one.
  budget_ = budget(count);

  // The search walks the ring from `ear`; after a cut it goes on two corners further (fewer
  // slivers than at the next one, as earcut does). After kMisses corners in a row that are
  // no ears it first tries those beside recent cuts (`pending_`, newest first), whose
  // angles shrank: where ears are few (a spiral, a comb, a thin ring zipped up from its
  // bridge) the next one is usually there, and walking the ring for each would cost a turn
  // per ear. (Trying them at once would cost more on polygons with many ears, a circle.)
  constexpr std::size_t kMisses = 16;
  std::uint32_t ear = 0, stop = 0;
  std::size_t misses = 0;
  bool complete = true;
  pending_.clear();
  const auto cut = [&](std::uint32_t v) {
    pending_.push_back(prev_[v]);
    pending_.push_back(next_[v]);
    clip(v, out);
  };
  while (left_ > 3) {
    if (work_ > budget_) {
      complete = false;
      break;
    }
    // Half the reflex corners gone (or many new ones): the tree is rebuilt for those left.
    if ((built_reflex_ >= 64 && 2 * reflex_count_ < built_reflex_) ||
        late_reflex_.size() > 64 + built_reflex_ / 8)
      build_tree(ear);
    ++work_;
    if (is_ear(ear, true)) {
      const std::uint32_t c = next_[ear];
      cut(ear);
      misses = 0;
      ear = stop = next_[c];
      continue;
    }
    bool done = false;
    if (++misses > kMisses) {
      while (!pending_.empty() && !done) {
        const std::uint32_t v = pending_.back();
        pending_.pop_back();
        ++work_;
        if (alive_[v] && is_ear(v, true)) {
          cut(v);  // not `ear`: nothing changed since it was found to be no ear
          misses = 0;
          done = true;
        }
      }
    }
    if (done) {
      stop = ear;
      continue;
    }
    ear = next_[ear];
    if (ear != stop) continue;
    // A whole turn without an ear.
    if (clip_zero_area(ear, out) || clip_relaxed_ear(ear, out)) {
      stop = ear;
      continue;
    }
    complete = false;
    break;
  }
  if (left_ == 3) {
    out.push_back({prev_[ear], ear, next_[ear]});
    return complete;
  }
  fan(ear, next_, out);
  return false;
}

}  // namespace rt2::io
